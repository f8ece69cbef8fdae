/**
 * @contract-studio/simulator — the supervisor simulator (docs/simulation.md): `.scenario` files
 * (parser: also alone and browser-safe as `@contract-studio/simulator/scenario`; checks against the
 * model), the native harness on the real engine cores (built per project from the generated
 * tables), the runner and its reports (text, JSON, JUnit) behind `contract simulate`.
 */
export * from './scenario/index.js';
export * from './harness/tables.js';
export * from './harness/cache.js';
export * from './harness/build.js';
export * from './harness/compile-diagnostics.js';
export * from './harness/confine.js';
export * from './runner/protocol.js';
export * from './runner/run-scenario.js';
export * from './simulate-project.js';
export * from './runner/report.js';
export * from './runner/output-lines.js';
