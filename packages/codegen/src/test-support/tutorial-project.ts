import { cpSync, readdirSync } from 'node:fs';
import { join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { REGION_COPY_NAME } from '@contract-studio/conventions';

/** The repository's examples (each a project: .contract files and the committed src-gen). */
export const EXAMPLES = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..', '..', 'examples');

/** The repository's tutorial project (examples/tutorial: .contract files and the committed src-gen). */
export const TUTORIAL = join(EXAMPLES, 'tutorial');

/** What a build or a run leaves in a src-gen (executables, runs, logs), by '/'-path from the src-gen folder. */
const BUILD_OUTPUT = /(^|\/)(run|logs)(\/|$)|_mod\/[A-Z]{3}$|tools\/control[A-Z]{3}$/;

/**
 * Whether a file of an example's src-gen (its '/'-path from the src-gen folder) is in a fresh
 * clone: not what a build or a run leaves there, nor the last generation's copy of the regions'
 * code, which the example's `.gitignore` lists (docs/getting-started.md §7) — a generate or a
 * build in a checkout writes one, a clone has none.
 */
export function inAClone(srcGenPath: string): boolean {
    return srcGenPath !== REGION_COPY_NAME && !BUILD_OUTPUT.test(srcGenPath);
}

/** A copy of example `example` in `dir` as a fresh clone has it: its sources, and with `withSrcGen` its committed src-gen with the user code. */
export function copyExample(example: string, dir: string, withSrcGen = true): void {
    const from = join(EXAMPLES, example);
    for (const f of readdirSync(from)) if (f.endsWith('.contract')) cpSync(join(from, f), join(dir, f));
    const srcGen = join(from, 'src-gen');
    if (withSrcGen) cpSync(srcGen, join(dir, 'src-gen'), { recursive: true, filter: (src) => inAClone(relative(srcGen, src).split(sep).join('/')) });
}

/** A copy of the tutorial project in `dir` as a fresh clone has it (sources and committed src-gen with user code; no executables, runs, logs or copy of the regions' code). */
export function copyTutorial(dir: string): void {
    copyExample('tutorial', dir);
}
