/**
 * A protected region found in another generated file than the one generating its ID (a git merge,
 * or a paste, put module NAV's protect_exec_NAV with its code into GTG's module.c): carried home
 * when unambiguous, else orphaned with a warning naming the file it belongs to (docs/codegen.md,
 * "A region in the wrong file").
 */
import { existsSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

const out = scratchDirs();

const module = (name: string): GeneratedFile => ({
    path: `generated/${name}_mod/module.c`,
    content: `// module ${name}\nvoid _exit_module(void){\n    ${region(`protect_exit_${name}`, '\n    //TODO\n    ')}\n}\nvoid _exec(void){\n    ${region(`protect_exec_${name}`, '\n    //TODO\n    ')}\n}\n`,
});
const GTG = 'generated/GTG_mod/module.c';
const NAV = 'generated/NAV_mod/module.c';
const LOC = 'generated/LOC_mod/module.c';
const tree = [module('GTG'), module('LOC'), module('NAV')];
const code = '\n    follow_path(); /* NAV\'s own */\n';
const read = (dir: string, p: string) => readFileSync(join(dir, p), 'utf8');

/** `dir`'s GTG module.c with NAV's exec region, holding `code`, pasted after GTG's own exec region. */
function pasteIntoGtg(dir: string, path = GTG): void {
    const text = read(dir, path).replace(/(PROTECTED REGION ID\(protect_exec_\w+\) ENABLED START[^]*?PROTECTED REGION END\*\/)/, `$1\n    ${region('protect_exec_NAV', code)}`);
    writeFileSync(join(dir, path), text);
}

describe('writeTree: a protected region in the wrong generated file', () => {
    it('is carried to the file generating its ID when that region holds the default there: code byte for byte, a warning naming both files, nothing orphaned (generate and build alike)', () => {
        for (const displacedCode of ['orphan', 'refuse'] as const) {
            const dir = out();
            writeTree(dir, tree);
            pasteIntoGtg(dir);
            const report = writeTree(dir, tree, { displacedCode });
            expect(report.errors).toEqual([]);
            expect(report.orphaned).toEqual([]);
            expect(report.warnings).toEqual([{ file: GTG, line: 11, message: `protected region protect_exec_NAV is no region of this file but of ${NAV} (a git merge or a paste put it here?): its code was carried there, byte for byte, into its protect_exec_NAV, which held the generated default; check that it belongs there` }]);
            expect(read(dir, NAV)).toBe(module('NAV').content.replace(/(protect_exec_NAV\) ENABLED START\*\/)\n {4}\/\/TODO\n {4}/, `$1${code}`));
            expect(read(dir, NAV)).toContain(`ID(protect_exec_NAV) ENABLED START*/${code}/*PROTECTED REGION END*/`);
            expect(read(dir, GTG)).toBe(module('GTG').content);
            // once home, the next generation has nothing to say
            const again = writeTree(dir, tree);
            expect([again.warnings, again.orphaned, again.filesWritten]).toEqual([[], [], 0]);
        }
    });

    it('also when its own file was deleted (it is generated with that code), or lacks that region', () => {
        const dir = out();
        writeTree(dir, tree);
        pasteIntoGtg(dir);
        rmSync(join(dir, NAV));
        expect(writeTree(dir, tree).orphaned).toEqual([]);
        expect(read(dir, NAV)).toContain(`ID(protect_exec_NAV) ENABLED START*/${code}/*PROTECTED REGION END*/`);
        const other = out();
        writeTree(other, tree);
        pasteIntoGtg(other);
        writeFileSync(join(other, NAV), read(other, NAV).replace(/\n {4}\/\*PROTECTED REGION ID\(protect_exec_NAV\)[^]*?END\*\//, ''));
        // (the line of the region carried home is no line removed outside its regions: nothing orphaned)
        expect(writeTree(other, tree).orphaned).toEqual([]);
        expect(read(other, NAV)).toContain(`ID(protect_exec_NAV) ENABLED START*/${code}/*PROTECTED REGION END*/`);
    });

    it('cut whole from its own file (its indentation left there, or its whole line) and pasted into another: carried home, its own file neither orphaned nor refused (generate and build alike)', () => {
        for (const displacedCode of ['orphan', 'refuse'] as const) {
            for (const left of ['    ', '']) {
                const dir = out();
                writeTree(dir, tree);
                const nav = read(dir, NAV).replace(`ID(protect_exec_NAV) ENABLED START*/\n    //TODO\n    `, `ID(protect_exec_NAV) ENABLED START*/${code}`);
                const cut = /\n( {4})(\/\*PROTECTED REGION ID\(protect_exec_NAV\)[^]*?END\*\/)/.exec(nav)!;
                writeFileSync(join(dir, NAV), nav.replace(cut[0], left === '' ? '' : `\n${left}`));
                writeFileSync(join(dir, GTG), read(dir, GTG).replace(/(protect_exec_GTG\) ENABLED START[^]*?PROTECTED REGION END\*\/)/, `$1\n    ${cut[2]}`));
                const report = writeTree(dir, tree, { displacedCode });
                expect(report.errors).toEqual([]);
                expect(report.orphaned).toEqual([]);
                expect(report.warnings).toEqual([{ file: GTG, line: 11, message: expect.stringMatching(/^protected region protect_exec_NAV is no region of this file but of generated\/NAV_mod\/module\.c .*: its code was carried there/) }]);
                expect(read(dir, NAV)).toContain(`ID(protect_exec_NAV) ENABLED START*/${code}/*PROTECTED REGION END*/`);
                expect(read(dir, GTG)).toBe(module('GTG').content);
                expect(existsSync(join(dir, 'orphans'))).toBe(false);
            }
        }
    });

    it('is orphaned, never lost, when its own file\'s region holds code of its own: the warning and the orphan name the file it belongs to and how to move it back', () => {
        const dir = out();
        writeTree(dir, tree);
        const mine = '\n    plan_route(); /* in NAV\'s file */\n    ';
        writeFileSync(join(dir, NAV), read(dir, NAV).replace(/(protect_exec_NAV\) ENABLED START\*\/)\n {4}\/\/TODO\n {4}/, `$1${mine}`));
        pasteIntoGtg(dir);
        const report = writeTree(dir, tree);
        expect(report.orphaned).toEqual([`orphans/${GTG}`]);
        expect(report.warnings).toEqual([{ file: GTG, line: 11, message: `user code of protected region(s) protect_exec_NAV moved to orphans/${GTG}; protect_exec_NAV is no region of this file but of ${NAV} (a git merge or a paste put it here?), whose protect_exec_NAV holds code of its own (or it is in more than one file): not carried there, paste its code into that region by hand` }]);
        expect(read(dir, NAV)).toContain(mine);
        const orphan = read(dir, `orphans/${GTG}`);
        expect(orphan).toContain(' * These protected regions are not generated in this file: protect_exec_NAV.\n');
        expect(orphan).toContain(` * protect_exec_NAV is no region of this file but of ${NAV} (a git merge or a paste put it here): paste its\n * content into the region of that ID there`);
        expect(orphan).toContain(code);
        // a build refuses it, naming where it belongs
        pasteIntoGtg(dir);
        const build = writeTree(dir, tree, { displacedCode: 'refuse' });
        expect(build.errors).toEqual([{ file: GTG, line: 11, message: expect.stringContaining(`protect_exec_NAV is no region of this file but of ${NAV}`) }]);
    });

    it('is orphaned when found in two wrong files (which one is meant?), each naming its home', () => {
        const dir = out();
        writeTree(dir, tree);
        pasteIntoGtg(dir);
        pasteIntoGtg(dir, LOC);
        const report = writeTree(dir, tree);
        expect(report.orphaned).toEqual([`orphans/${GTG}`, `orphans/${LOC}`]);
        expect(report.warnings.map((w) => w.message).every((m) => m.includes(`protect_exec_NAV is no region of this file but of ${NAV}`))).toBe(true);
        expect(read(dir, NAV)).toBe(module('NAV').content);
        expect(existsSync(join(dir, 'orphans', NAV))).toBe(false);
    });
});
