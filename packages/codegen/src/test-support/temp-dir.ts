import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, posix } from 'node:path';
import { afterEach } from 'vitest';

/** A fresh temporary folder; call the returned cleanup when done. */
export function tempDir(prefix = 'codegen-'): { dir: string; cleanup: () => void } {
    const dir = mkdtempSync(join(tmpdir(), prefix));
    return { dir, cleanup: () => rmSync(dir, { recursive: true, force: true }) };
}

/**
 * For a test file: `out()` gives a fresh temporary folder, and every folder it gave is removed
 * after each test.
 */
export function scratchDirs(prefix?: string): () => string {
    let cleanups: Array<() => void> = [];
    afterEach(() => {
        cleanups.forEach((c) => c());
        cleanups = [];
    });
    return () => {
        const t = tempDir(prefix);
        cleanups.push(t.cleanup);
        return t.dir;
    };
}

/** Every file under `root` (relative '/'-paths, sorted) with its bytes as a latin1 string. */
export function readTree(root: string, rel = ''): Map<string, string> {
    const out = new Map<string, string>();
    const walk = (r: string) => {
        for (const e of readdirSync(join(root, r), { withFileTypes: true })) {
            const child = r ? posix.join(r, e.name) : e.name;
            if (e.isDirectory()) walk(child);
            else out.set(child, readFileSync(join(root, child), 'latin1'));
        }
    };
    if (existsSync(join(root, rel))) walk(rel);
    return new Map([...out.entries()].sort(([a], [b]) => (a < b ? -1 : 1)));
}
