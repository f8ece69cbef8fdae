import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

/** A fresh output folder per call, removed after each test. */
const out = scratchDirs();

const module = (name: string): GeneratedFile => ({
    path: `generated/${name}_mod/module.c`,
    content: `// module ${name}\nvoid _init(void){\n    ${region(`protect_init_${name}`, '\n    //TODO\n    ')}\n}\nvoid _exec(void){\n    ${region(`protect_exec_${name}`, '\n    //TODO\n    ')}\n}\n`,
});
const GTG = 'generated/GTG_mod/module.c';
const put = (dir: string, path: string, change: (text: string) => string): string => {
    const text = change(readFileSync(join(dir, path), 'utf8'));
    writeFileSync(join(dir, path), text);
    return text;
};

describe("writeTree's displacedCode 'refuse' (a build's private copy): no user code moved to an orphans/ nobody sees", () => {
    it('refuses a file whose region vanished, lost ENABLED or that was edited outside its regions: an error per problem naming region and line, file untouched, no orphan', () => {
        const cases: Array<[string, (t: string) => string, RegExp, number]> = [
            // (a region of a port since removed: another file's region, here NAV's, is carried home: write-tree.misplaced.test.ts)
            ['vanished', (t) => t.replace('void _exec(void){', `void _exec(void){\n    ${region('protect_event_GTG', '\n    mine();\n    ')}`), /^protected region\(s\) protect_event_GTG hold user code but are not generated in this file any more/, 8],
            ['disabled', (t) => t.replace('protect_init_GTG) ENABLED START*/\n    //TODO', 'protect_init_GTG) START*/\n    mine();'), /^protected region\(s\) protect_init_GTG not ENABLED/, 3],
            ['outside', (t) => t.replace('void _exec(void){', 'int mine;\nvoid _exec(void){'), /^edited outside its protected regions \(line 7 not written by the generator\)/, 7],
        ];
        for (const [what, change, said, line] of cases) {
            const dir = out();
            writeTree(dir, [module('GTG'), module('NAV')]);
            const text = put(dir, GTG, change);
            const report = writeTree(dir, [module('GTG'), module('NAV')], { displacedCode: 'refuse' });
            // a changed region ID is also a change of the skeleton (an edit outside the regions): said too
            expect(report.errors.filter((e) => said.test(e.message)).map((e) => [e.file, e.line]), what).toEqual([[GTG, line]]);
            for (const e of report.errors) expect(e.message, what).toMatch(/a build leaves no user code out; run `contract generate` on the project \(Generate All in the IDE: it moves that code to src-gen\/orphans\/, where you get it back\), then build again; left untouched$/);
            expect(readFileSync(join(dir, GTG), 'utf8'), what).toBe(text);
            expect(report.orphaned, what).toEqual([]);
            expect(existsSync(join(dir, 'orphans')), what).toBe(false);
            // the project's own generate (default) moves it aside, as before
            expect(writeTree(dir, [module('GTG'), module('NAV')]).orphaned.length, what).toBeGreaterThan(0);
        }
    });

    it("leaves a deleted entity's file holding user code in place, with a warning naming no orphan", () => {
        const dir = out();
        writeTree(dir, [module('GTG'), module('OLD')]);
        const old = 'generated/OLD_mod/module.c';
        const text = put(dir, old, (t) => t.replace('//TODO', 'mine();'));
        const report = writeTree(dir, [module('GTG')], { displacedCode: 'refuse' });
        expect(report.errors).toEqual([]);
        expect(report.warnings).toEqual([{ file: old, message: expect.stringMatching(/its entity no longer exists; the file holds user code \(protect_init_OLD\), which this build leaves out; `contract generate` on the project moves it to src-gen\/orphans\/$/) }]);
        expect(readFileSync(join(dir, old), 'utf8')).toBe(text);
        expect(report.orphaned).toEqual([]);
    });
});

describe('writeTree: a rename merged by git (region carried over)', () => {
    it("GTG's file holding PLN's exec region (PLN gone, no protect_exec_GTG): carried over with a warning, no orphan, no edit outside the regions, in either mode", () => {
        for (const displacedCode of ['orphan', 'refuse'] as const) {
            const dir = out();
            writeTree(dir, [module('GTG')]);
            put(dir, GTG, (t) => t.replace('protect_exec_GTG) ENABLED START*/\n    //TODO', 'protect_exec_PLN) ENABLED START*/\n    pln_step();'));
            const report = writeTree(dir, [module('GTG')], { displacedCode });
            expect(report.errors, displacedCode).toEqual([]);
            expect(report.orphaned, displacedCode).toEqual([]);
            expect(report.warnings, displacedCode).toEqual([
                { file: GTG, line: 8, message: expect.stringMatching(/^protected region protect_exec_PLN carried over to protect_exec_GTG: nothing generates protect_exec_PLN any more and this file had no protect_exec_GTG of its own \(a rename merged by git\?\)/) },
            ]);
            expect(readFileSync(join(dir, GTG), 'utf8'), displacedCode).toBe(module('GTG').content.replace('protect_exec_GTG) ENABLED START*/\n    //TODO', 'protect_exec_GTG) ENABLED START*/\n    pln_step();'));
        }
    });
});
