export { writeTree, type GeneratedFile, type WriteTreeOptions } from './write-tree.js';
export { emptyReport, formatProblem, type GenerationReport, type GenerationProblem } from './report.js';
export { ORPHANS_DIR } from './orphans.js';
export { MANIFEST_NAME } from './manifest.js';
