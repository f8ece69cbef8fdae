import { writeFileSync } from 'node:fs';
import { join } from 'node:path';

/** The modules of the chain the browser tests draw: a periodic loop of 8 modules, the diagram's longest. */
export const CHAIN_MODULES = ['CHA', 'CHB', 'CHC', 'CHD', 'CHE', 'CHF', 'CHG', 'CHH'];

/**
 * Writes into `workspace` a periodic schema `chain` (chain.contract) of the synchronous modules
 * `names`, each in a file of its own, each flowing into the next: a schema the docked diagram
 * folds into columns (its straight drawing does not fit the pane at a readable size).
 */
export function writeChainSchema(workspace: string, names: string[] = CHAIN_MODULES): void {
  for (const n of names) writeFileSync(join(workspace, `${n.toLowerCase()}.contract`), `synchronous module ${n} {\n    scheduling { C=300us; }\n    data flows { in :0 float u; out :1 float y; }\n}\n`);
  const pairs = names.slice(1).map((n, i) => [names[i]!, n]);
  writeFileSync(join(workspace, 'chain.contract'), [
    ...names.map((n) => `import "${n.toLowerCase()}.contract";`), '',
    'periodic schema chain() {',
    '    realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }',
    `    modules { ${names.map((n) => `${n} ();`).join(' ')} }`,
    `    scheduling graph { ${pairs.map(([a, b]) => `${a} -> ${b};`).join(' ')} }`,
    `    communications { ${pairs.map(([a, b]) => `${a}:1 -> ${b}:0 * 1;`).join(' ')} }`,
    '}', '',
  ].join('\n'));
}
