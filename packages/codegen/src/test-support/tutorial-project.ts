import { cpSync, readdirSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

/** The repository's tutorial project (examples/tutorial: .contract files and the committed src-gen). */
export const TUTORIAL = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..', '..', 'examples', 'tutorial');

/** A copy of the tutorial project in `dir` (sources and committed src-gen with user code; no executables, runs or logs). */
export function copyTutorial(dir: string): void {
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) cpSync(join(TUTORIAL, f), join(dir, f));
    cpSync(join(TUTORIAL, 'src-gen'), join(dir, 'src-gen'), { recursive: true, filter: (src) => !/\/(run|logs)(\/|$)|_mod\/[A-Z]{3}$|tools\/control[A-Z]{3}$/.test(src) });
}
