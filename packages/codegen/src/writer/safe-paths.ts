import { lstatSync, readlinkSync, type Stats } from 'node:fs';
import { join } from 'node:path';

/**
 * Path rules for everything the generator reads, writes or deletes in an output tree
 * (docs/codegen.md, "What generate refuses"). The paths come from files of the project folder
 * (the manifest, the generated tree itself), which is untrusted input: a path is acted on only
 * when it is a plain relative path inside the tree, and no component on the way is a link.
 */

/** A path of an output tree that the generator refuses to act on; `link` names the symlink met, if any. */
export class UnsafePathError extends Error {
    constructor(message: string, readonly link?: string) {
        super(message);
        this.name = 'UnsafePathError';
    }
}

const MAX_PATH = 4096;
const MAX_COMPONENT = 255;

/**
 * Why `rel` is not a plain relative '/'-separated path inside a tree, or undefined when it is one:
 * not a string, empty, too long, a control character (NUL included: the OS would cut the path
 * there; a newline would forge report lines), a backslash, absolute, or an empty, `.` or `..`
 * component.
 */
export function treePathProblem(rel: unknown): string | undefined {
    if (typeof rel !== 'string') return 'not a string';
    if (rel.length === 0) return 'empty path';
    if (rel.length > MAX_PATH) return `longer than ${MAX_PATH} characters`;
    if (/[\u0000-\u001f\u007f]/.test(rel)) return 'control character (NUL, newline...) in the path';
    if (rel.includes('\\')) return 'backslash in the path';
    if (rel.startsWith('/')) return 'absolute path';
    for (const part of rel.split('/')) {
        if (part === '' || part === '.' || part === '..') return `empty, "." or ".." component`;
        if (part.length > MAX_COMPONENT) return `component longer than ${MAX_COMPONENT} characters`;
    }
    return undefined;
}

/** `rel` when it is a plain relative path inside a tree (see treePathProblem), else an UnsafePathError. */
export function checkTreePath(rel: unknown): string {
    const problem = treePathProblem(rel);
    if (problem) throw new UnsafePathError(`refused path ${JSON.stringify(rel)}: ${problem}`);
    return rel as string;
}

function lstatOrUndefined(abs: string): Stats | undefined {
    try {
        return lstatSync(abs);
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        if (code === 'ENOENT' || code === 'ENOTDIR') return undefined;
        throw e;
    }
}

function linkTarget(abs: string): string {
    try {
        return readlinkSync(abs);
    } catch {
        return '?';
    }
}

/**
 * The error for a symlink met at `link` (relative to the tree `root`, '' for the root itself);
 * `at`: the path to read the link from when it is not root/link (a /proc/self/fd path, dir-fd.ts).
 */
export function linkRefused(root: string, link: string, at?: string): UnsafePathError {
    const shown = link === '' ? root : link;
    return new UnsafePathError(
        `${shown} is a symbolic link (-> ${linkTarget(at ?? (link === '' ? root : join(root, link)))}): refused, the generator never reads, writes or deletes through a link`,
        link,
    );
}

/**
 * The output folder itself: a real folder (lstat, so not a symlink to one), or absent. Returns
 * whether it exists. The folders above it are the user's choice (the project folder).
 */
export function checkTreeRoot(root: string): boolean {
    const st = lstatOrUndefined(root);
    if (!st) return false;
    if (st.isSymbolicLink()) throw linkRefused(root, '');
    if (!st.isDirectory()) throw new UnsafePathError(`${root} is not a folder`);
    return true;
}

/**
 * lstat of `root/rel` after checking, with lstat, every folder on the way from `root` down: each
 * must be a real folder. Returns undefined when a component does not exist. The last component
 * may be anything but a symlink (the caller checks its type); a symlink anywhere is an
 * UnsafePathError naming it. `verified` caches folders already checked during one tree write.
 */
export function lstatInTree(root: string, rel: string, verified?: Set<string>): Stats | undefined {
    const parts = checkTreePath(rel).split('/');
    let current = '';
    for (let i = 0; i < parts.length; i++) {
        current = current ? `${current}/${parts[i]}` : parts[i]!;
        const last = i === parts.length - 1;
        if (!last && verified?.has(current)) continue;
        const st = lstatOrUndefined(join(root, current));
        if (!st) return undefined;
        if (st.isSymbolicLink()) throw linkRefused(root, current);
        if (last) return st;
        if (!st.isDirectory()) throw new UnsafePathError(`${current} is not a folder (on the way to ${rel})`);
        verified?.add(current);
    }
    return undefined;
}
