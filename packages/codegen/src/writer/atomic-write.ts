import { closeSync, constants, openSync, renameSync, unlinkSync, writeSync } from 'node:fs';
import { join } from 'node:path';

/** The temporary file of `name` written by process `pid` (stale-temp.ts recognises the form). */
export function tempName(name: string, pid = process.pid): string {
    return `.${name}.tmp-${pid}`;
}

/** Creates `path` for writing; never opens an existing file or a symlink (O_EXCL, O_NOFOLLOW). */
function createExclusive(path: string): number {
    const flags = constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW;
    try {
        return openSync(path, flags, 0o666);
    } catch (e) {
        if ((e as NodeJS.ErrnoException).code !== 'EEXIST') throw e;
        // our own name: left by an earlier process with this pid (the generator writes
        // synchronously, so never by a live write of ours); unlink removes a planted link itself
        unlinkSync(path);
        return openSync(path, flags, 0o666);
    }
}

/**
 * Writes `data` to `dir/name` through a temporary file in the same folder and a rename: readers
 * never see half a file. The temporary file is created exclusively without following links, and
 * rename replaces the directory entry, so nothing is ever written through a symlink planted at
 * either name. `dir` must already be checked (OutputTree.write does it).
 */
export function writeFileAtomic(dir: string, name: string, data: Buffer): void {
    const tmp = join(dir, tempName(name));
    const fd = createExclusive(tmp);
    try {
        try {
            for (let off = 0; off < data.length; ) off += writeSync(fd, data, off, data.length - off);
        } finally {
            closeSync(fd);
        }
        renameSync(tmp, join(dir, name));
    } catch (e) {
        try {
            unlinkSync(tmp);
        } catch {
            // already gone
        }
        throw e;
    }
}
