/**
 * Confined imports (loadWorkspace's `confineImportsTo`): a service that loads an untrusted project
 * (the build service, docs/sandbox.md "Imports stay in the project") must not read host files
 * through `import "..."`. An import is loaded only when it stays lexically inside the root (no `..`
 * escape, no absolute path), no component below the root is a symbolic link, and the target is a
 * regular file of at most `maxBytes`. The path is refused before anything is looked up outside the
 * root, so a refusal says nothing about the host's files; the file is opened with O_NOFOLLOW and
 * O_NONBLOCK (a FIFO put there after the check cannot make the loader wait) and checked again
 * with fstat on the open descriptor.
 */
import { closeSync, constants, fstatSync, lstatSync, openSync, readSync } from 'node:fs';
import { dirname, isAbsolute, relative, resolve, sep } from 'node:path';

/** Default bound of one imported file (the build service's whole model is bounded lower, by modelBytes). */
export const DEFAULT_MAX_IMPORT_BYTES = 8 * 1024 * 1024;

export type ConfinedImport =
    | { kind: 'ok'; path: string; text: string }
    /** Inside the root but absent: left to the validator's `import-missing-file`. */
    | { kind: 'missing'; path: string }
    | { kind: 'refused'; reason: string };

/** Why `importPath` (written in `fromFile`) may not be used under `root`, from its text alone; undefined when it may. */
export function lexicalRefusal(root: string, fromFile: string, importPath: string): string | undefined {
    if (isAbsolute(importPath)) return 'absolute import paths are not allowed here; use a path relative to the importing file';
    const rel = relative(root, resolve(dirname(fromFile), importPath));
    if (rel === '' || rel === '..' || rel.startsWith(`..${sep}`) || isAbsolute(rel)) return 'it leads outside the project folder';
    return undefined;
}

/** Where `importPath` (written in the file `fromFile`) leads, if the confinement to `root` allows it. */
export function resolveConfinedImport(root: string, fromFile: string, importPath: string, maxBytes = DEFAULT_MAX_IMPORT_BYTES): ConfinedImport {
    const lexical = lexicalRefusal(root, fromFile, importPath);
    if (lexical) return { kind: 'refused', reason: lexical };
    const target = resolve(dirname(fromFile), importPath);
    const rel = relative(root, target);
    // every component below the root, with lstat: a link anywhere on the way would lead elsewhere
    const parts = rel.split(sep);
    let current = root;
    for (let i = 0; i < parts.length; i++) {
        current = `${current}${sep}${parts[i]}`;
        let st;
        try {
            st = lstatSync(current);
        } catch {
            return { kind: 'missing', path: target };
        }
        if (st.isSymbolicLink()) return { kind: 'refused', reason: `${parts.slice(0, i + 1).join('/')} is a symbolic link` };
        if (i < parts.length - 1 && !st.isDirectory()) return { kind: 'missing', path: target };
        if (i === parts.length - 1 && !st.isFile()) return { kind: 'refused', reason: 'it is not a regular file' };
    }
    return readBounded(target, maxBytes);
}

function readBounded(path: string, maxBytes: number): ConfinedImport {
    let fd: number;
    try {
        fd = openSync(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        if (code === 'ENOENT') return { kind: 'missing', path };
        return { kind: 'refused', reason: code === 'ELOOP' ? 'it is a symbolic link' : `it cannot be opened (${code ?? 'error'})` };
    }
    try {
        const st = fstatSync(fd);
        if (!st.isFile()) return { kind: 'refused', reason: 'it is not a regular file' };
        if (st.size > maxBytes) return { kind: 'refused', reason: `it is larger than ${maxBytes} bytes` };
        // read at most maxBytes + 1: a file growing after the fstat still cannot exceed the bound
        const buf = Buffer.alloc(st.size + 1);
        let n = 0;
        for (let got; n < buf.length && (got = readSync(fd, buf, n, buf.length - n, null)) > 0;) n += got;
        if (n > maxBytes) return { kind: 'refused', reason: `it is larger than ${maxBytes} bytes` };
        return { kind: 'ok', path, text: buf.subarray(0, n).toString('utf8') };
    } finally {
        closeSync(fd);
    }
}
