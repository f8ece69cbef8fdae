import { closeSync, constants, existsSync, lstatSync, mkdirSync, openSync, type Stats } from 'node:fs';

/**
 * Folder-relative file access without openat(2), which Node lacks (docs/codegen.md, "What
 * generate refuses"). A folder is opened once (O_DIRECTORY|O_NOFOLLOW) and its entries are then
 * named as /proc/self/fd/N/<name>: the kernel resolves <name> inside the opened folder, whatever
 * path that folder has now, so swapping a folder on the way for a symlink after it was opened
 * cannot redirect an access. Each step opens one component, never following a link.
 */
export const PROC_FD = '/proc/self/fd';

/** The path naming entry `name` of opened folder `fd` (the folder itself when `name` is ''). */
export function fdPath(fd: number, name = ''): string {
    return name === '' ? `${PROC_FD}/${fd}` : `${PROC_FD}/${fd}/${name}`;
}

/** Throws unless /proc/self/fd is there (Linux): without it, folder-relative access is impossible. */
export function requireProcFd(): void {
    if (!existsSync(PROC_FD)) throw new Error(`the generator needs ${PROC_FD} (Linux) to write output trees safely`);
}

const DIR_FLAGS = constants.O_RDONLY | constants.O_DIRECTORY | constants.O_NOFOLLOW;

/** What is at a path that could not be opened as a folder: a symlink, something else, or nothing. */
export type NotAFolder = { kind: 'link' } | { kind: 'other'; stats: Stats } | { kind: 'missing' } | { kind: 'changing' } | { kind: 'gone' };

/** The outcome of opening one folder: its fd, or why not. */
export type DirOpen = { fd: number; created: boolean } | NotAFolder;

function lstatOrUndefined(path: string): Stats | undefined {
    try {
        return lstatSync(path);
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        if (code === 'ENOENT' || code === 'ENOTDIR') return undefined;
        throw e;
    }
}

/**
 * Opens the folder at `path` (for a child: fdPath(parentFd, name)) without following a link at
 * its last component. With `create`, a missing folder is made first (mkdir never follows a link
 * at its last component, EEXIST then), and the open is retried. A few retries absorb an entry
 * that changes between the failed open and the lstat telling why; an entry still changing after
 * them is 'changing' (another process keeps moving it); 'gone' when the opened folder it is made
 * in was removed meanwhile.
 */
export function openDirNoFollow(path: string, create: boolean): DirOpen {
    let created = false;
    for (let attempt = 0; ; attempt++) {
        try {
            return { fd: openSync(path, DIR_FLAGS), created };
        } catch (e) {
            const code = (e as NodeJS.ErrnoException).code;
            if (code === 'ENOENT') {
                if (!create) return { kind: 'missing' };
                if (attempt >= 3) return { kind: 'changing' };
                try {
                    mkdirSync(path);
                    created = true;
                } catch (m) {
                    const mcode = (m as NodeJS.ErrnoException).code;
                    if (mcode === 'ENOENT') return { kind: 'gone' };
                    if (mcode !== 'EEXIST') throw m;
                }
                continue;
            }
            // O_DIRECTORY|O_NOFOLLOW on a symlink fails ENOTDIR on Linux (ELOOP elsewhere): look
            if (code !== 'ENOTDIR' && code !== 'ELOOP') throw e;
            const st = lstatOrUndefined(path);
            if (st?.isSymbolicLink()) return { kind: 'link' };
            if (st && !st.isDirectory()) return { kind: 'other', stats: st };
            if (attempt >= 3) return { kind: 'changing' };
            // gone, or a real folder again: it changed meanwhile, open again
        }
    }
}

/** Closes `fd`, ignoring an fd already closed. */
export function closeQuietly(fd: number): void {
    try {
        closeSync(fd);
    } catch {
        // already closed
    }
}
