import { existsSync, readFileSync, rmSync, statSync, utimesSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it, vi } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { MANIFEST_NAME } from './manifest.js';
import { OutputTree } from './output-tree.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

/** A fresh output folder per call, removed after each test. */
const out = scratchDirs();

const file = (path: string, ...ids: string[]): GeneratedFile => ({
    path,
    content: `// ${path}\n` + ids.map((id) => `code_${id}();\n${region(id, '\n//TODO\n')}\n`).join(''),
});
function edit(dir: string, path: string, id: string, text: string): void {
    const abs = join(dir, path);
    const src = readFileSync(abs, 'utf8');
    const re = new RegExp(`(ID\\(${id}\\) ENABLED START\\*/)[\\s\\S]*?(/\\*PROTECTED REGION END)`);
    writeFileSync(abs, src.replace(re, (_m, a: string, b: string) => a + text + b));
}

/** The folders writeTree lists (OutputTree.list), in order, while it writes `files` into `dir`. */
function listedWhileWriting(dir: string, files: GeneratedFile[]): string[] {
    const spy = vi.spyOn(OutputTree.prototype, 'list');
    try {
        writeTree(dir, files);
        return spy.mock.calls.map(([rel]) => rel);
    } finally {
        spy.mockRestore();
    }
}

describe('writeTree: folders listed', () => {
    const tree = [file('generated/a.c', 'x'), file('generated/sub/b.h', 'y'), file('generated/sub/deep/c.c', 'z'), file('generated/other/d.c', 'w')];

    it('a new tree: only the generated folder is looked for (missing: nothing under it is listed)', () => {
        expect(listedWhileWriting(out(), tree)).toEqual(['generated']);
    });

    it('a tree without its manifest: each folder listed once, by the search for files of deleted entities', () => {
        const dir = out();
        writeTree(dir, tree);
        rmSync(join(dir, MANIFEST_NAME));
        const listed = listedWhileWriting(dir, [...tree, file('generated/sub/new/e.c', 'v')]);
        expect([...listed].sort()).toEqual(['generated', 'generated/other', 'generated/sub', 'generated/sub/deep']);
    });

    it('a tree with its manifest: each folder of a generated file listed once, to know which files exist', () => {
        const dir = out();
        writeTree(dir, tree);
        expect([...listedWhileWriting(dir, tree)].sort()).toEqual(['generated', 'generated/other', 'generated/sub', 'generated/sub/deep']);
    });
});

describe('writeTree', () => {
    it('creates files, then rewrites nothing when regenerated unchanged (mtime stays)', () => {
        const dir = out();
        const files = [file('generated/a.c', 'x', 'y'), file('generated/sub/b.h', 'z')];
        const first = writeTree(dir, files);
        expect(first.created).toEqual(['generated/a.c', 'generated/sub/b.h']);
        const past = new Date('2020-01-01T00:00:00Z');
        utimesSync(join(dir, 'generated/a.c'), past, past);
        const second = writeTree(dir, files);
        expect(second.filesWritten).toBe(0);
        expect(second.unchanged).toEqual(['generated/a.c', 'generated/sub/b.h']);
        expect(statSync(join(dir, 'generated/a.c')).mtime.getTime()).toBe(past.getTime());
    });

    it('keeps user code across a regeneration that changes the surrounding code', () => {
        const dir = out();
        writeTree(dir, [file('generated/a.c', 'x', 'y')]);
        edit(dir, 'generated/a.c', 'y', 'int mine = 1;');
        const r = writeTree(dir, [file('generated/a.c', 'w', 'y', 'x')]);
        expect(r.updated).toEqual(['generated/a.c']);
        expect(readFileSync(join(dir, 'generated/a.c'), 'utf8')).toContain(region('y', 'int mine = 1;'));
    });

    it('moves user code of a vanished region to orphans/, numbering later orphans of the same file', () => {
        const dir = out();
        writeTree(dir, [file('generated/a.c', 'x', 'y')]);
        edit(dir, 'generated/a.c', 'y', 'first();');
        const r1 = writeTree(dir, [file('generated/a.c', 'x')]);
        expect(r1.orphaned).toEqual(['orphans/generated/a.c']);
        expect(r1.warnings[0]!.message).toMatch(/protected region\(s\) y moved to orphans\/generated\/a\.c/);
        expect(readFileSync(join(dir, 'orphans/generated/a.c'), 'utf8')).toContain(region('y', 'first();'));
        writeTree(dir, [file('generated/a.c', 'x', 'y')]);
        edit(dir, 'generated/a.c', 'y', 'second();');
        const r2 = writeTree(dir, [file('generated/a.c', 'x')]);
        expect(r2.orphaned).toEqual(['orphans/generated/a.2.c']);
        expect(readFileSync(join(dir, 'orphans/generated/a.c'), 'utf8')).toContain('first();');
        expect(readFileSync(join(dir, 'orphans/generated/a.2.c'), 'utf8')).toContain('second();');
    });

    it('does not orphan a vanished region that holds a non-TODO generated default', () => {
        const dir = out();
        const withDefault = (ids: string[]): GeneratedFile => ({
            path: 'generated/t.h',
            content: ids.map((id) => region(id, `return ${id.length};`)).join('\n'),
        });
        writeTree(dir, [withDefault(['eq', 'diff'])]);
        const r = writeTree(dir, [withDefault(['eq'])]);
        expect(r.orphaned).toEqual([]);
        expect(r.updated).toEqual(['generated/t.h']);
    });

    it('a region still holding a default the generator changed since is kept, and stays no user code (not recorded as such, not orphaned)', () => {
        const dir = out();
        const reacting = (body: string, regions = true): GeneratedFile => ({
            path: 'generated/m.c',
            content: `void react(int port){\n${regions ? region('protect_event_M', body) : ''}\n}\n`,
        });
        const before = '\n(void)port;\n//TODO\n';
        writeTree(dir, [reacting(before)]);
        // the newer generator's default lost the cast: the region keeps the old one, byte for byte
        writeTree(dir, [reacting('\n//TODO\n')]);
        expect(readFileSync(join(dir, 'generated/m.c'), 'utf8')).toBe(reacting(before).content);
        const manifest = JSON.parse(readFileSync(join(dir, MANIFEST_NAME), 'utf8')) as { userCode?: unknown };
        expect(manifest.userCode).toEqual({}); // written (an older manifest is told apart by its absence), holding none
        // still the generator's the time after, and when the region goes
        expect(writeTree(dir, [reacting('\n//TODO\n')]).filesWritten).toBe(0);
        const gone = writeTree(dir, [reacting('', false)]);
        expect([gone.orphaned, gone.warnings]).toEqual([[], []]);
    });

    it('moves a deleted entity file holding user code to orphans/ and removes one without user code', () => {
        const dir = out();
        writeTree(dir, [file('generated/m/A.c', 'x'), file('generated/n/B.c', 'x'), file('generated/k.c', 'x')]);
        edit(dir, 'generated/m/A.c', 'x', 'keep_me();');
        const r = writeTree(dir, [file('generated/k.c', 'x')]);
        expect(r.orphaned).toEqual(['orphans/generated/m/A.c']);
        expect(r.removed).toEqual(['generated/n/B.c']);
        expect(existsSync(join(dir, 'generated/m'))).toBe(false);
        expect(existsSync(join(dir, 'generated/n'))).toBe(false);
        expect(readFileSync(join(dir, 'orphans/generated/m/A.c'), 'utf8')).toContain('keep_me();');
    });

    it('leaves a malformed file untouched with file and line, and still writes the rest', () => {
        const dir = out();
        writeTree(dir, [file('generated/a.c', 'x'), file('generated/b.c', 'x')]);
        const broken = '// broken\n/*PROTECTED REGION ID(x) ENABLED START*/\nuser code with no end\n';
        writeFileSync(join(dir, 'generated/a.c'), broken);
        const r = writeTree(dir, [file('generated/a.c', 'x', 'y'), file('generated/b.c', 'x', 'y'), file('generated/c.c', 'x')]);
        expect(r.errors).toEqual([{ file: 'generated/a.c', line: 2, message: expect.stringMatching(/START without END; left untouched/) }]);
        expect(readFileSync(join(dir, 'generated/a.c'), 'utf8')).toBe(broken);
        expect(r.updated).toEqual(['generated/b.c']);
        expect(r.created).toEqual(['generated/c.c']);
    });

    it('recognises user code without a manifest (tree from the original tool) and keeps it', () => {
        const dir = out();
        writeTree(dir, [file('generated/old.c', 'x', 'y')]);
        edit(dir, 'generated/old.c', 'x', 'legacy();');
        writeFileSync(join(dir, '.contract-manifest.json'), '{ not json');
        const r = writeTree(dir, [file('generated/new.c', 'x')]);
        expect(r.warnings.map((w) => w.file)).toContain('.contract-manifest.json');
        expect(r.orphaned).toEqual(['orphans/generated/old.c']);
        expect(readFileSync(join(dir, 'orphans/generated/old.c'), 'utf8')).toContain('legacy();');
    });
});

describe('writeTree: a CRLF checkout (core.autocrlf=true)', () => {
    it('does not rewrite a manifest whose only difference is its CRLF line endings, and keeps them when it changes', () => {
        const dir = out();
        const files = [file('generated/a.c', 'x')];
        writeTree(dir, files);
        const path = join(dir, MANIFEST_NAME);
        const crlf = readFileSync(path, 'utf8').replace(/\n/g, '\r\n');
        writeFileSync(path, crlf);
        expect(writeTree(dir, files).filesWritten).toBe(0);
        expect(readFileSync(path, 'utf8')).toBe(crlf);
        writeTree(dir, [...files, file('generated/b.c', 'y')]);
        const changed = readFileSync(path, 'utf8');
        expect(changed).toContain('generated/b.c');
        expect(changed.replace(/\r\n/g, '')).not.toContain('\n');
    });
});

describe('writeTree: a file derived from the tree as written', () => {
    /** A file listing what `a.c`'s region holds and what `user.h` (not generated) holds. */
    const derived: GeneratedFile = {
        path: 'generated/A.list',
        content: 'fresh\n',
        derive: (textOf) => `a.c: ${/START\*\/([\s\S]*?)\/\*PROTECTED/.exec(textOf('generated/a.c') ?? '')?.[1]?.trim()}\nuser.h: ${textOf('generated/user.h') ?? 'none'}\n`,
    };

    it('is written after the others, from their text with the regions merged and from the user\'s files; then left alone while they stay', () => {
        const dir = out();
        writeTree(dir, [file('generated/a.c', 'x'), derived]);
        expect(readFileSync(join(dir, 'generated/A.list'), 'utf8')).toBe('a.c: //TODO\nuser.h: none\n');
        edit(dir, 'generated/a.c', 'x', '\nmine();\n');
        writeFileSync(join(dir, 'generated/user.h'), 'int u;');
        const report = writeTree(dir, [file('generated/a.c', 'x'), derived]);
        expect(report.updated).toEqual(['generated/A.list']);
        expect(readFileSync(join(dir, 'generated/A.list'), 'utf8')).toBe('a.c: mine();\nuser.h: int u;\n');
        expect(writeTree(dir, [file('generated/a.c', 'x'), derived]).unchanged).toEqual(['generated/A.list', 'generated/a.c']);
    });

    it('is told when a file could not be written (textOf throws)', () => {
        const dir = out();
        writeTree(dir, [file('generated/a.c', 'x')]);
        writeFileSync(join(dir, 'generated/a.c'), '/*PROTECTED REGION ID(x) ENABLED START*/ unterminated\n');
        let told: unknown;
        const report = writeTree(dir, [file('generated/a.c', 'x'), { ...derived, derive: (textOf) => { try { textOf('generated/a.c'); } catch (e) { told = e; } return 'unknown\n'; } }]);
        expect(report.errors.map((e) => e.file)).toEqual(['generated/a.c']);
        expect(String(told)).toMatch(/generated\/a\.c could not be written/);
    });
});
