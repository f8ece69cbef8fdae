import { existsSync, readFileSync } from 'node:fs';
import { posix } from 'node:path';
import type { Region } from '../regions/parse-regions.js';
import { bytesOf } from './byte-string.js';
import { writeFileAtomic } from './atomic-write.js';

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
 * Returns the orphan's path relative to the output folder and whether a file was written.
 */
export function writeOrphan(outDir: string, path: string, content: string): { path: string; written: boolean } {
    for (let n = 1; ; n++) {
        const rel = candidate(path, n);
        const abs = posix.join(outDir, rel);
        if (!existsSync(abs)) {
            writeFileAtomic(abs, bytesOf(content));
            return { path: rel, written: true };
        }
        if (readFileSync(abs, 'latin1') === content) return { path: rel, written: false };
    }
}

/** The text of an orphan file holding the regions that vanished from `path`. */
export function regionOrphanText(path: string, source: string, regions: Region[]): string {
    const header =
        `/* Orphaned protected regions of ${path}\n` +
        ` * Their IDs no longer exist in the generated code (renamed or deleted entity, removed port...).\n` +
        ` * Copy what you still need back into the generated tree, then delete this file. */\n`;
    return header + regions.map((r) => `\n${source.slice(r.start, r.end)}\n`).join('');
}
