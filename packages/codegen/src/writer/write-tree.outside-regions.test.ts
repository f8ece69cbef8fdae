/**
 * Code written where the generator owns the file (outside the protected regions), and regions whose
 * ENABLED flag is gone: regenerated as documented, but never silently (docs/codegen.md, "Protected
 * regions"): the code as it was goes to orphans/ with a header saying why, and a warning says where.
 */
import { existsSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { MANIFEST_NAME, hashContent, skeletonHash, skeletonText } from './manifest.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

/** A fresh output folder per call, removed after each test. */
const out = scratchDirs();

const A = 'generated/modules/MSC_mod/module.c';
const file = (extra = ''): GeneratedFile => ({
    path: A,
    content: `// generated\n#include "tools.h"\n${extra}int step(void);\n${region('protect_vars_MSC', '\n//TODO\n')}\n${region('protect_exec_MSC', '\nreturn -1;\n')}\n`,
});
const read = (dir: string, p: string) => readFileSync(join(dir, p), 'latin1');
const write = (dir: string, p: string, text: string) => writeFileSync(join(dir, p), Buffer.from(text, 'latin1'));
const manifest = (dir: string) => JSON.parse(readFileSync(join(dir, MANIFEST_NAME), 'utf8')) as { version: number; files: Record<string, unknown>; skeletons?: Record<string, string>; skeletonLines?: Record<string, string> };

describe('code written outside the protected regions', () => {
    it('is copied to orphans/ with a header saying why and how to get it back, a warning names the file and line, the file is still regenerated', () => {
        const dir = out();
        writeTree(dir, [file()]);
        const edited = read(dir, A).replace('int step(void);\n', 'int step(void);\nstatic int helper_\xe9(void) { return 4; } /* mine */\n');
        write(dir, A, edited);
        const r = writeTree(dir, [file()]);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.warnings).toEqual([{
            file: A,
            line: 4,
            message: `edited outside its protected regions (line 4 not written by the generator): that code is regenerated, not kept; the file as it was is in orphans/${A} (move your code into a protected region)`,
        }]);
        expect(read(dir, A)).toBe(file().content);
        const orphan = read(dir, `orphans/${A}`);
        expect(orphan).toMatch(/^\/\* Orphaned user code of generated\/modules\/MSC_mod\/module\.c \(module or supervisor MSC\), moved here on /);
        expect(orphan).toContain('The file was edited outside its protected regions (line 4 not written by the generator)');
        expect(orphan).toContain('move it into a protected region of');
        expect(orphan.slice(orphan.indexOf('*/\n') + 3)).toBe(edited); // byte for byte
        // the next regeneration has nothing more to say
        const again = writeTree(dir, [file()]);
        expect([again.orphaned, again.warnings, again.filesWritten]).toEqual([[], [], 0]);
    });

    it('a whitespace-only line holds no code: no edit outside the regions (generate and build alike), while a real line beside it still is one', () => {
        for (const displacedCode of ['orphan', 'refuse'] as const) {
            const dir = out();
            writeTree(dir, [file()]);
            write(dir, A, read(dir, A).replace('int step(void);\n', 'int step(void);\n    \n\t\n'));
            const r = writeTree(dir, [file()], { displacedCode });
            expect([r.errors, r.orphaned, r.warnings]).toEqual([[], [], []]);
            expect(read(dir, A)).toBe(file().content);
        }
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace('int step(void);\n', 'int step(void);\n    \nint mine;\n'));
        const r = writeTree(dir, [file()]);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.warnings[0]!.message).toMatch(/^edited outside its protected regions \(line 5 not written by the generator\)/);
    });

    it('also when the model changed the generated code around the edit', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace('// generated\n', '// generated\n#define MINE 1\n'));
        const r = writeTree(dir, [file('int added_port;\n')]);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.warnings[0]).toMatchObject({ file: A, line: 2 });
        expect(read(dir, `orphans/${A}`)).toContain('#define MINE 1\n');
        expect(read(dir, A)).toBe(file('int added_port;\n').content);
    });

    it('names the lines the user wrote, not the lines the model changed since', () => {
        const dir = out();
        writeTree(dir, [file()]);
        // the user writes two lines after the exec region and replaces the comment on line 1; the
        // model then adds a line near the top (line 3 of the regenerated file)
        const edited = read(dir, A).replace('// generated\n', '// generated for my robot\n') + '// mine\nint mine(void);\n';
        write(dir, A, edited);
        const r = writeTree(dir, [file('int added_port;\n')]);
        expect(r.warnings).toHaveLength(1);
        const lines = edited.split('\n');
        const at = (text: string) => lines.indexOf(text) + 1;
        expect(r.warnings[0]).toMatchObject({ file: A, line: 1 });
        expect(r.warnings[0]!.message).toContain(`(lines 1, ${at('// mine')}-${at('int mine(void);')} not written by the generator)`);
        expect(at('// mine')).toBeGreaterThan(3);
        // only the appended lines: named, where the regenerated file's first difference is the model's line 3
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A) + '// mine\n');
        const again = writeTree(dir, [file('int added_port;\n')]);
        const appended = file().content.split('\n').length;
        expect(again.warnings[0]).toMatchObject({ line: appended });
        expect(again.warnings[0]!.message).toContain(`(line ${appended} not written by the generator)`);
        expect(read(dir, `orphans/${A}`).endsWith(edited)).toBe(true);
    });

    it('names where generated lines were removed, and reads a CRLF checkout with an edit as the same lines', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace('#include "tools.h"\n', ''));
        let r = writeTree(dir, [file()]);
        expect(r.warnings[0]).toMatchObject({ line: 1 });
        expect(r.warnings[0]!.message).toContain('(generated lines removed after line 1)');
        write(dir, A, read(dir, A).replace(/\n/g, '\r\n').replace('int step(void);', 'int step(void); /* mine */'));
        r = writeTree(dir, [file()]);
        expect(r.warnings[0]).toMatchObject({ line: 3 });
        expect(r.warnings[0]!.message).toContain('(line 3 not written by the generator)');
    });

    it('without line hashes (an older or tampered manifest, more lines than a generated file has): the first line that differs from the regenerated file', () => {
        for (const lines of [undefined, 'not base64!', 42, 'AAAA'.repeat(1_000_001)]) {
            const dir = out();
            writeTree(dir, [file()]);
            const m = manifest(dir) as Record<string, unknown> & { skeletonLines?: Record<string, unknown> };
            expect(typeof m.skeletonLines?.[A]).toBe('string');
            if (lines === undefined) delete m.skeletonLines;
            else m.skeletonLines = { [A]: lines };
            writeFileSync(join(dir, MANIFEST_NAME), JSON.stringify(m));
            write(dir, A, read(dir, A).replace('int step(void);\n', 'int step(void);\nint mine;\n'));
            const r = writeTree(dir, [file()]);
            expect(r.warnings).toHaveLength(1);
            expect(r.warnings[0]).toMatchObject({ line: 4 });
            expect(r.warnings[0]!.message).toContain('(first line that differs from the regenerated file: 4)');
            // and the regeneration records them again
            expect(typeof manifest(dir).skeletonLines?.[A]).toBe('string');
        }
    });

    it('does not count edits inside regions, ENABLED toggles, re-spaced markers or a model change', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A)
            .replace('\n//TODO\n', '\nint mine = 1;\n')
            .replace('/*PROTECTED REGION ID(protect_exec_MSC) ENABLED START*/', '/* PROTECTED REGION ID( protect_exec_MSC )\n START */'));
        const r = writeTree(dir, [file('int added_port;\n')]);
        expect([r.orphaned, r.warnings]).toEqual([[], []]);
        expect(read(dir, A)).toContain(region('protect_vars_MSC', '\nint mine = 1;\n'));
    });

    it('does not count line endings turned into CRLF (a checkout with autocrlf), and keeps them: unchanged, or updated all CRLF', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace(/\n/g, '\r\n').replace('//TODO\r\n', '// mine\r\n'));
        const crlf = read(dir, A);
        const r = writeTree(dir, [file()]);
        expect([r.orphaned, r.warnings]).toEqual([[], []]);
        // the same model: nothing to write (the file was rewritten LF outside its regions: mixed endings, every line a diff)
        expect(r.unchanged).toContain(A);
        expect(read(dir, A)).toBe(crlf);
        // a model change: the new lines are CRLF too, the user's code kept
        const changed = writeTree(dir, [file('int added_port;\n')]);
        expect(changed.updated).toContain(A);
        const text = read(dir, A);
        expect(text).toContain('int added_port;\r\n');
        expect(text).toContain('// mine\r\n');
        expect(text.replace(/\r\n/g, '')).not.toContain('\n');
    });

    it('warns of a file its regions make larger than a build reads (8 MiB), keeping it all', () => {
        const dir = out();
        writeTree(dir, [file()]);
        const big = `/* ${'x'.repeat(9 * 1024 * 1024)} */`;
        write(dir, A, read(dir, A).replace('//TODO', big));
        const r = writeTree(dir, [file('int added_port;\n')]);
        expect(r.warnings.map((w) => w.message)).toEqual([expect.stringMatching(/^is \d+ bytes with its protected regions, above the 8388608 a build reads of a project's file \(and the IDE opens\): contract build and Build & Run will refuse the project/)]);
        expect(read(dir, A)).toContain(big);
    });

    it('the skeleton reduces each region to its ID', () => {
        expect(skeletonText(`a${region('x', 'body')}b/*PROTECTED REGION ID( x2 ) START*/other/*PROTECTED REGION END*/c`, 'f.c')).toBe('a\u0000x\u0000b\u0000x2\u0000c');
    });

    it('a file of a deleted entity edited outside its regions moves to orphans/ whole even without user regions', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace('int step(void);\n', 'int step(void);\nint mine;\n'));
        const r = writeTree(dir, []);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.removed).toEqual([]);
        expect(r.warnings[0]!.message).toContain('code outside the protected regions');
        expect(read(dir, `orphans/${A}`)).toContain('int mine;\n');
        expect(existsSync(join(dir, A))).toBe(false);
    });

    it('manifest: one skeleton hash per file; an old manifest without them loads, and the file is compared with the regenerated one instead; bad entries are ignored', () => {
        const dir = out();
        writeTree(dir, [file()]);
        const m = manifest(dir);
        expect(m.version).toBe(1);
        expect(Object.keys(m.skeletons!)).toEqual([A]);
        expect(m.skeletons![A]).toBe(skeletonHash(file().content, A));
        // an older manifest: no skeletons. The edit outside is not the regenerated file's: copied to orphans/
        delete m.skeletons;
        writeFileSync(join(dir, MANIFEST_NAME), JSON.stringify(m));
        write(dir, A, read(dir, A).replace('int step(void);\n', 'int step(void);\nint mine;\n'));
        const old = writeTree(dir, [file()]);
        expect(old.orphaned).toEqual([`orphans/${A}`]);
        // said once for the tree (an upgrade copies many files), not once a file; the copy's header says why
        expect(old.warnings).toEqual([{ file: MANIFEST_NAME, message: expect.stringContaining(`written by an older version of ContrACT Studio, it records of each file only the defaults of its protected regions, nothing of its text outside them (a file without regions, a Makefile, not at all). 1 file holds lines outside the protected regions that this generator does not write, an older generator's lines or code of yours (it cannot tell which): each was regenerated, its regions' code kept, and copied first as it was to orphans/ under its own path (orphans/${A})`) }]);
        expect(read(dir, `orphans/${A}`)).toContain('(line 4 not in the regenerated file; the manifest holds no record of its text (a manifest of an older version))');
        expect(read(dir, `orphans/${A}`)).toContain('int mine;\n');
        expect(read(dir, A)).toBe(file().content);
        expect(manifest(dir).skeletons).toEqual({ [A]: hashContent(skeletonText(file().content, A)) });
        // hostile skeleton entries: not a hash, not a listed file, not an object: ignored (no record of
        // the file, which is compared with the regenerated one), nothing acted on through them
        for (const skeletons of [{ [A]: 'not a hash' }, { '../../etc/passwd': '0123456789abcdef' }, ['x'], 'x', { [A]: 42 }]) {
            writeFileSync(join(dir, MANIFEST_NAME), JSON.stringify({ ...manifest(dir), skeletons }));
            write(dir, A, read(dir, A).replace('int step(void);\n', 'int step(void);\nint mine;\n'));
            const r = writeTree(dir, [file()]);
            expect([r.orphaned, r.warnings.map((w) => w.line), r.errors], JSON.stringify(skeletons)).toEqual([[`orphans/${A}`], [4], []]);
            expect(read(dir, A)).toBe(file().content);
        }
        expect(existsSync(join(dir, 'etc'))).toBe(false);
    });
});

describe('code outside the protected regions with no record of what the generator wrote (no manifest, an older one)', () => {
    const helper = 'static int my_helper(void) { return 42; }\n';

    it('a deleted manifest: code outside the regions is copied to orphans/, not dropped; a build refuses it', () => {
        const dir = out();
        writeTree(dir, [file()]);
        const edited = read(dir, A).replace('int step(void);\n', `int step(void);\n${helper}`);
        write(dir, A, edited);
        rmSync(join(dir, MANIFEST_NAME));
        const build = writeTree(dir, [file()], { displacedCode: 'refuse' });
        expect(build.errors).toEqual([{ file: A, line: 4, message: expect.stringMatching(/^holds lines outside its protected regions that this generator does not write \(line 4 not in the regenerated file\): an older generator's lines or code of yours, and there is no manifest \(\.contract-manifest\.json\) recording what the generator wrote, so the generator cannot tell which: a build leaves no user code out; .*left untouched$/) }]);
        expect(read(dir, A)).toBe(edited);
        rmSync(join(dir, MANIFEST_NAME)); // the one the build wrote beside (a build runs in its own copy of the project)
        const r = writeTree(dir, [file()]);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.warnings).toEqual([{ file: MANIFEST_NAME, message: expect.stringContaining(`1 file holds lines outside the protected regions that this generator does not write, an older generator's lines or code of yours (it cannot tell which): each was regenerated, its regions' code kept, and copied first as it was to orphans/ under its own path (orphans/${A})`) }]);
        expect(read(dir, `orphans/${A}`)).toContain(helper);
        expect(read(dir, A)).toBe(file().content);
    });

    it('a tree from another version or tool (no manifest at all): one warning for all the copies, and each copy\'s header says what is true (an older generator\'s lines, or yours)', () => {
        const dir = out();
        const names = ['MAA', 'MAB', 'MSA', 'MSB', 'MSC'];
        const modules = names.map((n): GeneratedFile => ({ path: `generated/modules/${n}_mod/module.c`, content: file().content.replaceAll('MSC', n) }));
        writeTree(dir, modules);
        rmSync(join(dir, MANIFEST_NAME));
        // the old tool's template lines: a comment it wrote, a global it declared
        for (const m of modules) write(dir, m.path, read(dir, m.path).replace('// generated\n', '//          module source file\n').replace('int step(void);\n', 'int step(void);\nFILE* logFile;\n'));
        const r = writeTree(dir, modules);
        const copies = modules.map((m) => `orphans/${m.path}`);
        expect(r.orphaned).toEqual(copies);
        expect(r.warnings).toEqual([{
            file: MANIFEST_NAME,
            message: `not there: this tree has no record of what was generated in it (a tree of another version of ContrACT Studio, or of another tool such as the ContrACT Eclipse tool?). 5 files hold lines outside the protected regions that this generator does not write, an older generator's lines or code of yours (it cannot tell which): each was regenerated, its regions' code kept, and copied first as it was to orphans/ under its own path (${copies.slice(0, 3).join(', ')} and 2 more). Move any code of yours found there into a protected region, then delete the copies; an older generator's lines need nothing. The manifest is written now: the next generation tells the generator's lines from yours`,
        }]);
        const copy = read(dir, copies[0]!);
        expect(copy).toMatch(/^\/\* Copy of generated\/modules\/MAA_mod\/module\.c \(module or supervisor MAA\), made on \d{4}-\d\d-\d\dT[^ ]+ before it was regenerated\.\n/);
        expect(copy).toContain('It held lines outside its protected regions that this generator does not write (lines 1, 4 not in the regenerated file; there is no manifest (.contract-manifest.json) recording what the generator wrote)');
        expect(copy).toContain("an older generator's lines (another version of ContrACT Studio, or another tool such as the ContrACT Eclipse tool),\n * or code of yours");
        expect(copy).not.toContain('edited outside');
        expect(copy).toContain('FILE* logFile;\n'); // the file as it was
        // nothing more to say: the manifest now records the generation; the same copy again is not written twice
        const again = writeTree(dir, modules);
        expect([again.orphaned, again.warnings, again.filesWritten]).toEqual([[], [], 0]);
    });

    it('an unmodified generated file, one with code in its regions only, one whose generated lines were removed, re-indented or re-spaced (an older generator\'s spacing), or one with a region the new output drops: not copied', () => {
        const dir = out();
        writeTree(dir, [file()]);
        rmSync(join(dir, MANIFEST_NAME));
        const variants = [
            file().content,
            read(dir, A).replace('return -1;', 'return step() + 1;'),
            read(dir, A).replace('#include "tools.h"\n', ''),
            read(dir, A).replace('int step(void);', '  int   step( void ) ;\t').replace('// generated\n', '// generated\n\n\n'),
            read(dir, A).replace('\n', '\r\n'),
            read(dir, A).replace('int step(void);\n', `int step(void);\n${region('protect_event_MSC', '\n//TODO\n')}\n`),
        ];
        for (const text of variants) {
            write(dir, A, text);
            rmSync(join(dir, MANIFEST_NAME), { force: true });
            const r = writeTree(dir, [file()]);
            expect([r.orphaned, r.warnings, r.errors], JSON.stringify(text)).toEqual([[], [], []]);
        }
        expect(existsSync(join(dir, 'orphans'))).toBe(false);
    });

    it('a file of a deleted entity, with no record of it: moved to orphans/ whole, saying why (nothing generated to compare it with)', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace('int step(void);\n', `int step(void);\n${helper}`));
        rmSync(join(dir, MANIFEST_NAME));
        const r = writeTree(dir, []);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.warnings).toEqual([{ file: A, message: expect.stringContaining('perhaps code outside the protected regions (there is no manifest (.contract-manifest.json) recording what the generator wrote)') }]);
        expect(read(dir, `orphans/${A}`)).toContain(helper);
        expect(existsSync(join(dir, A))).toBe(false);
    });

    it('an older generator\'s line that differs by more than whitespace (a reworded comment) is copied, saying it may be an older version\'s', () => {
        const dir = out();
        writeTree(dir, [file()]);
        const m = manifest(dir);
        delete m.skeletons;
        delete m.skeletonLines;
        writeFileSync(join(dir, MANIFEST_NAME), JSON.stringify(m));
        write(dir, A, read(dir, A).replace('// generated\n', '// generated by version 0.9\n'));
        const r = writeTree(dir, [file()]);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(read(dir, `orphans/${A}`)).toContain('(line 1 not in the regenerated file; the manifest holds no record of its text (a manifest of an older version))');
        expect(r.warnings).toEqual([{ file: MANIFEST_NAME, message: expect.stringContaining("an older generator's lines or code of yours (it cannot tell which)") }]);
        expect(r.warnings[0]!.message).toContain("then delete the copies; an older generator's lines need nothing");
    });
});

describe('a region that lost ENABLED', () => {
    it('holding user code: its content goes to orphans/ with a warning, then the default is put back', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace(
            '/*PROTECTED REGION ID(protect_exec_MSC) ENABLED START*/\nreturn -1;\n',
            '/*PROTECTED REGION ID(protect_exec_MSC) START*/\n*stateindex = 2; my_step(); /* caf\xe9 */\n'));
        const r = writeTree(dir, [file()]);
        expect(read(dir, A)).toBe(file().content);
        expect(r.orphaned).toEqual([`orphans/${A}`]);
        expect(r.warnings).toEqual([{
            file: A,
            line: 7,
            message: `protected region(s) protect_exec_MSC not ENABLED: their content was replaced by the generated default; what they held is in orphans/${A} (put ENABLED back in the start marker to keep your code)`,
        }]);
        const orphan = read(dir, `orphans/${A}`);
        expect(orphan).toContain('These protected regions were not ENABLED');
        expect(orphan).toContain('/*PROTECTED REGION ID(protect_exec_MSC) START*/\n*stateindex = 2; my_step(); /* caf\xe9 */\n/*PROTECTED REGION END*/');
    });

    it('holding the default (the manifest\'s, or the fresh one without a manifest): replaced silently, as asked', () => {
        const dir = out();
        writeTree(dir, [file()]);
        write(dir, A, read(dir, A).replace('(protect_exec_MSC) ENABLED START', '(protect_exec_MSC) START'));
        // the default changed in the generator: the old default is known by the manifest's hash
        const changed: GeneratedFile = { path: A, content: file().content.replace('\nreturn -1;\n', '\nreturn 0;\n') };
        const r = writeTree(dir, [changed]);
        expect([r.orphaned, r.warnings]).toEqual([[], []]);
        expect(read(dir, A)).toBe(changed.content);
        // without a manifest: only the fresh default counts as a default
        const bare = out();
        writeTree(bare, [file()]);
        write(bare, MANIFEST_NAME, '');
        write(bare, A, read(bare, A).replace('(protect_exec_MSC) ENABLED START', '(protect_exec_MSC) START'));
        const same = writeTree(bare, [file()]);
        expect([same.orphaned, same.warnings.filter((w) => w.file !== MANIFEST_NAME)]).toEqual([[], []]);
        write(bare, A, read(bare, A).replace('(protect_exec_MSC) ENABLED START', '(protect_exec_MSC) START'));
        write(bare, MANIFEST_NAME, '');
        const other = writeTree(bare, [changed]); // 'return -1;' is not the fresh default: kept aside
        expect(other.orphaned).toEqual([`orphans/${A}`]);
    });

    it('a start marker with a typo: the file is left untouched, the error is at the typo\'s line', () => {
        const dir = out();
        writeTree(dir, [file()]);
        const typo = read(dir, A).replace('(protect_exec_MSC) ENABLED START', '(protect_exec_MSC) ENABELD START');
        write(dir, A, typo);
        const r = writeTree(dir, [file()]);
        expect(r.errors).toEqual([{ file: A, line: 7, message: "protected region start 'protect_exec_MSC' is malformed: 'ENABELD START' (expected 'ENABLED START' or 'START'); left untouched" }]);
        expect(read(dir, A)).toBe(typo);
        expect(r.orphaned).toEqual([]);
    });
});
