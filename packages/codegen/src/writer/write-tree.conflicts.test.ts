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
        expect(report.warnings).toEqual([{ file: MANIFEST_NAME, message: expect.stringMatching(/^holds git merge conflict markers \(lines 3, 5, 7\): unreadable, ignored, and written anew by this generation; resolve a conflict in the manifest by taking either side \(git checkout --theirs or --ours/) }]);
    });
});
