/**
 * @contract-studio/conventions — what the packages agree on (browser-safe, no dependencies): the
 * generated tree's layout, the sandbox conventions, the protected-region markers with their
 * one parser, the writing of a time literal and of untrusted text as it reads (visibleText) (docs/architecture.md "Shared conventions").
 */
export * from './layout.js';
export * from './project-root.js';
export * from './sandbox.js';
export * from './regions.js';
export * from './conflict-markers.js';
export * from './time-literal.js';
export * from './visible-text.js';
export * from './json-body.js';
export * from './run-bounds.js';
export * from './limit-option.js';
export * from './stuck-advice.js';
export * from './crash-signals.js';
export * from './histogram-quantile.js';
export * from './runtime-parts.js';
export * from './stdin-entry.js';
