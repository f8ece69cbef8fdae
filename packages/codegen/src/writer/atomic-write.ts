/**
 * The one atomic file write of the project (the generator's output tree, `contract rename`, the
 * IDE's saves): a temporary file in the same folder, created exclusively without following links,
 * written and fsync'ed, renamed over the target, then the folder fsync'ed. Readers see the old or
 * the new bytes, never a mix; after a crash the file is one of the two; nothing is ever written
 * through a symlink planted at either name. Also published as `@contract-studio/codegen/atomic-write`
 * (Node built-ins only) for the IDE server.
 */
import { closeSync, constants, fsyncSync, openSync, renameSync, unlinkSync, writeSync } from 'node:fs';
import { join } from 'node:path';

/** The temporary file of `name` written by process `pid` (stale-temp.ts recognises the form). */
export function tempName(name: string, pid = process.pid): string {
    return `.${name}.tmp-${pid}`;
}

/** `.<name>.tmp-<pid>`: group 1 = the writer's pid. */
export const TEMP_NAME = /^\..+\.tmp-(\d{1,10})$/;

/** True for the temporary files writeFileAtomic creates (hidden from listings and watchers). */
export function isAtomicTempFile(name: string): boolean {
    return TEMP_NAME.test(name);
}

/** Creates `path` for writing; never opens an existing file or a symlink (O_EXCL, O_NOFOLLOW). */
function createExclusive(path: string): number {
    const flags = constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW;
    try {
        return openSync(path, flags, 0o666);
    } catch (e) {
        if ((e as NodeJS.ErrnoException).code !== 'EEXIST') throw e;
        // our own name: left by an earlier process with this pid (the write is synchronous, so
        // never by a live write of ours); unlink removes a planted link itself
        unlinkSync(path);
        return openSync(path, flags, 0o666);
    }
}

/** fsync of a folder, so a rename in it survives a crash; some filesystems refuse it (the rename is still atomic). */
export function syncFolder(dir: string): void {
    let fd: number | undefined;
    try {
        fd = openSync(dir, constants.O_RDONLY | constants.O_DIRECTORY);
        fsyncSync(fd);
    } catch {
        // refused: nothing more to do
    } finally {
        if (fd !== undefined) closeSync(fd);
    }
}

/**
 * Writes `data` to `dir/name` atomically and durably (see above). `dir` must already be checked
 * (OutputTree.write does it; the IDE passes a folder it opened without following links as
 * /proc/self/fd/N). On failure the old file is untouched and the temporary file removed.
 * `syncDir: false` leaves the folder's fsync to the caller, which writes many files into it and
 * syncs it once (OutputTree, before it closes the folder).
 */
export function writeFileAtomic(dir: string, name: string, data: Uint8Array, { syncDir = true }: { syncDir?: boolean } = {}): void {
    const tmp = join(dir, tempName(name));
    const fd = createExclusive(tmp);
    try {
        try {
            for (let off = 0; off < data.length; ) off += writeSync(fd, data, off, data.length - off);
            fsyncSync(fd);
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
    if (syncDir) syncFolder(dir);
}
