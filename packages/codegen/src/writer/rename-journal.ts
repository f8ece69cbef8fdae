/**
 * The journal of a `contract rename` (docs/codegen.md, "A rename killed half-way"): a rename
 * changes the generated tree (paths, region IDs, identifiers in user code) and then the project's
 * `.contract` and `.scenario` files. Killed between the two, the tree was renamed and the model
 * not: the next generation moved the renamed module's code to `orphans/`. So, before it changes
 * anything, the rename writes `src-gen/.contract-rename.json`: what it renames, and each project
 * file's text before (a hash) and after. It removes the journal once every file is written. The
 * next writer of the tree that finds one (`contract generate`, `contract rename`, the IDE's
 * Generate All and rename: they take the tree's lock, then finishInterruptedRename) finishes it:
 * the tree carry-over again (it is idempotent: what moved already is not there any more), then
 * each file still as it was before the rename gets its text after; a file changed since (neither
 * before nor after) is left as it is, and named. writeTree refuses a tree holding a journal (a
 * build's staged copy of such a tree): the model it was given is the half-renamed one.
 *
 * A journal is read as untrusted input (a project folder may come from anywhere): its file paths
 * must be plain relative `.contract`/`.scenario` paths of the project, outside src-gen, reached
 * without following any link (OutputTree); anything else refuses the whole journal, naming why.
 */
import { createHash } from 'node:crypto';
import { realpathSync } from 'node:fs';
import { resolve } from 'node:path';
import { RENAME_JOURNAL_NAME, SRC_GEN_DIR } from '@contract-studio/conventions';
import { OutputTree } from './output-tree.js';
import { carryRenameIntoTree, type TreeCarryOver } from './carry-rename.js';
import { carryRefusedMessage, type RegionMention } from './rename-user-code.js';
import { treePathProblem } from './safe-paths.js';

export { RENAME_JOURNAL_NAME };

/** A journal larger than this is refused (it holds the project's renamed `.contract` texts). */
export const MAX_JOURNAL_BYTES = 64 * 1024 * 1024;

export interface RenameJournalFile {
    /** Relative to the project folder (the parent of src-gen). */
    path: string;
    /** sha256 (hex) of the file's bytes before the rename. */
    before: string;
    /** The file's text after the rename. */
    after: string;
}

export interface RenameJournal {
    version: 1;
    /** The language's kind of the renamed entity (module, port, datatype...), as told to the user. */
    kind: string;
    oldName: string;
    newName: string;
    /** Whether the entity names generated files and region IDs (renameInGeneratedTree). */
    generatedNames: boolean;
    /** C identifiers renamed in the protected regions' code (identifierRenames), as pairs. */
    identifiers: Array<[string, string]>;
    /** The module whose module.c alone holds those identifiers (a port or parameter). */
    identifierOwner?: string;
    files: RenameJournalFile[];
    /**
     * The project folder (real path) of a rename whose tree is not the project's own src-gen
     * (`contract rename -o OUT`): finished only by a generate or rename of that folder with that
     * OUT. Absent for the project's src-gen, whose parent is the project wherever it was cloned.
     */
    project?: string;
}

export function sha256(bytes: Buffer): string {
    return createHash('sha256').update(bytes).digest('hex');
}

const NAME = /^[A-Za-z_][A-Za-z0-9_]*$/;

/** Why `value` is not a journal this code wrote, or undefined. */
function journalProblem(value: unknown): string | undefined {
    const j = value as Partial<RenameJournal> | null;
    if (typeof j !== 'object' || j === null || j.version !== 1) return 'not a journal of this version';
    if (typeof j.kind !== 'string' || !/^[a-z ]{1,40}$/.test(j.kind)) return 'bad kind';
    if (typeof j.oldName !== 'string' || !NAME.test(j.oldName) || typeof j.newName !== 'string' || !NAME.test(j.newName)) return 'bad names';
    if (typeof j.generatedNames !== 'boolean') return 'bad generatedNames';
    if (!Array.isArray(j.identifiers) || !j.identifiers.every((p) => Array.isArray(p) && p.length === 2 && p.every((n) => typeof n === 'string' && NAME.test(n)))) return 'bad identifiers';
    if (j.identifierOwner !== undefined && (typeof j.identifierOwner !== 'string' || !NAME.test(j.identifierOwner))) return 'bad identifierOwner';
    if (j.project !== undefined && (typeof j.project !== 'string' || !j.project.startsWith('/') || j.project.length > 4096 || /[\u0000-\u001f]/.test(j.project))) return 'bad project';
    if (!Array.isArray(j.files) || j.files.length > 10_000) return 'bad files';
    for (const f of j.files) {
        if (typeof f !== 'object' || f === null || typeof f.path !== 'string' || typeof f.before !== 'string' || typeof f.after !== 'string') return 'bad file entry';
        const problem = treePathProblem(f.path);
        if (problem) return `file ${JSON.stringify(f.path.slice(0, 200))}: ${problem}`;
        if (!/\.(contract|scenario)$/.test(f.path)) return `file ${JSON.stringify(f.path.slice(0, 200))}: not a .contract or .scenario file`;
        if (f.path === SRC_GEN_DIR || f.path.startsWith(`${SRC_GEN_DIR}/`)) return `file ${JSON.stringify(f.path)}: inside ${SRC_GEN_DIR}`;
        if (!/^[0-9a-f]{64}$/.test(f.before)) return `file ${JSON.stringify(f.path)}: bad hash`;
    }
    return undefined;
}

/** Writes the journal of a rename into generated tree `srcGen` (atomic, no link followed), before the rename changes anything. */
export function writeRenameJournal(srcGen: string, journal: RenameJournal): void {
    const tree = new OutputTree(srcGen);
    try {
        tree.write(RENAME_JOURNAL_NAME, Buffer.from(JSON.stringify(journal), 'utf8'));
    } finally {
        tree.close();
    }
}

/** Removes the journal of tree `srcGen` (the rename wrote every file). */
export function removeRenameJournal(srcGen: string): void {
    const tree = new OutputTree(srcGen);
    try {
        tree.remove(RENAME_JOURNAL_NAME);
    } finally {
        tree.close();
    }
}

/** Whether tree `srcGen` holds a rename journal (an unfinished rename), without reading it. */
export function hasRenameJournal(tree: OutputTree): boolean {
    return tree.stat(RENAME_JOURNAL_NAME) !== undefined;
}

export interface FinishedRename {
    kind: string;
    oldName: string;
    newName: string;
    /** Project files given their renamed text. */
    written: string[];
    /** Project files that already had it. */
    already: string[];
    /** Project files changed since the rename began (or gone): left as they are. */
    changed: string[];
    /** The C identifiers the rename changes in the protected regions' code (the journal's), as pairs. */
    identifiers: Array<[string, string]>;
    /** The module whose module.c alone holds them (a port or parameter). */
    identifierOwner?: string;
    /**
     * Why the uses of those identifiers in the protected regions' code were not rewritten, when
     * they were not (IdentifierCarryReport.refused, a file relative to the tree): the build fails
     * until they are changed by hand.
     */
    refused?: RegionMention;
}

/**
 * Finishes the rename that tree `srcGen` of project folder `projectDir` (its parent) holds a journal
 * of, if any: undefined when there is none. The caller holds the tree's lock. Throws (an Error
 * naming the journal) when the journal is not one this code wrote: it is then left in place.
 */
export async function finishInterruptedRename(projectDir: string, srcGen: string): Promise<FinishedRename | undefined> {
    const tree = new OutputTree(srcGen);
    let text: string | undefined;
    try {
        text = tree.read(RENAME_JOURNAL_NAME, MAX_JOURNAL_BYTES);
    } catch (e) {
        throw new Error(`${SRC_GEN_DIR}/${RENAME_JOURNAL_NAME} (an unfinished rename) cannot be read: ${(e as Error).message}; remove it to go on`);
    } finally {
        tree.close();
    }
    if (text === undefined) return undefined;
    let journal: RenameJournal;
    let problem: string | undefined;
    try {
        journal = JSON.parse(Buffer.from(text, 'latin1').toString('utf8')) as RenameJournal;
        problem = journalProblem(journal);
    } catch {
        journal = null as unknown as RenameJournal;
        problem = 'not JSON';
    }
    if (problem) throw new Error(`${SRC_GEN_DIR}/${RENAME_JOURNAL_NAME} is not the journal of an unfinished rename (${problem}): nothing was changed; remove it to go on`);
    // a tree out of the project (-o OUT) is finished only for the project whose rename it journals
    const own = resolve(srcGen) === resolve(projectDir, SRC_GEN_DIR);
    if (!own && (journal.project === undefined || journal.project !== realOrSelf(projectDir))) {
        throw new Error(`${RENAME_JOURNAL_NAME} in this output folder journals a rename of ${journal.project ?? 'the project whose src-gen it was'}, not of ${projectDir}: nothing was changed; run contract generate on that project with this output folder, or remove it`);
    }
    let carried: TreeCarryOver;
    try {
        carried = await carryRenameIntoTree(srcGen, journal);
    } catch (e) {
        throw new Error(`the rename of ${journal.kind} ${journal.oldName} -> ${journal.newName} in ${SRC_GEN_DIR}/${RENAME_JOURNAL_NAME} cannot be finished: ${(e as Error).message}; nothing was changed; remove the journal to go on (the tree keeps what the killed rename moved)`);
    }
    const done: FinishedRename = {
        kind: journal.kind, oldName: journal.oldName, newName: journal.newName, written: [], already: [], changed: [],
        identifiers: journal.identifiers, ...(journal.identifierOwner !== undefined ? { identifierOwner: journal.identifierOwner } : {}),
        ...(carried.code?.refused ? { refused: carried.code.refused } : {}),
    };
    // the project folder as named (a link to it, or the IDE's /proc/self/fd path of the folder it
    // opened, is the user's own choice); below it no link is followed
    const project = new OutputTree(`${projectDir.replace(/\/+$/, '')}/.`);
    try {
        for (const f of journal.files) {
            const now = project.read(f.path);
            const bytes = now === undefined ? undefined : Buffer.from(now, 'latin1');
            const after = Buffer.from(f.after, 'utf8');
            if (bytes !== undefined && bytes.equals(after)) done.already.push(f.path);
            else if (bytes !== undefined && sha256(bytes) === f.before) {
                project.write(f.path, after);
                done.written.push(f.path);
            } else done.changed.push(f.path);
        }
    } finally {
        project.close();
    }
    removeRenameJournal(srcGen);
    return done;
}

/** `dir`'s real path, or `dir` when it cannot be resolved. */
export function realOrSelf(dir: string): string {
    try {
        return realpathSync(dir);
    } catch {
        return resolve(dir);
    }
}

/** What finishInterruptedRename did, in words: each caller (a terminal, the IDE) lays it out its own way. */
export interface FinishedRenameDescription {
    /** What was finished, and how many files it wrote: one sentence. */
    summary: string;
    /** The project files given their renamed text, as the caller names them. */
    written: string[];
    /**
     * One sentence per project file left as it was (changed since the rename began, or gone), and
     * one when the uses in the protected regions' code were not rewritten (a capture).
     */
    warnings: string[];
}

/**
 * Says what finishInterruptedRename did; `inProject` names a project file (relative path) for the
 * reader, `inTree` a file of the generated tree (relative to it; by default as the tree's folder
 * in the project, `src-gen/...`).
 */
export function describeFinishedRename(done: FinishedRename, inProject: (path: string) => string, inTree: (path: string) => string = (f) => inProject(`${SRC_GEN_DIR}/${f}`)): FinishedRenameDescription {
    const warnings = done.changed.map((f) => `${inProject(f)} changed since the rename began (or is gone): left as it is; rename ${done.oldName} there by hand`);
    if (done.refused) {
        const taken = done.refused;
        warnings.push(`${carryRefusedMessage(taken, done.identifiers.map(([from]) => from), `${inTree(taken.file)}:${taken.line}`)}: change them by hand, the build fails until then`);
    }
    return {
        summary: `finished the rename of ${done.kind} ${done.oldName} -> ${done.newName} that was interrupted (its journal ${SRC_GEN_DIR}/${RENAME_JOURNAL_NAME}): ${done.written.length} file(s) written, ${done.already.length} already renamed`,
        written: done.written.map(inProject),
        warnings,
    };
}
