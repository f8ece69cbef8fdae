/**
 * One writer of a generated tree at a time, across processes: `contract generate` or `contract
 * rename` in a terminal, and the IDE server's Generate All, rename carry-over and saves of generated
 * files, each read a file, merge, then write it. Without a common lock, one could write a file
 * between the other's read and write, and what the first had read was lost (a region save the IDE
 * had confirmed, overwritten by a terminal's generate).
 *
 * The lock is the file `.contract-lock` in the output folder (src-gen), created exclusively
 * (O_EXCL, never through a link) and holding the holder's pid; removed when done. A lock whose
 * holder no longer runs on this machine (killed mid-write) is taken over. Waiting is bounded:
 * LOCK_WAIT_MS, then an error names the holder.
 */
import { closeSync, constants, openSync, readSync, unlinkSync, writeSync } from 'node:fs';
import { join } from 'node:path';
import { TREE_LOCK_NAME } from '@contract-studio/conventions';
import { pidAlive } from './stale-temp.js';

export { TREE_LOCK_NAME };

/** How long a writer waits for another's lock before giving up, saying who holds it. */
export const LOCK_WAIT_MS = 30_000;

/** Between two tries. */
const POLL_MS = 20;

export function isTreeLock(name: string): boolean {
    return name === TREE_LOCK_NAME;
}

export class TreeLockedError extends Error {}


/**
 * One try at the lock of output folder `dir` (a path; `/proc/self/fd/N` for an opened folder):
 * a release function when taken, else the pid that holds it. A stale lock is removed and tried again.
 */
export function tryTreeLock(dir: string): (() => void) | { holder: number | undefined } {
    const path = join(dir, TREE_LOCK_NAME);
    for (let attempt = 0; attempt < 3; attempt++) {
        let fd: number;
        try {
            fd = openSync(path, constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW, 0o644);
        } catch (e) {
            if ((e as NodeJS.ErrnoException).code !== 'EEXIST') throw e;
            let holder: number | undefined;
            try {
                const held = openSync(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
                const buffer = Buffer.alloc(32);
                let text: string;
                try {
                    text = buffer.subarray(0, readSync(held, buffer, 0, buffer.length, 0)).toString('utf8').trim();
                } finally {
                    closeSync(held);
                }
                holder = /^\d{1,10}$/.test(text) ? Number(text) : undefined;
            } catch (readError) {
                const code = (readError as NodeJS.ErrnoException).code;
                if (code === 'ENOENT') continue; // released meanwhile
                if (code !== 'ELOOP') throw readError;
            }
            // a writer killed mid-write (or a lock with no pid in it, written by no writer of ours)
            if (holder === undefined || !pidAlive(holder)) {
                try {
                    unlinkSync(path);
                } catch (unlinkError) {
                    if ((unlinkError as NodeJS.ErrnoException).code !== 'ENOENT') throw unlinkError;
                }
                continue;
            }
            return { holder };
        }
        try {
            writeSync(fd, `${process.pid}\n`);
        } finally {
            closeSync(fd);
        }
        let released = false;
        return () => {
            if (released) return;
            released = true;
            try {
                unlinkSync(path);
            } catch {
                // already gone (the folder removed): nothing to release
            }
        };
    }
    return { holder: undefined };
}

function lockedError(what: string, holder: number | undefined, waitMs: number): TreeLockedError {
    return new TreeLockedError(`${what} is being written by another process${holder !== undefined ? ` (pid ${holder}: a contract generate or rename, or the IDE server)` : ''} for more than ${waitMs / 1000} s: try again when it has finished (or remove its ${TREE_LOCK_NAME} if no such process runs)`);
}

/** Takes the lock of `dir`, waiting (the thread sleeps) up to `waitMs`; `what` names the folder in the error. */
export function lockTreeSync(dir: string, what: string, waitMs = LOCK_WAIT_MS): () => void {
    const sleeper = new Int32Array(new SharedArrayBuffer(4));
    const until = Date.now() + waitMs;
    for (;;) {
        const got = tryTreeLock(dir);
        if (typeof got === 'function') return got;
        if (Date.now() >= until) throw lockedError(what, got.holder, waitMs);
        Atomics.wait(sleeper, 0, 0, POLL_MS);
    }
}

/** Takes the lock of `dir`, waiting (without blocking the event loop) up to `waitMs`. */
export async function lockTree(dir: string, what: string, waitMs = LOCK_WAIT_MS): Promise<() => void> {
    const until = Date.now() + waitMs;
    for (;;) {
        const got = tryTreeLock(dir);
        if (typeof got === 'function') return got;
        if (Date.now() >= until) throw lockedError(what, got.holder, waitMs);
        await new Promise((r) => setTimeout(r, POLL_MS));
    }
}
