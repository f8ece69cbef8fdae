import { posix } from 'node:path';
import type { Region } from '../regions/parse-regions.js';
import { bytesOf } from './byte-string.js';
import type { OutputTree } from './output-tree.js';

/** Folder (relative to the output folder) where orphaned user code goes (@contract-studio/conventions). */
import { ORPHANS_DIR } from '@contract-studio/conventions';
export { ORPHANS_DIR };

/**
 * The n-th candidate name for the orphan of `path`: `orphans/<path>`, then
 * `orphans/<dir>/<name>.2.<ext>`, `.3.`, ... (deterministic, never a timestamp).
 */
function candidate(path: string, n: number): string {
    const target = posix.join(ORPHANS_DIR, path);
    if (n === 1) return target;
    const dir = posix.dirname(target);
    const base = posix.basename(target);
    const dot = base.lastIndexOf('.');
    const name = dot > 0 ? `${base.slice(0, dot)}.${n}${base.slice(dot)}` : `${base}.${n}`;
    return posix.join(dir, name);
}

/** The orphans of `path` there are in the tree (`orphans/<path>`, `.2.`, ...), in the order they were written. */
export function existingOrphans(tree: OutputTree, path: string): string[] {
    const found: string[] = [];
    for (let n = 1; n <= 1000 && tree.stat(candidate(path, n)) !== undefined; n++) found.push(candidate(path, n));
    return found;
}

/**
 * Writes orphaned content (a byte string) for `path` without ever overwriting an earlier orphan:
 * the first free numbered name is used; an existing orphan with the very same content is reused.
 * Returns the orphan's path relative to the output folder and whether a file was written. Goes
 * through `tree`: an orphan path met as a link is refused (UnsafePathError), never read or written.
 */
export function writeOrphan(tree: OutputTree, path: string, content: string): { path: string; written: boolean } {
    for (let n = 1; ; n++) {
        const rel = candidate(path, n);
        const existing = tree.read(rel);
        if (existing === undefined) {
            tree.write(rel, bytesOf(content));
            return { path: rel, written: true };
        }
        // the same orphaned code again (its header's date aside): reuse it
        if (withoutHeader(existing) === withoutHeader(content)) return { path: rel, written: false };
    }
}

const HEADER_START = '/* Orphaned user code';
/** The start of the header of a copy made with no record of what the generator wrote (reason `unrecorded`): perhaps no user code at all. */
const COPY_HEADER_START = '/* Copy of';

function withoutHeader(text: string): string {
    return text.startsWith(HEADER_START) || text.startsWith(COPY_HEADER_START) ? text.slice(text.indexOf('*/\n') + 3) : text;
}

/** The entity a generated path is named after (docs/codegen.md, generated tree). */
export function orphanEntity(path: string): string {
    const module = /\/modules\/([A-Za-z0-9_]+)_mod\//.exec(path)?.[1] ?? /\/tools\/(?:make)?control([A-Za-z0-9_]+?)(?:\.c)?$/.exec(path)?.[1];
    if (module) return module === 'ORD' ? 'the scheduler ORD' : `module or supervisor ${module}`;
    const fn = /\/common\/SharedFunction([A-Za-z0-9_]+)\.h$/.exec(path)?.[1];
    if (fn) return `function ${fn}`;
    const type = /\/common\/Shared([A-Za-z0-9_]+)\.h$/.exec(path)?.[1];
    return type ? `datatype ${type}` : 'the entity it was generated for';
}

/**
 * Why code went to orphans/: its regions vanished from the generated code, its whole file did
 * (entity deleted), its regions were not ENABLED (the generator put its default back), the file
 * was edited outside its regions (the generator rewrote the file), or (`unrecorded`) with no record
 * of what a generator wrote in it, it held lines outside its regions that this generator does not
 * write: an older generator's, or the user's (docs/codegen.md, "Without a record").
 */
export type OrphanReason = 'vanished' | 'deleted' | 'disabled' | 'skeleton' | 'unrecorded';

/**
 * The comment an orphan file starts with: which entity and file the code came from, when it was
 * moved, why, and how to bring it back (docs/codegen.md, "Renames", "Protected regions").
 */
function orphanHeader(path: string, ids: string[], when: Date, reason: OrphanReason, regionless = false, homes: ReadonlyMap<string, string> = new Map()): string {
    const head = `${HEADER_START} of ${path} (${orphanEntity(path)}), moved here on ${when.toISOString()}.\n`;
    const tail = ` * Then delete this file. Renaming with \`contract rename DIR OLD NEW\` or the IDE's rename carries regions over. */\n`;
    if (reason === 'disabled') {
        return head +
            ` * These protected regions were not ENABLED (their start marker lacks the word ENABLED, removed or mistyped), so the\n` +
            ` * generator put its default back in them: ${ids.join(', ')}. Their content as it was is below.\n` +
            ` * To bring the code back: paste each region's content into the region of the same ID in ${path}, make its start\n` +
            ` * marker say ENABLED again (PROTECTED REGION ID(<id>) ENABLED START), then generate.\n` +
            ` * Then delete this file. (Removing ENABLED is the way to ask for the default: if you meant that, just delete this file.) */\n`;
    }
    if (reason === 'unrecorded') {
        return `${COPY_HEADER_START} ${path} (${orphanEntity(path)}), made on ${when.toISOString()} before it was regenerated.\n` +
            ` * It held lines outside its protected regions that this generator does not write (${ids.join('; ')}):\n` +
            ` * an older generator's lines (another version of ContrACT Studio, or another tool such as the ContrACT Eclipse tool),\n` +
            ` * or code of yours; with no record of what was generated, the generator cannot tell which, so it keeps this copy.\n` +
            ` * Its protected regions' code was kept in the regenerated file. Below is the file as it was, byte for byte.\n` +
            ` * If some of those lines are code of yours, move it into a protected region of ${path} (declarations in\n` +
            ` * protect_internal_vars_/protect_internal_functions_decl_, functions in protect_internal_functions_impl_, includes in\n` +
            ` * protect_additional_import_...), then generate. If they are only an older generator's lines, nothing is lost.\n` +
            ` * Then delete this file. */\n`;
    }
    if (reason === 'skeleton' && regionless) {
        return head +
            ` * The file differed from what the generator wrote (${ids.join('; ')}), and it has no protected region: it is generated\n` +
            ` * whole, so nothing written in it is kept, and it was regenerated. Below is the file as it was, byte for byte.\n` +
            ` * If the difference came from a git merge of two generated versions (a rename on one branch, a model change on the\n` +
            ` * other), the regenerated file is the merged model's and this copy can be deleted. If you wrote code here, put it in\n` +
            ` * a protected region of the module's module.c, or change the .contract model, then generate.\n` +
            tail;
    }
    if (reason === 'skeleton') {
        return head +
            ` * The file was edited outside its protected regions (${ids.join('; ')}): code there belongs to the generator and was\n` +
            ` * regenerated. Below is the file as it was, byte for byte.\n` +
            ` * To bring the code back: move it into a protected region of ${path} (declarations in\n` +
            ` * protect_internal_vars_/protect_internal_functions_decl_, functions in protect_internal_functions_impl_, includes in\n` +
            ` * protect_additional_import_...), or change the .contract model if it was generated code you meant to change, then generate.\n` +
            tail;
    }
    const wholeFile = reason === 'deleted';
    const elsewhere = ids.filter((id) => homes.has(id)).map((id) => ` * ${id} is no region of this file but of ${homes.get(id)} (a git merge or a paste put it here): paste its\n * content into the region of that ID there (beside any code that region holds), then generate.\n`).join('');
    return head +
        (elsewhere !== '' && !wholeFile
            ? ` * These protected regions are not generated in this file: ${ids.join(', ')}.\n`
            : ` * ${wholeFile ? 'The entity no longer exists' : 'These protected regions no longer exist'} in the generated code (renamed or deleted entity, removed port...): ${ids.join(', ')}.\n`) +
        elsewhere +
        ` * To bring the code back: if the entity was renamed, paste each region's content into the region of the same\n` +
        ` * role in the new entity's file (protect_exec_OLD -> protect_exec_NEW); if it was deleted by mistake, restore it\n` +
        ` * in the .contract files${wholeFile ? ` and copy this file, without this comment, back to ${path}` : ''}, then generate.\n` +
        tail;
}

/**
 * The text of an orphan file holding regions of `path`: vanished from the generated code (`homes`:
 * those generated in another file, by ID: found in the wrong file), or (`disabled`) replaced by their default.
 */
export function regionOrphanText(path: string, source: string, regions: Region[], when = new Date(), reason: 'vanished' | 'disabled' = 'vanished', homes?: ReadonlyMap<string, string>): string {
    return orphanHeader(path, regions.map((r) => r.id), when, reason, false, homes) + regions.map((r) => `\n${source.slice(r.start, r.end)}\n`).join('');
}

/**
 * The text of the orphan of a whole file, the header then the file as it was: its entity
 * disappeared (`ids`: its user regions), or (`skeleton`) it was edited outside its regions (`ids`:
 * what is known of where, e.g. the first line that differs), or (`unrecorded`) with no record of
 * what was generated, it held lines outside its regions this generator does not write (`ids`: which, and why no record).
 */
export function fileOrphanText(path: string, source: string, ids: string[], when = new Date(), reason: 'deleted' | 'skeleton' | 'unrecorded' = 'deleted'): string {
    return orphanHeader(path, ids, when, reason, !source.includes('PROTECTED REGION ID(')) + source;
}
