/** @contract-studio/language/node — Node-only entry: loading a workspace from disk. */
export * from './load-workspace.js';
export { NodeFileSystem } from 'langium/node';
export { planRename, findEntity, RenameError, type RenamePlan, type PlannedFileEdit } from './rename-entity.js';
export { projectScenarios, renameInScenarios, type ScenarioRename, type ScenarioEdit, type ScenarioFileChange } from './rename-scenarios.js';
