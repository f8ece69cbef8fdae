/**
 * `contract generate` and `contract rename` hold the generated tree's write lock (codegen
 * tree-lock.ts) for their whole work: taken before the model is read, so that a rename running in
 * another terminal or in the IDE (its .contract files and its tree change together) is seen whole
 * or not at all. A wait says for whom, as a build waiting for another command does.
 */
import { lstatSync } from 'node:fs';
import type { CliIO } from './command.js';
import { safeName } from './terminal-text.js';

/** Holds the lock of output folder `out` (when it is a real folder: else the generator's refusal applies); the release. */
export async function holdTreeLock(out: string, shownAs: string, io: CliIO): Promise<() => void> {
    if (!lstatSync(out, { throwIfNoEntry: false })?.isDirectory()) return () => {};
    const { lockTree } = await import('@contract-studio/codegen');
    return lockTree(out, shownAs, undefined, (holder) => {
        io.err(`waiting for the other writer of ${safeName(shownAs)}${holder !== undefined ? ` (pid ${holder}: a contract generate or rename, or the IDE server)` : ''} to finish ...\n`);
    });
}
