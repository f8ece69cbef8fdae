import { posix } from 'node:path';
import type { Region } from '../regions/parse-regions.js';
import { bytesOf } from './byte-string.js';
import type { OutputTree } from './output-tree.js';

/** Folder (relative to the output folder) where orphaned user code goes. */
export const ORPHANS_DIR = 'orphans';

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

function withoutHeader(text: string): string {
    return text.startsWith(HEADER_START) ? text.slice(text.indexOf('*/\n') + 3) : text;
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
 * The comment an orphan file starts with: which entity and file the code came from, when it was
 * moved, and how to bring it back (docs/codegen.md, "Renames").
 */
function orphanHeader(path: string, ids: string[], when: Date, wholeFile: boolean): string {
    return `${HEADER_START} of ${path} (${orphanEntity(path)}), moved here on ${when.toISOString()}.\n` +
        ` * ${wholeFile ? 'The entity no longer exists' : 'These protected regions no longer exist'} in the generated code (renamed or deleted entity, removed port...): ${ids.join(', ')}.\n` +
        ` * To bring the code back: if the entity was renamed, paste each region's content into the region of the same\n` +
        ` * role in the new entity's file (protect_exec_OLD -> protect_exec_NEW); if it was deleted by mistake, restore it\n` +
        ` * in the .contract files${wholeFile ? ` and copy this file, without this comment, back to ${path}` : ''}, then generate.\n` +
        ` * Then delete this file. Renaming with \`contract rename DIR OLD NEW\` or the IDE's rename carries regions over. */\n`;
}

/** The text of an orphan file holding the regions that vanished from `path`. */
export function regionOrphanText(path: string, source: string, regions: Region[], when = new Date()): string {
    return orphanHeader(path, regions.map((r) => r.id), when, false) + regions.map((r) => `\n${source.slice(r.start, r.end)}\n`).join('');
}

/** The text of the orphan of a whole file whose entity disappeared: the header, then the file as it was. */
export function fileOrphanText(path: string, source: string, ids: string[], when = new Date()): string {
    return orphanHeader(path, ids, when, true) + source;
}
