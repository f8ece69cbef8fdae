/**
 * The steps of a rename, in the one order `contract rename`, the IDE's rename and the finishing of
 * an interrupted one share (docs/codegen.md, "A rename killed half-way"):
 * 1. the journal written in the generated tree (rename-journal.ts), when the rename has one;
 * 2. the tree carried over (carryRenameIntoTree): paths and region IDs of an entity that names
 *    generated files, then the C identifiers of the user code;
 * 3. the project's `.contract` and `.scenario` files written (the caller's own way: the CLI writes
 *    them, the IDE saves them through its file queue);
 * 4. the journal removed: the rename is whole.
 * A failed step says which it was (RenameStepError): the journal not written, nothing changed; the
 * carry-over failed, the journal is removed (the project's files are as they were); the files
 * failed, the journal stays, and the next generation finishes the rename.
 */
import { carryRenameIntoTree, type TreeCarryOver } from './carry-rename.js';
import { removeRenameJournal, writeRenameJournal, type RenameJournal } from './rename-journal.js';

/** The step of runJournaledRename that failed. */
export type RenameStep = 'journal' | 'carry-over' | 'files';

/** A step of a rename that failed, with the error it threw (`cause`, whose message this one keeps). */
export class RenameStepError extends Error {
    constructor(readonly step: RenameStep, override readonly cause: unknown) {
        super(cause instanceof Error ? cause.message : String(cause));
        this.name = 'RenameStepError';
    }
}

export interface JournaledRenameOptions<W> {
    /** Whether the journal is written (a rename with project files to write and a tree to hold it). */
    journaled: boolean;
    /** Writes the project's files once the tree is carried over; throwing leaves the journal. */
    writeFiles: (carried: TreeCarryOver) => Promise<W> | W;
    /** Tests only: called after the journal is written and after the carry-over; what it throws stops the rename there, as a crash would. */
    step?: (at: 'journaled' | 'tree carried over') => void;
}

/**
 * Runs a rename whose journal is `journal` on generated tree `srcGen`, in the order above. Throws
 * a RenameStepError naming the step that failed. The caller holds the tree's lock.
 */
export async function runJournaledRename<W>(srcGen: string, journal: RenameJournal, options: JournaledRenameOptions<W>): Promise<{ carried: TreeCarryOver; written: W }> {
    if (options.journaled) {
        try {
            writeRenameJournal(srcGen, journal);
        } catch (e) {
            throw new RenameStepError('journal', e);
        }
    }
    options.step?.('journaled');
    let carried: TreeCarryOver;
    try {
        carried = await carryRenameIntoTree(srcGen, journal);
    } catch (e) {
        if (options.journaled) removeRenameJournal(srcGen); // the project's files are as they were
        throw new RenameStepError('carry-over', e);
    }
    options.step?.('tree carried over');
    let written: W;
    try {
        written = await options.writeFiles(carried);
    } catch (e) {
        throw new RenameStepError('files', e); // the journal stays: the next generation finishes the rename
    }
    if (options.journaled) removeRenameJournal(srcGen);
    return { carried, written };
}
