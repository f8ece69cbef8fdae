/** Carry-over of a renamed entity in a generated tree (shared by the IDE and `contract rename`). */
import { describe, it, expect } from 'vitest';
import { mkdirSync, writeFileSync, readFileSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { renameInGeneratedTree, renameRegionId } from './rename-generated.js';
import { writeTree } from './write-tree.js';
import { MANIFEST_NAME } from './manifest.js';
import { scratchDirs } from '../test-support/temp-dir.js';

const scratch = scratchDirs('rename-generated-');

describe('renameRegionId', () => {
    it('renames only whole name parts', () => {
        expect(renameRegionId('protect_init_MAA', 'MAA', 'MAB')).toBe('protect_init_MAB');
        expect(renameRegionId('protect_eq_TypeA', 'TypeA', 'Pose')).toBe('protect_eq_Pose');
        expect(renameRegionId('protect_eq_TypeAB', 'TypeA', 'Pose')).toBe('protect_eq_TypeAB');
        expect(renameRegionId('MAA.init', 'MAA', 'XYZ')).toBe('XYZ.init');
    });
});

describe('renameInGeneratedTree', () => {
    it('moves the module folder and rewrites its region IDs, keeping user code', async () => {
        const root = scratch();
        const mod = join(root, 'generated', 'architecture', 'modules', 'MSC_mod');
        mkdirSync(mod, { recursive: true });
        const body = '/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/\nmy_code();\n/*PROTECTED REGION END*/\n' +
            '/*PROTECTED REGION ID(protect_exec_MSCX) ENABLED START*/\nother();\n/*PROTECTED REGION END*/\n';
        writeFileSync(join(mod, 'module.c'), body);
        const report = await renameInGeneratedTree(root, 'MSC', 'MSK');
        const moved = join(root, 'generated', 'architecture', 'modules', 'MSK_mod', 'module.c');
        expect(existsSync(mod)).toBe(false);
        const text = readFileSync(moved, 'utf8');
        expect(text).toContain('ID(protect_init_MSK) ENABLED START*/\nmy_code();');
        expect(text).toContain('ID(protect_exec_MSCX)');
        expect(report.regionIds).toEqual([{ file: 'generated/architecture/modules/MSK_mod/module.c', from: 'protect_init_MSC', to: 'protect_init_MSK' }]);
    });

    it('an enumeration moves its Shared<Enum>.h only: no region ID (one whose role is its name: an enumeration named init), no module\'s folder of its name', async () => {
        const root = scratch();
        const common = join(root, 'generated', 'architecture', 'common');
        const mod = join(root, 'generated', 'architecture', 'modules', 'CTL_mod');
        mkdirSync(common, { recursive: true });
        mkdirSync(mod, { recursive: true });
        writeFileSync(join(common, 'Sharedinit.h'), 'typedef enum init { init_A = 0 } init;\n');
        const body = '/*PROTECTED REGION ID(protect_init_CTL) ENABLED START*/\nmy_code();\n/*PROTECTED REGION END*/\n';
        writeFileSync(join(mod, 'module.c'), body);
        const report = await renameInGeneratedTree(root, 'init', 'Phase', 'enumeration');
        expect(report.movedPaths).toEqual([{ from: 'generated/architecture/common/Sharedinit.h', to: 'generated/architecture/common/SharedPhase.h' }]);
        expect(report.regionIds).toEqual([]);
        expect(readFileSync(join(mod, 'module.c'), 'utf8')).toBe(body);
        // an enumeration named like a module moves no file of the module's
        expect(await renameInGeneratedTree(root, 'CTL', 'Ctl', 'enumeration')).toMatchObject({ movedPaths: [], regionIds: [] });
        expect(existsSync(join(mod, 'module.c'))).toBe(true);
        // the module itself (kind told, or not): its folder and IDs
        expect((await renameInGeneratedTree(root, 'CTL', 'CTX', 'module')).regionIds).toHaveLength(1);
        expect((await renameInGeneratedTree(root, 'CTX', 'CTY')).movedPaths).toEqual([{ from: 'generated/architecture/modules/CTX_mod', to: 'generated/architecture/modules/CTY_mod' }]);
    });

    it('leaves orphans/ as it is: user code moved aside keeps the name and IDs of where it came from', async () => {
        const root = scratch();
        const orphan = join(root, 'orphans', 'generated', 'architecture', 'modules', 'MSC_mod');
        mkdirSync(orphan, { recursive: true });
        const body = '/* orphaned from generated/architecture/modules/MSC_mod/module.c */\n/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/\nold();\n/*PROTECTED REGION END*/\n';
        writeFileSync(join(orphan, 'module.c'), body);
        const report = await renameInGeneratedTree(root, 'MSC', 'MSK');
        expect(report.movedPaths).toEqual([]);
        expect(readFileSync(join(orphan, 'module.c'), 'utf8')).toBe(body);
    });

    it('refuses to overwrite an existing target', async () => {
        const root = scratch();
        mkdirSync(join(root, 'MSC_mod'));
        mkdirSync(join(root, 'MSK_mod'));
        await expect(renameInGeneratedTree(root, 'MSC', 'MSK')).rejects.toThrow(/already exists/);
    });
});

describe('renameInGeneratedTree for datatypes and functions', () => {
    it('renames Shared<T>.h / SharedFunction<f>.h and their region IDs, leaving other entities alone', async () => {
        const root = scratch();
        const common = join(root, 'generated', 'architecture', 'common');
        mkdirSync(common, { recursive: true });
        const region = (id: string, body: string) => `/*PROTECTED REGION ID(${id}) ENABLED START*/\n${body}\n/*PROTECTED REGION END*/\n`;
        writeFileSync(join(common, 'SharedTypeF.h'), region('protect_eq_TypeF', 'return a->fufu == b->fufu;'));
        writeFileSync(join(common, 'SharedTypeA.h'), region('protect_eq_TypeA', 'keep'));
        writeFileSync(join(common, 'SharedFunctiondoit.h'), region('protect_function_impl_doit', 'do_it_by_hand();'));
        await renameInGeneratedTree(root, 'TypeF', 'Pose');
        await renameInGeneratedTree(root, 'doit', 'execute');
        expect(readFileSync(join(common, 'SharedPose.h'), 'utf8')).toBe(region('protect_eq_Pose', 'return a->fufu == b->fufu;'));
        expect(readFileSync(join(common, 'SharedFunctionexecute.h'), 'utf8')).toBe(region('protect_function_impl_execute', 'do_it_by_hand();'));
        expect(readFileSync(join(common, 'SharedTypeA.h'), 'utf8')).toBe(region('protect_eq_TypeA', 'keep'));
        expect(existsSync(join(common, 'SharedTypeF.h'))).toBe(false);
    });

    it('refuses names that are not identifiers', async () => {
        await expect(renameInGeneratedTree(tmpdir(), '../x', 'y')).rejects.toThrow(/invalid entity name/);
    });
});

describe('renameInGeneratedTree keeps user code byte for byte', () => {
    it('in any encoding, and in markers written with extra blanks', async () => {
        const root = scratch();
        const mod = join(root, 'generated', 'architecture', 'modules', 'MSC_mod');
        mkdirSync(mod, { recursive: true });
        // latin1 bytes that are not valid UTF-8, and a marker pasted with blanks and a line break
        const before = Buffer.concat([
            Buffer.from('/*PROTECTED REGION ID( protect_init_MSC ) ENABLED\n START*/\n/* caf', 'latin1'),
            Buffer.from([0xe9, 0xff]),
            Buffer.from(' */\n/*PROTECTED REGION END*/\n', 'latin1'),
        ]);
        writeFileSync(join(mod, 'module.c'), before);
        const report = await renameInGeneratedTree(root, 'MSC', 'MSK');
        const after = readFileSync(join(root, 'generated', 'architecture', 'modules', 'MSK_mod', 'module.c'));
        expect(after).toEqual(Buffer.from(before.toString('latin1').replace('protect_init_MSC', 'protect_init_MSK'), 'latin1'));
        expect(report.regionIds).toEqual([{ file: 'generated/architecture/modules/MSK_mod/module.c', from: 'protect_init_MSC', to: 'protect_init_MSK' }]);
    });

    it('moves the manifest entries with the files, so that a default region is still recognised as one', async () => {
        const root = scratch();
        const path = (m: string) => `generated/architecture/modules/${m}_mod/module.c`;
        // protect_init holds a generated default that is not a //TODO: only the manifest knows it is no user code
        const init = (m: string) => `/*PROTECTED REGION ID(protect_init_${m}) ENABLED START*/\nreturn 0;\n/*PROTECTED REGION END*/\n`;
        const exec = (m: string) => `/*PROTECTED REGION ID(protect_exec_${m}) ENABLED START*/\nstep();\n/*PROTECTED REGION END*/\n`;
        writeTree(root, [{ path: path('MSC'), content: init('MSC') + exec('MSC') }]);
        await renameInGeneratedTree(root, 'MSC', 'MSK');
        const manifest = JSON.parse(readFileSync(join(root, MANIFEST_NAME), 'utf8')) as { files: Record<string, Record<string, string>> };
        expect(Object.keys(manifest.files)).toEqual([path('MSK')]);
        expect(Object.keys(manifest.files[path('MSK')]!).sort()).toEqual(['protect_exec_MSK', 'protect_init_MSK']);
        // the next generation no longer has protect_init: its default content is dropped, not orphaned
        const r = writeTree(root, [{ path: path('MSK'), content: exec('MSK') }]);
        expect(r.orphaned).toEqual([]);
        expect(r.warnings).toEqual([]);
    });
});

describe('renameInGeneratedTree and the manifest', () => {
    const path = (m: string) => `generated/architecture/modules/${m}_mod/module.c`;
    const content = (m: string) => `// module\nint step(void);\n/*PROTECTED REGION ID(protect_exec_${m}) ENABLED START*/\nreturn 0;\n/*PROTECTED REGION END*/\nint done;\n`;
    const append = (root: string, m: string, text: string) => writeFileSync(join(root, path(m)), readFileSync(join(root, path(m)), 'utf8') + text);

    it('writes the manifest in its own line-ending style: a CRLF checkout (core.autocrlf=true) keeps CRLF, as generate does', async () => {
        const root = scratch();
        writeTree(root, [{ path: path('MSC'), content: content('MSC') }]);
        const manifestPath = join(root, MANIFEST_NAME);
        writeFileSync(manifestPath, readFileSync(manifestPath, 'utf8').replace(/\n/g, '\r\n'));
        await renameInGeneratedTree(root, 'MSC', 'MSK');
        const after = readFileSync(manifestPath, 'utf8');
        expect(after).toContain('protect_exec_MSK');
        expect(after).toContain('\r\n');
        expect(after.replace(/\r\n/g, '')).not.toContain('\n');
        // and generate then finds nothing to rewrite in it for its line endings
        writeTree(root, [{ path: path('MSK'), content: content('MSK') }]);
        expect(readFileSync(manifestPath, 'utf8')).toBe(after);
    });

    it('carries the skeleton line hashes with the region IDs: a later edit outside the regions is named at its own line', async () => {
        const root = scratch();
        writeTree(root, [{ path: path('MSC'), content: content('MSC') }]);
        await renameInGeneratedTree(root, 'MSC', 'MSK');
        const manifest = JSON.parse(readFileSync(join(root, MANIFEST_NAME), 'utf8')) as { skeletonLines: Record<string, string> };
        expect(Object.keys(manifest.skeletonLines)).toEqual([path('MSK')]);
        append(root, 'MSK', 'int mine;\n');
        // the model changed too (a line at the top): the warning names the user's line 7, not line 1
        const r = writeTree(root, [{ path: path('MSK'), content: '// a model change\n' + content('MSK') }]);
        expect(r.warnings).toHaveLength(1);
        expect(r.warnings[0]).toMatchObject({ line: 7 });
        expect(r.warnings[0]!.message).toContain('(line 7 not written by the generator)');
    });

    it('drops them for a file edited outside its regions before the rename: the warning names the first line that differs', async () => {
        const root = scratch();
        writeTree(root, [{ path: path('MSC'), content: content('MSC') }]);
        append(root, 'MSC', 'int mine;\n');
        await renameInGeneratedTree(root, 'MSC', 'MSK');
        const manifest = JSON.parse(readFileSync(join(root, MANIFEST_NAME), 'utf8')) as { skeletonLines: Record<string, string> };
        expect(manifest.skeletonLines).toEqual({});
        const r = writeTree(root, [{ path: path('MSK'), content: content('MSK') }]);
        expect(r.warnings[0]).toMatchObject({ line: 7 });
        expect(r.warnings[0]!.message).toContain('(first line that differs from the regenerated file: 7)');
    });
});
