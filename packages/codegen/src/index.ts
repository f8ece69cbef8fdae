/**
 * @contract-studio/codegen — Cactal model -> C source tree (docs/codegen.md, report §5), with protected
 * regions merged on every regeneration. Entry points: generateArchitecture (Seam 4) and the parts
 * it is made of (plain architecture model, generators, region merge, tree writer).
 */
export { architectureOf, generateArchitecture, generateFromArchitecture, type ModelSource } from './generate-architecture.js';
export { architectureFromModels } from './model/from-langium.js';
export type * from './model/architecture.js';
export { computePriorities, PRIORITY, type Priorities } from './model/priorities.js';
export { generateFiles } from './generators/generate-files.js';
export { architectureExecutables, makefileExecutables, stdinModulesProblem } from './generators/run-executables.js';
export { DEFAULT_RUNTIME } from './generators/build-settings.js';
export * from './regions/index.js';
export * from './writer/index.js';
