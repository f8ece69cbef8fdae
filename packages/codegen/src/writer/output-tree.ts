import { constants, fstatSync, closeSync, lstatSync, mkdirSync, openSync, readdirSync, readSync, renameSync, rmdirSync, unlinkSync, type Dirent, type Stats } from 'node:fs';
import { posix } from 'node:path';
import { syncFolder, writeFileAtomic } from './atomic-write.js';
import { closeQuietly, fdPath, openDirNoFollow, requireProcFd } from './dir-fd.js';
import { checkTreePath, checkTreeRoot, linkRefused, UnsafePathError } from './safe-paths.js';
import { removeStaleTemps } from './stale-temp.js';
import { lockTreeSync, tryTreeLock } from './tree-lock.js';

/**
 * Opened folders kept per tree (least recently used closed first): a generation walks its files
 * in path order, so a small cache serves nearly every access, and deep or wide trees cannot run
 * the process out of file descriptors.
 */
const MAX_OPEN_DIRS = 64;

/**
 * The output folder of one generation, seen through paths relative to it (docs/codegen.md, "What
 * generate refuses"). Each path is checked (safe-paths.ts: plain relative path), then reached
 * from an opened folder, never by its full path: the output folder is opened once with
 * O_DIRECTORY|O_NOFOLLOW, each folder below from its opened parent the same way (dir-fd.ts,
 * through /proc/self/fd/N/<name> since Node has no openat), and the last component is opened
 * with O_NOFOLLOW, created O_EXCL, or renamed/unlinked/rmdir'ed within its opened folder (these
 * act on the entry itself). A symlink anywhere on the way is refused, and swapping a folder (or
 * the output folder, or the project folder) for a link *during* a generation cannot redirect it:
 * the opened folders are the ones checked.
 *
 * Opened folders are cached during one generation; call close() at the end.
 */
export class OutputTree {
    private rootFd: number | undefined;
    /** Opened folders (relative path -> fd), in least-recently-used order. */
    private readonly dirs = new Map<string, number>();
    /** Folders whose stale temporary files were already removed (or that this generation created). */
    private readonly cleaned = new Set<string>();
    /** Listings made during this generation (reused to find stale temporary files). */
    private readonly listed = new Map<string, Dirent[]>();
    /** Opened folders written into since their last fsync: synced once, before they are closed. */
    private readonly unsynced = new Set<number>();

    constructor(readonly root: string) {
        requireProcFd();
    }

    /** Checks that the output folder is a real folder (not a link), creating it when missing, and opens it. */
    prepare(): void {
        this.openRoot(true);
    }

    /**
     * Takes the output folder's write lock (tree-lock.ts: one writer of a tree at a time, across
     * processes), waiting for another writer's; released by close().
     */
    lock(): void {
        if (this.release) return;
        const fd = this.openRoot(true)!;
        try {
            this.release = lockTreeSync(fdPath(fd), this.root);
        } catch (e) {
            // the folder removed or moved away since it was opened: said as every other write says it
            throw this.readable(e, fd, '');
        }
    }

    /**
     * One try at the output folder's write lock (for a writer that must not wait: a build's record
     * of the user code): true when taken (or already held by this process), false when another holds it.
     */
    tryLock(): boolean {
        if (this.release) return true;
        const fd = this.openRoot(true)!;
        const taken = tryTreeLock(fdPath(fd));
        if (typeof taken !== 'function') return false;
        this.release = taken;
        return true;
    }

    private release: (() => void) | undefined;

    /** Closes the opened folders and releases the lock; the tree can still be used after (folders are opened again). */
    close(): void {
        this.release?.();
        this.release = undefined;
        for (const fd of this.dirs.values()) this.syncAndClose(fd);
        this.dirs.clear();
        if (this.rootFd !== undefined) this.syncAndClose(this.rootFd);
        this.rootFd = undefined;
        this.unsynced.clear();
    }

    /** lstat of `rel` (undefined when absent); refuses a symlink anywhere on the way, `rel` included. */
    stat(rel: string): Stats | undefined {
        const at = this.entryAt(rel, false);
        if (!at) return undefined;
        let st: Stats;
        try {
            st = lstatSync(at.path);
        } catch (e) {
            if ((e as NodeJS.ErrnoException).code === 'ENOENT') return undefined;
            throw e;
        }
        if (st.isSymbolicLink()) throw linkRefused(this.root, rel, at.path);
        return st;
    }

    /**
     * The bytes of file `rel` as a latin1 byte string, or undefined when it does not exist.
     * Refuses a link (O_NOFOLLOW on the file, its folders opened O_NOFOLLOW), a folder, a FIFO or
     * a device (opened non-blocking, so a FIFO cannot hang us; fstat on the opened file decides).
     */
    read(rel: string, maxBytes = Number.POSITIVE_INFINITY): string | undefined {
        const at = this.entryAt(rel, false);
        if (!at) return undefined;
        let fd: number;
        try {
            fd = openSync(at.path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
        } catch (e) {
            const code = (e as NodeJS.ErrnoException).code;
            if (code === 'ELOOP') throw linkRefused(this.root, rel, at.path);
            if (code === 'ENOENT') return undefined;
            throw e;
        }
        try {
            const st = fstatSync(fd);
            if (!st.isFile()) throw new UnsafePathError(`${rel} is not a regular file: refused`);
            if (st.size > maxBytes) throw new UnsafePathError(`${rel} is larger than ${maxBytes} bytes: refused`);
            return readAll(fd, st.size).toString('latin1');
        } finally {
            closeSync(fd);
        }
    }

    /** Entries of folder `rel` ('' = the output folder), or undefined when it does not exist. */
    list(rel: string): Dirent[] | undefined {
        const fd = this.dirFd(rel === '' ? '' : checkTreePath(rel), false, rel);
        if (fd === undefined) return undefined;
        const entries = readdirSync(fdPath(fd), { withFileTypes: true });
        this.listed.set(rel, entries);
        return entries;
    }

    /** Writes file `rel` atomically within its opened folder, made one by one; first removes stale temp files there. */
    write(rel: string, data: Buffer): void {
        const at = this.entryAt(rel, true)!;
        const dirPath = fdPath(at.dirFd);
        try {
            if (!this.cleaned.has(at.dir)) {
                removeStaleTemps(dirPath, this.listed.get(at.dir));
                this.cleaned.add(at.dir);
            }
            writeFileAtomic(dirPath, at.name, data, { syncDir: false });
            this.unsynced.add(at.dirFd);
        } catch (e) {
            throw this.readable(e, at.dirFd, at.dir);
        }
    }

    /**
     * `e` with the /proc/self/fd path of opened folder `dir` shown as the folder: for a write, ENOENT
     * there means the folder itself was removed (or replaced, then removed) since it was opened.
     */
    private readable(e: unknown, fd: number, dir: string, enoentIsVanished = true): unknown {
        const err = e as NodeJS.ErrnoException;
        if (typeof err?.message !== 'string' || !err.message.includes(fdPath(fd))) return e;
        if (err.code === 'ENOENT' && enoentIsVanished) return vanished(dir === '' ? this.root : dir);
        err.message = err.message.split(fdPath(fd)).join(dir === '' ? this.root : posix.join(this.root, dir));
        return err;
    }

    /** Deletes file `rel` (never what a link points to); false when it was not there. */
    remove(rel: string): boolean {
        const st = this.stat(rel);
        if (!st) return false;
        if (!st.isFile()) throw new UnsafePathError(`${rel} is not a regular file: refused`);
        try {
            unlinkSync(this.entryAt(rel, false)!.path);
        } catch (e) {
            if ((e as NodeJS.ErrnoException).code === 'ENOENT') return false; // removed meanwhile
            throw e;
        }
        return true;
    }

    /**
     * Renames entry `from` of folder `dir` ('' = the output folder) to `to` within that opened
     * folder (rename acts on the entry itself, a link included); replaces an existing `to`
     * like rename(2), so callers check first.
     */
    rename(dir: string, from: string, to: string): void {
        if (from.includes('/') || to.includes('/')) throw new UnsafePathError(`rename within one folder only: ${from} -> ${to}`);
        const fromRel = dir === '' ? checkTreePath(from) : checkTreePath(`${dir}/${from}`);
        const toRel = dir === '' ? checkTreePath(to) : checkTreePath(`${dir}/${to}`);
        const fd = this.dirFd(dir === '' ? '' : checkTreePath(dir), false, fromRel);
        if (fd === undefined) throw new UnsafePathError(`${dir} does not exist: ${fromRel} not renamed`);
        this.forget(fromRel);
        this.forget(toRel);
        try {
            renameSync(fdPath(fd, from), fdPath(fd, to));
        } catch (e) {
            throw this.readable(e, fd, dir, false);
        }
    }

    /** Removes the now-empty real folders above `rel`, up to (excluding) the output folder and `keep`. */
    pruneEmptyDirs(rel: string, keep: (dir: string) => boolean): void {
        for (let dir = posix.dirname(rel); dir !== '.' && dir !== '' && !keep(dir); dir = posix.dirname(dir)) {
            try {
                const at = this.entryAt(dir, false);
                if (!at) return;
                // opened (not cached) to look inside: an empty real folder, not a link, is removed
                const opened = openDirNoFollow(at.path, false);
                if (!('fd' in opened)) return;
                let empty: boolean;
                try {
                    empty = readdirSync(fdPath(opened.fd)).length === 0;
                } finally {
                    closeSync(opened.fd);
                }
                if (!empty) return;
                this.forget(dir);
                rmdirSync(at.path);
            } catch {
                return;
            }
        }
    }

    /**
     * Where entry `rel` is: its opened folder (made when `create`), its name there and the
     * /proc/self/fd path naming it; undefined when a folder on the way does not exist.
     */
    private entryAt(rel: string, create: boolean): { dir: string; dirFd: number; name: string; path: string } | undefined {
        const parent = posix.dirname(checkTreePath(rel));
        const dir = parent === '.' ? '' : parent;
        const dirFd = this.dirFd(dir, create, rel);
        if (dirFd === undefined) return undefined;
        const name = posix.basename(rel);
        return { dir, dirFd, name, path: fdPath(dirFd, name) };
    }

    /**
     * The opened folder `rel` ('' = the output folder), opened from its opened parent when not
     * cached (made when `create`); undefined when missing. A link or a non-folder on the way is an
     * UnsafePathError naming it (`target`: the path asked for, shown in the message).
     */
    private dirFd(rel: string, create: boolean, target: string): number | undefined {
        if (rel === '') return this.openRoot(create);
        const cached = this.dirs.get(rel);
        if (cached !== undefined) {
            this.dirs.delete(rel); // most recently used last
            this.dirs.set(rel, cached);
            return cached;
        }
        const parent = posix.dirname(rel);
        const parentFd = this.dirFd(parent === '.' ? '' : parent, create, target);
        if (parentFd === undefined) return undefined;
        const path = fdPath(parentFd, posix.basename(rel));
        const opened = openDirNoFollow(path, create);
        if ('fd' in opened) {
            if (opened.created) this.cleaned.add(rel); // new and empty: no stale temporary file
            this.remember(rel, opened.fd);
            return opened.fd;
        }
        if (opened.kind === 'missing') return undefined;
        if (opened.kind === 'link') throw linkRefused(this.root, rel, path);
        if (opened.kind === 'changing') throw changing(rel);
        if (opened.kind === 'gone') throw vanished(parent === '.' ? this.root : parent);
        throw new UnsafePathError(rel === target ? `${rel} is not a folder` : `${rel} is not a folder (on the way to ${target})`);
    }

    private remember(rel: string, fd: number): void {
        this.dirs.set(rel, fd);
        if (this.dirs.size <= MAX_OPEN_DIRS) return;
        const [oldest, oldFd] = this.dirs.entries().next().value as [string, number];
        this.dirs.delete(oldest);
        this.syncAndClose(oldFd);
    }

    /** Closes an opened folder, first making the renames done in it durable when it was written into. */
    private syncAndClose(fd: number): void {
        if (this.unsynced.delete(fd)) syncFolder(fdPath(fd));
        closeQuietly(fd);
    }

    /** Closes the cached folders `rel` and below (it is being removed). */
    private forget(rel: string): void {
        for (const [dir, fd] of [...this.dirs]) {
            if (dir === rel || dir.startsWith(`${rel}/`)) {
                this.dirs.delete(dir);
                this.unsynced.delete(fd);
                closeQuietly(fd);
            }
        }
        this.cleaned.delete(rel);
    }

    /**
     * The opened output folder: checked to be a real folder (not a link; made when missing and
     * `create`), then opened O_DIRECTORY|O_NOFOLLOW, so a swap between the check and the open is
     * refused too. Undefined when missing. The folders above it are the user's choice.
     */
    private openRoot(create: boolean): number | undefined {
        if (this.rootFd !== undefined) return this.rootFd;
        if (!checkTreeRoot(this.root)) {
            if (!create) return undefined;
            try {
                mkdirSync(this.root, { recursive: true });
            } catch (e) {
                // a folder above it is being moved (ENOENT), or a link appeared at it (EEXIST, ENOTDIR)
                const code = (e as NodeJS.ErrnoException).code;
                if (code === 'ENOENT' || code === 'EEXIST' || code === 'ENOTDIR') throw changing(this.root);
                throw e;
            }
        }
        const opened = openDirNoFollow(this.root, create);
        if ('fd' in opened) {
            this.rootFd = opened.fd;
            return opened.fd;
        }
        if (opened.kind === 'missing') return undefined;
        if (opened.kind === 'link') throw linkRefused(this.root, '');
        if (opened.kind === 'changing' || opened.kind === 'gone') throw changing(this.root);
        throw new UnsafePathError(`${this.root} is not a folder`);
    }
}

function vanished(shown: string): UnsafePathError {
    return new UnsafePathError(`${shown} was removed or moved while the generator was writing into it (another process is changing the tree): refused`);
}

function changing(shown: string): UnsafePathError {
    return new UnsafePathError(`${shown} kept changing while being opened (another process is moving or replacing it): refused`);
}

/**
 * The whole content of an opened regular file. `size` (from fstat) is a hint: one byte more is
 * asked for, so a short read (EOF, for a regular file) ends it in one call; a grown file is read on.
 */
function readAll(fd: number, size: number): Buffer {
    const chunks: Buffer[] = [];
    let total = 0;
    for (;;) {
        const buf = Buffer.allocUnsafe(Math.max(size - total, 0) + 1);
        const n = readSync(fd, buf, 0, buf.length, null);
        chunks.push(buf.subarray(0, n));
        total += n;
        if (n < buf.length) break;
    }
    return chunks.length === 1 ? chunks[0]! : Buffer.concat(chunks, total);
}
