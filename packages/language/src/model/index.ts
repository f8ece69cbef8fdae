export * from './time.js';
export * from './blocks.js';
export * from './ports.js';
export * from './types.js';
export * from './values.js';
export * from './schema-conflicts.js';
export * from './constants.js';
export * from './strings.js';
