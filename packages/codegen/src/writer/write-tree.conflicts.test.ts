import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { MANIFEST_NAME } from './manifest.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

/** A fresh output folder per call, removed after each test. */
const out = scratchDirs();

const module = (name: string): GeneratedFile => ({
    path: `generated/${name}_mod/module.c`,
    content: `// module ${name}\nvoid _exit_module(void){\n    ${region(`protect_exit_${name}`, '\n    //TODO\n    ')}\n}\nvoid _exec(void){\n    ${region(`protect_exec_${name}`, '\n    //TODO\n    ')}\n}\n`,
});

/** What `git stash pop` over a rename PLN -> GTG left: a hunk holding GTG's default exit region beside PLN's with user code. */
function conflicted(): string {
    return [
        '// module GTG',
        'void _exit_module(void){',
        '<<<<<<< Updated upstream',
        `    ${region('protect_exit_GTG', '\n    //TODO\n    ')}`,
        '=======',
        `    ${region('protect_exit_PLN', '\n    printf("PLN: exit\\n");\n')}`,
        '>>>>>>> Stashed changes',
        '}',
        'void _exec(void){',
        `    ${region('protect_exec_GTG', '\n    step();\n    ')}`,
        '}',
        '',
    ].join('\n');
}

describe('writeTree: files holding git merge conflict markers', () => {
    it('refuses a generated file with a conflict hunk outside its regions: error naming the marker lines, file untouched, nothing orphaned', () => {
        const dir = out();
        writeTree(dir, [module('GTG')]);
        const path = 'generated/GTG_mod/module.c';
        const manifestBefore = readFileSync(join(dir, MANIFEST_NAME), 'utf8');
        writeFileSync(join(dir, path), conflicted());
        const report = writeTree(dir, [module('GTG')]);
        expect(report.errors).toEqual([
            { file: path, line: 3, message: expect.stringContaining('holds git merge conflict markers (lines 3, 7, 11): resolve the merge conflict first') },
        ]);
        expect(report.errors[0]!.message).toMatch(/left untouched$/);
        expect(readFileSync(join(dir, path), 'utf8')).toBe(conflicted());
        expect(report.orphaned).toEqual([]);
        expect(report.warnings).toEqual([]);
        expect(existsSync(join(dir, 'orphans'))).toBe(false);
        // what the manifest knew of the file is kept: once resolved, it is read as before
        expect(readFileSync(join(dir, MANIFEST_NAME), 'utf8')).toBe(manifestBefore);
    });

    it('refuses one with the markers inside a protected region too (diff3 style), and one of a deleted entity (not removed)', () => {
        const dir = out();
        writeTree(dir, [module('GTG'), module('OLD')]);
        const gtg = 'generated/GTG_mod/module.c';
        const inRegion = readFileSync(join(dir, gtg), 'utf8').replace('    //TODO\n', '<<<<<<< HEAD\n    a();\n||||||| base\n=======\n    b();\n>>>>>>> eng-b\n');
        writeFileSync(join(dir, gtg), inRegion);
        const old = 'generated/OLD_mod/module.c';
        const oldText = readFileSync(join(dir, old), 'utf8').replace('    //TODO\n', '<<<<<<< HEAD\n    mine();\n=======\n>>>>>>> eng-b\n');
        writeFileSync(join(dir, old), oldText);
        const report = writeTree(dir, [module('GTG')]);
        expect(report.errors.map((e) => [e.file, e.line])).toEqual([[gtg, 4], [old, 4]]);
        expect(report.errors.every((e) => e.message.includes('resolve the merge conflict first'))).toBe(true);
        expect(readFileSync(join(dir, gtg), 'utf8')).toBe(inRegion);
        expect(readFileSync(join(dir, old), 'utf8')).toBe(oldText);
        expect(report.removed).toEqual([]);
        expect(report.orphaned).toEqual([]);
    });
});

describe('writeTree: a manifest holding git merge conflict markers', () => {
    it('says so (not a JSON parser position), naming the marker lines and how to resolve it', () => {
        const dir = out();
        writeTree(dir, [module('GTG')]);
        const text = readFileSync(join(dir, MANIFEST_NAME), 'utf8').replace('\n "files"', '\n<<<<<<< HEAD\n "x": 1,\n=======\n "y": 2,\n>>>>>>> eng-b\n "files"');
        writeFileSync(join(dir, MANIFEST_NAME), text);
        const report = writeTree(dir, [module('GTG')]);
        expect(report.warnings).toEqual([{ file: MANIFEST_NAME, message: expect.stringMatching(/^holds git merge conflict markers \(lines 3, 5, 7\): unreadable, ignored, and written anew by this generation; next time, resolve such a conflict before generating: take either side of it \(git checkout --theirs src-gen\/\.contract-manifest\.json, or --ours\), then run `contract generate` on the project$/) }]);
    });

    /** The manifest of `dir` with a conflict hunk in it, as a merge of two branches' generations leaves it. */
    const conflictManifest = (dir: string) => {
        const text = readFileSync(join(dir, MANIFEST_NAME), 'utf8').replace('\n "files"', '\n<<<<<<< HEAD\n "x": 1,\n=======\n "y": 2,\n>>>>>>> eng-b\n "files"');
        writeFileSync(join(dir, MANIFEST_NAME), text);
        return text;
    };
    const helper = 'static int my_helper_outside(void){return 42;}\n';

    it('with no record of what it wrote, copies a file that differs outside its regions to orphans/ before regenerating it, saying why', () => {
        const dir = out();
        const path = 'generated/GTG_mod/module.c';
        writeTree(dir, [module('GTG')]);
        const edited = readFileSync(join(dir, path), 'utf8').replace('void _exec(void){', `${helper}void _exec(void){`);
        writeFileSync(join(dir, path), edited);
        conflictManifest(dir);
        const report = writeTree(dir, [module('GTG')]);
        expect(report.orphaned).toEqual([`orphans/${path}`]);
        expect(readFileSync(join(dir, 'orphans', path), 'utf8')).toContain(helper);
        expect(report.warnings).toContainEqual({ file: path, line: 7, message: expect.stringContaining('holds lines outside its protected regions that this generator does not write (line 7 not in the regenerated file): an older generator\'s lines or code of yours, and the manifest holds git merge conflict markers, so the generator cannot tell which: the file as it was is copied to orphans/') });
        // the manifest is written anew: the next generation knows the regenerated file
        expect(readFileSync(join(dir, MANIFEST_NAME), 'utf8')).not.toContain('<<<<<<<');
        expect(writeTree(dir, [module('GTG')]).orphaned).toEqual([]);
    });

    it('copies only a file holding text a regeneration would lose: not one whose differences are generated lines removed, whitespace, or a region the new output drops', () => {
        const dir = out();
        const names = ['GTG', 'NAV', 'LOC', 'MAP'];
        writeTree(dir, names.map(module));
        const at = (name: string) => `generated/${name}_mod/module.c`;
        const edit = (name: string, change: (text: string) => string) => writeFileSync(join(dir, at(name)), change(readFileSync(join(dir, at(name)), 'utf8')));
        // what a merge of two generations can leave: a generated line gone, another one re-indented,
        // a region (default) of a port the other branch removed; and in MAP, the user's helper
        edit('GTG', (t) => t.replace('// module GTG\n', ''));
        edit('NAV', (t) => t.replace('void _exit_module(void){', 'void  _exit_module( void )  {'));
        edit('LOC', (t) => t.replace('void _exec(void){\n', `void _exec(void){\n    ${region('protect_event_LOC', '\n    //TODO\n    ')}\n`));
        edit('MAP', (t) => t.replace('void _exec(void){', `${helper}void _exec(void){`));
        conflictManifest(dir);
        const report = writeTree(dir, names.map(module));
        expect(report.orphaned).toEqual([`orphans/${at('MAP')}`]);
        expect(report.warnings.filter((w) => w.file !== MANIFEST_NAME).map((w) => [w.file, w.line])).toEqual([[at('MAP'), 7]]);
        for (const name of names) expect(readFileSync(join(dir, at(name)), 'utf8')).toBe(module(name).content);
    });

    it('a build refuses it: an error saying to take either side and generate, the file untouched', () => {
        const dir = out();
        const path = 'generated/GTG_mod/module.c';
        writeTree(dir, [module('GTG')]);
        const edited = readFileSync(join(dir, path), 'utf8').replace('void _exec(void){', `${helper}void _exec(void){`);
        writeFileSync(join(dir, path), edited);
        conflictManifest(dir);
        const report = writeTree(dir, [module('GTG')], { displacedCode: 'refuse' });
        expect(report.errors).toContainEqual({ file: MANIFEST_NAME, message: expect.stringMatching(/^holds git merge conflict markers \(lines 3, 5, 7\): unreadable, ignored: with no record of what the generator wrote, a build cannot tell its lines from code written outside the protected regions, and would leave that code out; take either side of it \(git checkout --theirs src-gen\/\.contract-manifest\.json, or --ours\), then run `contract generate` on the project, then build again$/) });
        expect(report.errors).toContainEqual({ file: path, line: 7, message: expect.stringContaining('a build leaves no user code out') });
        expect(readFileSync(join(dir, path), 'utf8')).toBe(edited);
        expect(report.orphaned).toEqual([]);
        // an unedited tree is refused too: nothing tells the build that no code is left out
        const clean = out();
        writeTree(clean, [module('GTG')]);
        conflictManifest(clean);
        expect(writeTree(clean, [module('GTG')], { displacedCode: 'refuse' }).errors.map((e) => e.file)).toEqual([MANIFEST_NAME]);
    });

    it('leaves it as it is while a generated file is refused, so that the file, once resolved with a line outside its regions, is copied to orphans/', () => {
        const dir = out();
        const path = 'generated/GTG_mod/module.c';
        writeTree(dir, [module('GTG'), module('NAV')]);
        const generated = readFileSync(join(dir, path), 'utf8');
        writeFileSync(join(dir, path), conflicted());
        const manifest = conflictManifest(dir);
        const first = writeTree(dir, [module('GTG'), module('NAV')]);
        expect(first.errors.map((e) => e.file)).toEqual([path]);
        expect(first.warnings).toContainEqual({ file: MANIFEST_NAME, message: expect.stringContaining('unreadable, ignored; left as it is while generated files are refused') });
        expect(readFileSync(join(dir, MANIFEST_NAME), 'utf8')).toBe(manifest);
        // resolved: the user's side, with a helper written outside the regions
        const resolved = generated.replace('void _exec(void){', `${helper}void _exec(void){`);
        writeFileSync(join(dir, path), resolved);
        const second = writeTree(dir, [module('GTG'), module('NAV')]);
        expect(second.errors).toEqual([]);
        expect(second.orphaned).toEqual([`orphans/${path}`]);
        expect(readFileSync(join(dir, 'orphans', path), 'utf8')).toContain(helper);
    });
});

describe('writeTree: a file refused (conflict markers) keeps its manifest records', () => {
    it('files, skeletons and skeletonLines of the refused file are in the manifest written, so an edit outside its regions is still found once resolved', () => {
        const dir = out();
        const path = 'generated/GTG_mod/module.c';
        writeTree(dir, [module('GTG')]);
        const before = JSON.parse(readFileSync(join(dir, MANIFEST_NAME), 'utf8')) as Record<string, Record<string, unknown>>;
        writeFileSync(join(dir, path), conflicted());
        // a model change in the same generation: the manifest is rewritten
        writeTree(dir, [module('GTG'), module('NAV')]);
        const after = JSON.parse(readFileSync(join(dir, MANIFEST_NAME), 'utf8')) as Record<string, Record<string, unknown>>;
        for (const table of ['files', 'skeletons', 'skeletonLines']) expect(after[table]![path]).toEqual(before[table]![path]);
        expect(after.files!['generated/NAV_mod/module.c']).toBeDefined();
    });
});
