/**
 * `contract generate` and `contract rename` hold the generated tree's write lock (codegen
 * tree-lock.ts) for their whole work: taken before the model is read, so that a rename running in
 * another terminal or in the IDE (its .contract files and its tree change together) is seen whole
 * or not at all. A wait says for whom, as a build waiting for another command does. A rename that
 * was killed half-way left its journal in the tree (codegen rename-journal.ts): it is finished
 * here, lock held, before the model is read, and said (what it could not do as warnings); the
 * caller gets what was finished (generate lists, once it has generated, the regions that still
 * mention the old name).
 */
import { lstatSync } from 'node:fs';
import { join } from 'node:path';
import type { FinishedRename } from '@contract-studio/codegen';
import type { CliIO } from './command.js';
import { finishedRenameText } from './finished-rename-text.js';
import { safeName } from './terminal-text.js';

/**
 * Holds the lock of output folder `out` (when it is a real folder: else the generator's refusal
 * applies); the release. `project`: the project folder (`dir`) and its name as the user wrote it
 * (`label`); a journal in `out` is finished for it (one of `-o OUT` only when it journals that
 * very project: finishInterruptedRename checks it).
 */
export async function holdTreeLock(out: string, shownAs: string, io: CliIO, project?: { dir: string; label: string }): Promise<HeldTree> {
    if (!lstatSync(out, { throwIfNoEntry: false })?.isDirectory()) return { release: () => {} };
    const { lockTree, finishInterruptedRename, describeFinishedRename, TREE_WRITERS } = await import('@contract-studio/codegen');
    const release = await lockTree(out, shownAs, undefined, (holder) => {
        io.err(`waiting for the other writer of ${safeName(shownAs)}${holder !== undefined ? ` (pid ${holder}: ${TREE_WRITERS})` : ''} to finish ...\n`);
    });
    if (project === undefined) return { release };
    try {
        const done = await finishInterruptedRename(project.dir, out);
        if (done) io.err(finishedRenameText(describeFinishedRename(done, (f) => safeName(join(project.label, f)), (f) => safeName(`${shownAs.replace(/\/+$/, '')}/${f}`))));
        return done ? { release, finished: done } : { release };
    } catch (e) {
        // said, and left: the generation then refuses the tree, naming the journal
        io.err(`warning: ${safeName((e as Error).message)}\n`);
        return { release };
    }
}

/** The tree's lock held: its release, and the rename killed half-way that was finished, if any. */
export interface HeldTree {
    release: () => void;
    finished?: FinishedRename;
}
