/** @contract-studio/cli — the `contract` command as a library (for tests and other tools). */
export * from './command.js';
export * from './cli.js';
export * from './args.js';
export * from './diagnostic-format.js';
export { COMMANDS } from './commands/index.js';
