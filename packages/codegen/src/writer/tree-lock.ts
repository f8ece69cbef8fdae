/**
 * One writer of a generated tree at a time, across processes: `contract generate` or `contract
 * rename` in a terminal, and the IDE server's Generate All, rename carry-over and saves of generated
 * files, each read a file, merge, then write it. Without a common lock, one could write a file
 * between the other's read and write, and what the first had read was lost (a region save the IDE
 * had confirmed, overwritten by a terminal's generate).
 *
 * The lock is the file `.contract-lock` in the output folder (src-gen), holding the holder's pid and
 * host name (a lock of another machine's is not this one's), created exclusively (O_EXCL, never
 * through a link); one with no pid yet is being written by its taker, not stale (for 2 s).
 * Removed when done, only while it still holds this process's pid. A lock whose holder no longer
 * runs on this machine (killed mid-write), or that holds no pid, is taken over. Waiting is bounded:
 * LOCK_WAIT_MS, then an error names the holder.
 *
 * Within one process the lock is re-entrant (by the folder's device and inode): the IDE server takes
 * it without blocking its event loop (lockTree), then the generator's own synchronous take
 * (lockTreeSync, in writeTree) finds it held by itself and goes on.
 */
import { closeSync, constants, lstatSync, openSync, readSync, statSync, unlinkSync, writeSync } from 'node:fs';
import { hostname } from 'node:os';
import { join } from 'node:path';
import { TREE_LOCK_NAME } from '@contract-studio/conventions';
import { pidAlive } from './stale-temp.js';

export { TREE_LOCK_NAME };

/** How long a writer waits for another's lock before giving up, saying who holds it. */
export const LOCK_WAIT_MS = 30_000;

/** Between two tries. */
const POLL_MS = 20;

export class TreeLockedError extends Error {}

/**
 * The pid a lock file holds; 'empty' while its taker has not written it yet; undefined when it holds
 * none of ours (garbage, another machine's, a link); null when it is gone.
 */
function holderOf(path: string): number | 'empty' | undefined | null {
    let fd: number;
    try {
        fd = openSync(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        if (code === 'ENOENT') return null;
        if (code === 'ELOOP') return undefined; // a link planted there: no lock of ours
        throw e;
    }
    try {
        const buffer = Buffer.alloc(300);
        const text = buffer.subarray(0, readSync(fd, buffer, 0, buffer.length, 0)).toString('utf8').trim();
        if (text === '') return 'empty';
        const m = /^(\d{1,10})(?: (\S{1,255}))?$/.exec(text);
        // a lock written on another machine (a src-gen committed, or copied, with one in it): its pid means nothing here
        if (!m || (m[2] !== undefined && m[2] !== hostname())) return undefined;
        return Number(m[1]);
    } finally {
        closeSync(fd);
    }
}

/** How long a lock file with no pid in it is taken for one being written, not a stale one. */
const EMPTY_LOCK_GRACE_MS = 2000;

/** Whether `path` is a regular file modified less than `ms` ago (false when it cannot be read). */
function youngerThan(path: string, ms: number): boolean {
    try {
        const st = lstatSync(path);
        return st.isFile() && Date.now() - st.mtimeMs < ms; // a link planted there is no lock being written
    } catch {
        return false;
    }
}

/** Locks this process holds, by folder (device:inode), with how many takes. */
const held = new Map<string, number>();

function folderKey(dir: string): string {
    const st = statSync(dir);
    return `${st.dev}:${st.ino}`;
}

/**
 * One try at the lock of output folder `dir` (a path; `/proc/self/fd/N` for an opened folder):
 * a release function when taken (or already held by this process), else the pid that holds it.
 */
export function tryTreeLock(dir: string): (() => void) | { holder: number | undefined } {
    const key = folderKey(dir);
    const mine = held.get(key);
    if (mine !== undefined) {
        held.set(key, mine + 1);
        return releaser(dir, key);
    }
    const path = join(dir, TREE_LOCK_NAME);
    for (let attempt = 0; attempt < 3; attempt++) {
        let fd: number | undefined;
        try {
            fd = openSync(path, constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW, 0o644);
        } catch (e) {
            if ((e as NodeJS.ErrnoException).code !== 'EEXIST') throw e;
        }
        if (fd !== undefined) {
            try {
                writeSync(fd, `${process.pid} ${hostname()}\n`);
            } finally {
                closeSync(fd);
            }
            held.set(key, 1);
            return releaser(dir, key);
        }
        const holder = holderOf(path);
        if (holder === null) continue; // released meanwhile
        if (typeof holder === 'number' && pidAlive(holder) && holder !== process.pid) return { holder };
        // a lock with no pid yet is one being written (its writer has not got to its pid): waited
        // for, unless it stays so (a writer killed between the two)
        if (holder === 'empty' && youngerThan(path, EMPTY_LOCK_GRACE_MS)) return { holder: undefined };
        // a writer killed mid-write, a lock with no pid for long, another machine's, or a lock of
        // this pid that this process does not hold (left by an earlier process of the same pid)
        try {
            unlinkSync(path);
        } catch (e) {
            if ((e as NodeJS.ErrnoException).code !== 'ENOENT') throw e;
        }
    }
    return { holder: undefined };
}

/** Releases one take; the last removes the lock file while it still holds this process's pid. */
function releaser(dir: string, key: string): () => void {
    let released = false;
    return () => {
        if (released) return;
        released = true;
        const n = held.get(key) ?? 0;
        if (n > 1) {
            held.set(key, n - 1);
            return;
        }
        held.delete(key);
        const path = join(dir, TREE_LOCK_NAME);
        try {
            if (holderOf(path) === process.pid) unlinkSync(path);
        } catch {
            // already gone (the folder removed): nothing to release
        }
    };
}

/** Who takes the lock of a generated tree, as a locked error names its holder. */
export const TREE_WRITERS = 'a contract generate or rename, or the IDE server';

function lockedError(what: string, holder: number | undefined, waitMs: number, writers: string): TreeLockedError {
    return new TreeLockedError(`${what} is being written by another process${holder !== undefined ? ` (pid ${holder}: ${writers})` : ''} for more than ${waitMs / 1000} s: try again when it has finished (or remove its ${TREE_LOCK_NAME} if no such process runs)`);
}

/** Says once, when a take has to wait, who holds the lock. */
export type LockWaitNotice = (holder: number | undefined) => void;

/**
 * The tries of a wait for the lock of `dir`, one per step: the release once taken, undefined to
 * wait POLL_MS and step again; the first blocked try tells `onWait`, one past `waitMs` throws.
 * lockTreeSync and lockTree differ only in how they wait between steps.
 */
function* lockTries(dir: string, what: string, waitMs: number, onWait: LockWaitNotice | undefined, writers: string): Generator<undefined, () => void> {
    const until = Date.now() + waitMs;
    for (let first = true; ; first = false) {
        const got = tryTreeLock(dir);
        if (typeof got === 'function') return got;
        if (first) onWait?.(got.holder);
        if (Date.now() >= until) throw lockedError(what, got.holder, waitMs, writers);
        yield undefined;
    }
}

/**
 * Takes the lock of `dir`, waiting (the thread sleeps) up to `waitMs`; `what` names the folder in
 * the error, `writers` the kinds of process that take it (another folder than a generated tree
 * can use the same lock: contract run's logs folder).
 */
export function lockTreeSync(dir: string, what: string, waitMs = LOCK_WAIT_MS, onWait?: LockWaitNotice, writers = TREE_WRITERS): () => void {
    const sleeper = new Int32Array(new SharedArrayBuffer(4));
    const tries = lockTries(dir, what, waitMs, onWait, writers);
    for (let step = tries.next(); ; step = tries.next()) {
        if (step.done) return step.value;
        Atomics.wait(sleeper, 0, 0, POLL_MS);
    }
}

/** Takes the lock of `dir`, waiting (without blocking the event loop) up to `waitMs`. */
export async function lockTree(dir: string, what: string, waitMs = LOCK_WAIT_MS, onWait?: LockWaitNotice, writers = TREE_WRITERS): Promise<() => void> {
    const tries = lockTries(dir, what, waitMs, onWait, writers);
    for (let step = tries.next(); ; step = tries.next()) {
        if (step.done) return step.value;
        await new Promise((r) => setTimeout(r, POLL_MS));
    }
}
