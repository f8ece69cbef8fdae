/**
 * The `.scenario` parser and model checks live in the language package
 * (`@contract-studio/language/scenario`), so the language server checks scenarios in the editor
 * with the same code as `contract simulate` (docs/simulation.md "Editing scenarios").
 */
export * from '@contract-studio/language/scenario';
