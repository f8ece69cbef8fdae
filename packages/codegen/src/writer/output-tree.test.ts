/**
 * OutputTree reaches entries from opened folders, not by path (docs/codegen.md, "What generate
 * refuses"): a folder swapped for a symlink after it was opened is not followed. Deterministic
 * counterpart of write-tree.race.test.ts: the swap happens between two operations.
 */
import { afterEach, describe, expect, it } from 'vitest';
import { existsSync, mkdirSync, readdirSync, readFileSync, renameSync, symlinkSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { tempDir } from '../test-support/temp-dir.js';
import { OutputTree } from './output-tree.js';
import { UnsafePathError } from './safe-paths.js';
import { writeTree } from './write-tree.js';

let cleanups: Array<() => void> = [];
afterEach(() => {
    const now = cleanups;
    cleanups = [];
    now.forEach((c) => c());
});
function base(): { root: string; outside: string } {
    const t = tempDir();
    cleanups.push(t.cleanup);
    mkdirSync(join(t.dir, 'outside'));
    writeFileSync(join(t.dir, 'outside', 'a.c'), 'OUTSIDE');
    return { root: join(t.dir, 'proj', 'src-gen'), outside: join(t.dir, 'outside') };
}
const openFds = () => readdirSync('/proc/self/fd').length;

describe('OutputTree against a folder swapped for a symlink after it was opened', () => {
    it('keeps using the opened folder inside src-gen: writes, reads, deletes and renames never go through the link', () => {
        const { root, outside } = base();
        const tree = new OutputTree(root);
        cleanups.unshift(() => tree.close());
        tree.prepare();
        tree.write('generated/a.c', Buffer.from('inside'));
        renameSync(join(root, 'generated'), join(root, 'generated.moved'));
        symlinkSync(outside, join(root, 'generated'));

        tree.write('generated/b.c', Buffer.from('new'));
        expect(tree.read('generated/a.c')).toBe('inside');
        expect(tree.list('generated')?.map((e) => e.name).sort()).toEqual(['a.c', 'b.c']);
        expect(readdirSync(outside)).toEqual(['a.c']);
        tree.rename('generated', 'b.c', 'c.c');
        expect(tree.remove('generated/a.c')).toBe(true);

        expect(readdirSync(outside)).toEqual(['a.c']);
        expect(readFileSync(join(outside, 'a.c'), 'utf8')).toBe('OUTSIDE');
        expect(readdirSync(join(root, 'generated.moved'))).toEqual(['c.c']);
    });

    it('keeps using the opened src-gen when src-gen itself is swapped', () => {
        const { root, outside } = base();
        const tree = new OutputTree(root);
        cleanups.unshift(() => tree.close());
        tree.prepare();
        renameSync(root, `${root}.moved`);
        symlinkSync(outside, root);

        tree.write('a.c', Buffer.from('inside'));
        tree.write('generated/x.c', Buffer.from('inside'));

        expect(readFileSync(join(outside, 'a.c'), 'utf8')).toBe('OUTSIDE');
        expect(existsSync(join(outside, 'generated'))).toBe(false);
        expect(readFileSync(join(`${root}.moved`, 'a.c'), 'utf8')).toBe('inside');
    });

    it('refuses the link once the opened folders are closed (a later generation meets it)', () => {
        const { root, outside } = base();
        const tree = new OutputTree(root);
        tree.prepare();
        tree.write('generated/a.c', Buffer.from('inside'));
        renameSync(join(root, 'generated'), join(root, 'generated.moved'));
        symlinkSync(outside, join(root, 'generated'));
        tree.close();
        expect(() => tree.write('generated/b.c', Buffer.from('x'))).toThrow(UnsafePathError);
        expect(() => tree.read('generated/a.c')).toThrow(/^generated is a symbolic link \(-> .*outside\): refused/);
        tree.close();
        expect(readdirSync(outside)).toEqual(['a.c']);
    });

    it('writeTree closes every folder it opened', () => {
        const { root } = base();
        const files = Array.from({ length: 100 }, (_, i) => ({ path: `generated/d${i % 80}/f${i}.c`, content: `// ${i}\n` }));
        writeTree(root, files);
        const before = openFds();
        writeTree(root, files);
        writeTree(root, files.slice(0, 10));
        expect(openFds()).toBe(before);
    });
});
