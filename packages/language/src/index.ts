/**
 * @contract-studio/language — the Cactal language: Langium services, generated AST types and
 * model helpers (ports by index, block accessors, types, values, time literals) shared with
 * code generation. Node-only helpers (loadWorkspace) are in '@contract-studio/language/node'.
 */
export * from './cactal-module.js';
export * from './generated/ast.js';
export { CactalGrammar } from './generated/grammar.js';
export { CactalLanguageMetaData } from './generated/module.js';
export * from './model/index.js';
export * from './validation/codes/index.js';
export { report } from './validation/report.js';
export { checkValue, type ValueCheckOptions } from './validation/value-checker.js';
export * from './validation/timing-analysis.js';
export { CHECK_FACTORIES, type CheckFactory } from './validation/cactal-validator.js';
export { ImportResolver } from './scoping/import-resolver.js';
export { CactalProjects, type FolderTreeProbe } from './scoping/projects.js';
export { CactalScopeProvider } from './scoping/cactal-scope-provider.js';
export { PROJECT_TEMPLATES } from './templates/project-templates.js';
export { addScenarioSupport, ScenarioSupport } from './lsp/scenario/scenario-server.js';
export { SCENARIO_LANGUAGE_ID, SCENARIO_EXTENSION, isScenarioUri } from './lsp/scenario/scenario-project.js';
