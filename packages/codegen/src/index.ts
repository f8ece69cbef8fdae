export * from './regions/index.js';
export * from './writer/index.js';
