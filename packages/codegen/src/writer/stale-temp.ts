import { lstatSync, readdirSync, unlinkSync, type Dirent } from 'node:fs';
import { join } from 'node:path';
import { TEMP_NAME as TEMP } from './atomic-write.js';

/**
 * Temporary files (`.<name>.tmp-<pid>`, atomic-write.ts) left in an output folder by a generator
 * that was killed between writing and renaming. They are removed on the next write into that
 * folder when their writer is gone: its pid is not alive, or the file is older than
 * STALE_TEMP_AGE_MS (a pid may have been reused, or belong to another pid namespace). The temp
 * file of a live writer is never touched (docs/codegen.md, "Temporary files").
 */
export const STALE_TEMP_AGE_MS = 10 * 60 * 1000;


/** Whether process `pid` exists (EPERM: it exists but belongs to another user). */
export function pidAlive(pid: number): boolean {
    if (!Number.isSafeInteger(pid) || pid <= 0) return false;
    try {
        process.kill(pid, 0);
        return true;
    } catch (e) {
        return (e as NodeJS.ErrnoException).code === 'EPERM';
    }
}

/**
 * Removes the stale temporary files of folder `dir` (already checked: a real folder); returns
 * their names. `listing`: the folder's entries when the caller has just read them.
 */
export function removeStaleTemps(dir: string, listing?: Dirent[], now = Date.now()): string[] {
    const removed: string[] = [];
    let entries = listing;
    try {
        entries ??= readdirSync(dir, { withFileTypes: true });
    } catch {
        return removed;
    }
    for (const entry of entries) {
        const m = TEMP.exec(entry.name);
        if (!m || !entry.isFile()) continue;
        const abs = join(dir, entry.name);
        try {
            const st = lstatSync(abs);
            if (!st.isFile()) continue;
            if (pidAlive(Number(m[1])) && now - st.mtimeMs <= STALE_TEMP_AGE_MS) continue;
            unlinkSync(abs);
            removed.push(entry.name);
        } catch {
            // removed meanwhile by another cleaner, or not ours to remove: leave it
        }
    }
    return removed.sort();
}
