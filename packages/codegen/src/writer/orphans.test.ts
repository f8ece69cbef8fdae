/** Orphan files say where their code came from, when, and how to bring it back (docs/codegen.md, "Renames"). */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { fileOrphanText, orphanEntity, writeOrphan } from './orphans.js';
import { OutputTree } from './output-tree.js';
import { writeTree } from './write-tree.js';

/** A fresh output folder per call, removed after each test. */
const out = scratchDirs();

const MSC = 'generated/architecture/modules/MSC_mod/module.c';
const module = (path: string, ...ids: string[]) => ({ path, content: `// ${path}\n` + ids.map((id) => `${region(id, '\n//TODO\n')}\n`).join('') });

describe('orphan files', () => {
    it('a whole file whose entity vanished: header with entity, file, date, regions and the way back, then the file byte for byte', () => {
        const dir = out();
        writeTree(dir, [module(MSC, 'protect_exec_MSC')]);
        const edited = readFileSync(join(dir, MSC), 'latin1').replace('\n//TODO\n', '\nmy_step(); /* caf\xe9 */\n');
        writeFileSync(join(dir, MSC), Buffer.from(edited, 'latin1'));
        const before = Date.now();
        const r = writeTree(dir, []);
        expect(r.orphaned).toEqual([`orphans/${MSC}`]);
        const text = readFileSync(join(dir, 'orphans', MSC), 'latin1');
        const header = text.slice(0, text.indexOf('*/\n') + 3);
        expect(header).toContain(`/* Orphaned user code of ${MSC} (module or supervisor MSC), moved here on `);
        const when = Date.parse(/moved here on (\S+)\./.exec(header)![1]!);
        expect(when).toBeGreaterThanOrEqual(before - 1000);
        expect(header).toContain('The entity no longer exists in the generated code (renamed or deleted entity, removed port...): protect_exec_MSC.');
        expect(header).toContain('(protect_exec_OLD -> protect_exec_NEW)');
        expect(header).toContain(`copy this file, without this comment, back to ${MSC}`);
        expect(header).toContain('`contract rename DIR OLD NEW`');
        expect(text.slice(header.length)).toBe(edited);
    });

    it('vanished regions of a file that remains: header naming the regions', () => {
        const dir = out();
        writeTree(dir, [module(MSC, 'protect_exec_MSC', 'protect_event_MSC')]);
        const edited = readFileSync(join(dir, MSC), 'latin1').replace('\n//TODO\n', '\nkeep_me();\n');
        writeFileSync(join(dir, MSC), edited);
        const r = writeTree(dir, [module(MSC, 'protect_event_MSC')]);
        const text = readFileSync(join(dir, r.orphaned[0]!), 'latin1');
        expect(text).toMatch(/^\/\* Orphaned user code of generated\/architecture\/modules\/MSC_mod\/module\.c \(module or supervisor MSC\), moved here on /);
        expect(text).toContain('These protected regions no longer exist in the generated code (renamed or deleted entity, removed port...): protect_exec_MSC.');
        expect(text).toContain(region('protect_exec_MSC', '\nkeep_me();\n'));
    });

    it('a file with no protected region that differs from the generated one: the advice fits a file generated whole (a git merge, or code to put in a region), not "move it into a region of this file"', () => {
        const dir = out();
        const VOC = 'generated/architecture/modules/NAV_mod/vocabulary.c';
        writeTree(dir, [{ path: VOC, content: '// tables\nint rules = 1;\n' }]);
        // two generated versions git merged: the manifest's (one side's) hash no longer matches
        writeFileSync(join(dir, VOC), '// tables\nint rules = 1;\nint slow = 2;\n');
        const r = writeTree(dir, [{ path: VOC, content: '// tables\nint rules = 1;\nint slow = 2;\nint guide = 3;\n' }]);
        expect(r.orphaned).toEqual([`orphans/${VOC}`]);
        const text = readFileSync(join(dir, 'orphans', VOC), 'utf8');
        expect(text).toContain('it has no protected region: it is generated');
        expect(text).toContain('If the difference came from a git merge of two generated versions');
        expect(text).not.toContain('move it into a protected region of');
        expect(text.endsWith('// tables\nint rules = 1;\nint slow = 2;\n')).toBe(true);
    });

    it('the same orphaned code written again at another time reuses the first orphan', () => {
        const dir = new OutputTree(out());
        const first = writeOrphan(dir, MSC, fileOrphanText(MSC, 'x();\n', ['a'], new Date('2026-01-01T00:00:00Z')));
        const again = writeOrphan(dir, MSC, fileOrphanText(MSC, 'x();\n', ['a'], new Date('2026-02-01T00:00:00Z')));
        expect(again).toEqual({ path: first.path, written: false });
        expect(writeOrphan(dir, MSC, fileOrphanText(MSC, 'y();\n', ['a'])).path).toBe(`orphans/${MSC}`.replace('.c', '.2.c'));
    });

    it('names the entity of each generated path', () => {
        expect(orphanEntity('generated/architecture/common/SharedTypeA.h')).toBe('datatype TypeA');
        expect(orphanEntity('generated/architecture/common/SharedFunctiondoit.h')).toBe('function doit');
        expect(orphanEntity('generated/architecture/tools/controlSUP.c')).toBe('module or supervisor SUP');
        expect(orphanEntity('generated/architecture/tools/makecontrolMSA')).toBe('module or supervisor MSA');
        expect(orphanEntity('generated/architecture/modules/ORD_mod/module.c')).toBe('the scheduler ORD');
        expect(orphanEntity('generated/other.c')).toBe('the entity it was generated for');
    });
});
