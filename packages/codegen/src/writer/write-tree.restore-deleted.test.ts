/**
 * A generated file deleted by hand gets its protected regions' code back (docs/codegen.md, "A
 * generated file deleted"): the copy of the regions' user code (region-copy.ts,
 * src-gen/.contract-regions.json), written by every generation and by a build's record
 * (record-user-code.ts), fills the file generated anew. A file emptied on purpose is not restored;
 * a copy missing, corrupt or hostile restores nothing and the deletion is said as before.
 */
import { existsSync, mkdirSync, readFileSync, rmSync, statSync, symlinkSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { MANIFEST_NAME } from './manifest.js';
import { recordUserCode, userCodeOf, userCodeOfFiles } from './record-user-code.js';
import { MAX_COPY_BYTES, REGION_COPY_NAME } from './region-copy.js';
import { renameInGeneratedTree } from './rename-generated.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

const out = scratchDirs();

const module = (name: string): GeneratedFile => ({
    path: `generated/architecture/modules/${name}_mod/module.c`,
    content: `// module ${name}\n${region(`protect_vars_${name}`, '\n//TODO\n')}\nvoid _exec(void){\n${region(`protect_exec_${name}`, '\n//TODO\n')}\n}\n`,
});
const NAV = 'generated/architecture/modules/NAV_mod/module.c';
const tree = () => [module('LOC'), module('NAV')];
const read = (dir: string, p: string) => readFileSync(join(dir, p), 'utf8');
const manifest = (dir: string) => JSON.parse(read(dir, MANIFEST_NAME)) as { userCode?: Record<string, string[]>; lostUserCode?: Record<string, string[]> };
const writeExec = (dir: string, code: string) =>
    writeFileSync(join(dir, NAV), read(dir, NAV).replace(/(protect_exec_NAV\) ENABLED START\*\/)\n[\s\S]*?(\/\*PROTECTED REGION END)/, `$1\n${code}\n$2`));
const RESTORED = `was not there (deleted?): restored 1 protected region(s) of src-gen/${NAV} (protect_exec_NAV) from the last generation's copy (src-gen/${REGION_COPY_NAME}), as they were when it was last generated or built; check them`;

/** Generated once, code written in NAV's exec region, then generated again (or only recorded, as a build does). */
function withCode(record: 'generate' | 'build' = 'generate'): string {
    const dir = out();
    writeTree(dir, tree());
    writeExec(dir, 'follow_path(); // é');
    if (record === 'generate') writeTree(dir, tree());
    else recordUserCode(dir);
    return dir;
}

describe('a generated file deleted: its regions restored from the last generation\'s copy', () => {
    it('generate restores the code of the regions that held code, says so, and records it again', () => {
        const dir = withCode();
        expect(JSON.parse(read(dir, REGION_COPY_NAME)).files).toEqual({ [NAV]: { protect_exec_NAV: '\nfollow_path(); // é\n' } });
        rmSync(join(dir, NAV));
        const r = writeTree(dir, tree());
        expect(r.created).toEqual([NAV]);
        expect(r.warnings).toEqual([{ file: NAV, message: RESTORED }]);
        expect(read(dir, NAV)).toContain('ENABLED START*/\nfollow_path(); // é\n/*PROTECTED REGION END');
        expect(manifest(dir).userCode).toEqual({ [NAV]: ['protect_exec_NAV'] });
        expect(manifest(dir).lostUserCode).toBeUndefined();
        expect(writeTree(dir, tree()).warnings).toEqual([]);
    });

    it('a build\'s generation (its private copy) restores it too', () => {
        const dir = withCode();
        rmSync(join(dir, NAV));
        const r = writeTree(dir, tree(), { displacedCode: 'refuse' });
        expect([r.errors, r.warnings]).toEqual([[], [{ file: NAV, message: RESTORED }]]);
        expect(read(dir, NAV)).toContain('follow_path();');
    });

    it('code written after the last generate and only built (recordUserCode) is restored: the manifest and the copy learn it without a generate', () => {
        const dir = out();
        writeTree(dir, tree());
        expect(manifest(dir).userCode).toEqual({});
        expect(existsSync(join(dir, REGION_COPY_NAME))).toBe(false);
        writeExec(dir, 'lab_code();');
        expect(recordUserCode(dir).written).toEqual([MANIFEST_NAME, REGION_COPY_NAME]);
        expect(manifest(dir).userCode).toEqual({ [NAV]: ['protect_exec_NAV'] });
        // nothing changed: nothing rewritten
        const before = [statSync(join(dir, MANIFEST_NAME)).mtimeMs, statSync(join(dir, REGION_COPY_NAME)).mtimeMs];
        expect(recordUserCode(dir).written).toEqual([]);
        expect(writeTree(dir, tree()).filesWritten).toBe(0);
        expect([statSync(join(dir, MANIFEST_NAME)).mtimeMs, statSync(join(dir, REGION_COPY_NAME)).mtimeMs]).toEqual(before);
        // deleted: its record stays (a build records nothing for a missing file), and generate restores it
        rmSync(join(dir, NAV));
        expect(recordUserCode(dir).written).toEqual([]);
        expect(writeTree(dir, tree()).warnings).toEqual([{ file: NAV, message: RESTORED }]);
        expect(read(dir, NAV)).toContain('lab_code();');
    });

    it('a file whose regions the user emptied on purpose (present, regions back to their defaults) is generated again with the defaults, silently', () => {
        for (const record of ['generate', 'build'] as const) {
            const dir = withCode();
            writeExec(dir, '//TODO');
            if (record === 'generate') writeTree(dir, tree());
            else recordUserCode(dir);
            expect(existsSync(join(dir, REGION_COPY_NAME))).toBe(false);
            rmSync(join(dir, NAV));
            const r = writeTree(dir, tree());
            expect([r.created, r.warnings]).toEqual([[NAV], []]);
            expect(read(dir, NAV)).toBe(module('NAV').content);
        }
    });

    it('the copy follows a rename of the module (path and region IDs)', async () => {
        const dir = withCode();
        await renameInGeneratedTree(dir, 'NAV', 'NVX');
        const NVX = 'generated/architecture/modules/NVX_mod/module.c';
        rmSync(join(dir, NVX));
        const r = writeTree(dir, [module('LOC'), module('NVX')]);
        expect(r.warnings).toEqual([{ file: NVX, message: expect.stringMatching(/^was not there \(deleted\?\): restored 1 protected region\(s\) of src-gen\/.*NVX_mod\/module\.c \(protect_exec_NVX\)/) }]);
        expect(read(dir, NVX)).toContain('follow_path();');
    });
});

describe('the copy missing, corrupt or hostile: nothing restored from it, the deletion said as before, never a crash', () => {
    const LOST = /^was not there \(deleted\?\), though its protected region\(s\) protect_exec_NAV held code when it was last generated: generated anew with the defaults, without that code/;
    const cases: [string, (dir: string) => void, RegExp | undefined][] = [
        ['missing', (dir) => rmSync(join(dir, REGION_COPY_NAME)), undefined],
        ['not JSON', (dir) => writeFileSync(join(dir, REGION_COPY_NAME), '{"version": 1, "files": {'), /^unreadable \(/],
        ['of another format', (dir) => writeFileSync(join(dir, REGION_COPY_NAME), '[1,2]'), /^of an unknown format/],
        ['a link', (dir) => { rmSync(join(dir, REGION_COPY_NAME)); symlinkSync('/etc/passwd', join(dir, REGION_COPY_NAME)); }, /^not read \(.*link/],
        ['too large', (dir) => writeFileSync(join(dir, REGION_COPY_NAME), Buffer.alloc(MAX_COPY_BYTES + 1, 32)), /^not read \(.*larger than/],
    ];
    for (const [what, spoil, problem] of cases) {
        it(`a copy ${what}`, () => {
            const dir = withCode();
            spoil(dir);
            rmSync(join(dir, NAV));
            const r = writeTree(dir, tree());
            expect(r.created).toEqual([NAV]);
            expect(read(dir, NAV)).toBe(module('NAV').content);
            const warnings = r.warnings.map((w) => `${w.file}: ${w.message}`);
            expect(warnings.some((w) => w.startsWith(`${NAV}: `) && LOST.test(w.slice(NAV.length + 2)))).toBe(true);
            if (problem) {
                const copyWarning = r.warnings.find((w) => w.file === REGION_COPY_NAME);
                expect(copyWarning?.message).toMatch(problem);
                expect(copyWarning?.message).toContain('no protected region of a deleted generated file can be restored from it');
            }
            if (what === 'a link') {
                // refused, never written through
                expect(r.errors.some((e) => e.file === REGION_COPY_NAME)).toBe(true);
                expect(readFileSync('/etc/passwd', 'utf8')).not.toContain('follow_path');
            }
        });
    }

    it('entries that are not the tree\'s files, unknown region IDs and contents holding region markers are never used', () => {
        const dir = withCode();
        const forged = { version: 1, files: {
            '../../outside.c': { protect_exec_NAV: 'evil();' },
            [NAV]: { protect_exec_NAV: '\n/*PROTECTED REGION END*/ evil();\n', protect_elsewhere_NAV: 'evil();', 'bad id': 'evil();' },
            'generated/architecture/modules/LOC_mod/module.c': { protect_exec_LOC: 42 },
        } };
        writeFileSync(join(dir, REGION_COPY_NAME), JSON.stringify(forged));
        rmSync(join(dir, NAV));
        const r = writeTree(dir, tree());
        expect(r.errors).toEqual([]);
        expect(read(dir, NAV)).toBe(module('NAV').content);
        expect(r.warnings.find((w) => w.file === NAV)?.message).toMatch(LOST);
        expect(existsSync(join(dir, '../../outside.c'))).toBe(false);
        // written anew from the files as they are (none holds code now)
        expect(existsSync(join(dir, REGION_COPY_NAME))).toBe(false);
    });

    it('a copy in a tree without a manifest is not read', () => {
        const dir = withCode();
        rmSync(join(dir, MANIFEST_NAME));
        mkdirSync(join(dir, 'generated/architecture/modules/NAV_mod'), { recursive: true });
        rmSync(join(dir, NAV));
        const r = writeTree(dir, tree());
        expect(read(dir, NAV)).toBe(module('NAV').content);
        expect(r.warnings.filter((w) => w.file === NAV)).toEqual([]);
    });
});

describe('userCodeOfFiles: what the IDE\'s delete of a folder says of its generated files', () => {
    it('the files holding code, each with its regions, restorable once recorded; files without code left out; one record for all', () => {
        const dir = out();
        writeTree(dir, tree());
        writeExec(dir, 'lab_code();');
        const LOC = 'generated/architecture/modules/LOC_mod/module.c';
        const held = userCodeOfFiles(dir, [LOC, NAV, 'generated/not/there.c']);
        expect([...held]).toEqual([[NAV, { regions: ['protect_exec_NAV'], restorable: true }]]);
        expect(userCodeOf(dir, NAV)).toEqual({ regions: ['protect_exec_NAV'], restorable: true });
        expect(userCodeOf(dir, LOC)).toEqual({ regions: [], restorable: false });
        // no tree there: nothing
        expect(userCodeOfFiles(join(dir, 'missing'), [NAV]).size).toBe(0);
    });
});
