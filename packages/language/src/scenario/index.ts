/**
 * `@contract-studio/language/scenario`: the `.scenario` format of the simulator (docs/simulation.md
 * "Scenario files") — the parser and the checks against the project's model. Browser-safe: the
 * simulator (`contract simulate`) and the editors (the language server's scenario support,
 * `src/lsp/scenario/`) use this one implementation.
 */
export * from './parse.js';
export * from './model-check.js';
