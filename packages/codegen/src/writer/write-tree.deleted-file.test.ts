/**
 * A generated file deleted by hand while its protected regions held code (docs/codegen.md,
 * "A generated file deleted"): the manifest records which regions of each file held code
 * (userCode), so the next generation says that the file, generated anew with the defaults, lost
 * that code, and how to get it back; a build says it too, as a warning (it does not fail). Every
 * later generation and build says it again (lostUserCode) until one of the regions holds code; a
 * manifest of an older version (no userCode) makes the first command say the file may have held code.
 * With the copy of the regions' code (region-copy.ts, .contract-regions.json), the file is generated
 * anew with that code restored instead; the tests of the warnings remove the copy first (a copy
 * missing: the older behaviour).
 */
import { cpSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { MANIFEST_NAME } from './manifest.js';
import { REGION_COPY_NAME } from './region-copy.js';
import { renameInGeneratedTree } from './rename-generated.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

const out = scratchDirs();

const module = (name: string): GeneratedFile => ({
    path: `generated/architecture/modules/${name}_mod/module.c`,
    content: `// module ${name}\n${region(`protect_vars_${name}`, '\n//TODO\n')}\nvoid _exec(void){\n${region(`protect_exec_${name}`, '\n//TODO\n')}\n}\n`,
});
const NAV = 'generated/architecture/modules/NAV_mod/module.c';
const read = (dir: string, p: string) => readFileSync(join(dir, p), 'utf8');
const userCode = (dir: string) => (JSON.parse(read(dir, MANIFEST_NAME)) as { userCode?: Record<string, string[]> }).userCode;
const lostUserCode = (dir: string) => (JSON.parse(read(dir, MANIFEST_NAME)) as { lostUserCode?: Record<string, string[]> }).lostUserCode;

/** A tree of NAV and LOC whose NAV exec region holds code, generated twice (the manifest records it); `keepCopy` false: without the copy of the regions' code. */
function withCode(keepCopy = false): string {
    const dir = out();
    const tree = [module('LOC'), module('NAV')];
    writeTree(dir, tree);
    writeFileSync(join(dir, NAV), read(dir, NAV).replace(/(protect_exec_NAV\) ENABLED START\*\/)\n\/\/TODO\n/, '$1\nfollow_path();\n'));
    writeTree(dir, tree);
    if (!keepCopy) rmSync(join(dir, REGION_COPY_NAME));
    return dir;
}

describe('writeTree: a generated file deleted while its regions held code', () => {
    it('the manifest records the regions holding code; the file, generated anew, is a warning naming them and how to get the code back, at every generation until the code is back', () => {
        const dir = withCode();
        expect(userCode(dir)).toEqual({ [NAV]: ['protect_exec_NAV'] });
        rmSync(join(dir, NAV));
        const r = writeTree(dir, [module('LOC'), module('NAV')]);
        expect(r.created).toEqual([NAV]);
        expect(r.warnings).toEqual([{
            file: NAV,
            message: `was not there (deleted?), though its protected region(s) protect_exec_NAV held code when it was last generated: generated anew with the defaults, without that code. To get it back, restore the file (\`git checkout -- src-gen/${NAV}\` in the project folder, or \`git restore\`) and generate again`,
        }]);
        expect(read(dir, NAV)).toBe(module('NAV').content);
        // the manifest records the loss: the next generation, and a build, say it again
        expect(userCode(dir)).toEqual({});
        expect(lostUserCode(dir)).toEqual({ [NAV]: ['protect_exec_NAV'] });
        for (const options of [{}, { displacedCode: 'refuse' as const }]) {
            expect(writeTree(dir, [module('LOC'), module('NAV')], options).warnings).toEqual([{
                file: NAV,
                message: expect.stringMatching(/^its protected region\(s\) protect_exec_NAV hold only their defaults since the file was deleted and generated anew .*if you do not want it back, write anything \(a comment\) in one of them to stop this warning$/),
            }]);
        }
        // the code back (restored, or written anew): said no more
        writeFileSync(join(dir, NAV), read(dir, NAV).replace(/(protect_exec_NAV\) ENABLED START\*\/)\n\/\/TODO\n/, '$1\n// rewritten later\n'));
        expect(writeTree(dir, [module('LOC'), module('NAV')]).warnings).toEqual([]);
        expect(lostUserCode(dir)).toBeUndefined();
        expect(writeTree(dir, [module('LOC'), module('NAV')]).warnings).toEqual([]);
    });

    it('a manifest of an older version (no userCode record): the first command says the deleted file may have held code, and so does the next until one of its regions holds code', () => {
        const dir = withCode();
        const manifest = JSON.parse(read(dir, MANIFEST_NAME)) as Record<string, unknown>;
        delete manifest.userCode;
        writeFileSync(join(dir, MANIFEST_NAME), JSON.stringify(manifest));
        rmSync(join(dir, NAV));
        // a build first (in its copy of the project), then generate: both say it
        const buildCopy = out();
        cpSync(dir, buildCopy, { recursive: true });
        for (const [into, options] of [[buildCopy, { displacedCode: 'refuse' as const }], [dir, {}]] as const) {
            expect(writeTree(into, [module('LOC'), module('NAV')], options).warnings).toEqual([{
                file: NAV,
                message: expect.stringMatching(/^was not there \(deleted\?\), and the manifest, written by an older version of ContrACT Studio, does not record whether its protected region\(s\) protect_vars_NAV, protect_exec_NAV held code: generated anew with the defaults\. If they held code, restore the file/),
            }]);
        }
        expect(lostUserCode(dir)).toEqual({ [NAV]: ['protect_vars_NAV', 'protect_exec_NAV'] });
        expect(writeTree(dir, [module('LOC'), module('NAV')]).warnings).toHaveLength(1);
        // a file still there, of an older manifest: nothing to say
        expect(writeTree(dir, [module('LOC'), module('NAV')]).warnings.filter((w) => w.file !== NAV)).toEqual([]);
    });

    it('a build says it too, as a warning (it does not fail); an orphaned copy of the file is named', () => {
        const dir = withCode();
        rmSync(join(dir, NAV));
        mkdirSync(join(dir, 'orphans/generated/architecture/modules/NAV_mod'), { recursive: true });
        writeFileSync(join(dir, `orphans/${NAV}`), '/* an earlier orphan */\n');
        const r = writeTree(dir, [module('LOC'), module('NAV')], { displacedCode: 'refuse' });
        expect(r.errors).toEqual([]);
        expect(r.warnings).toEqual([{ file: NAV, message: expect.stringMatching(/^was not there \(deleted\?\), though its protected region\(s\) protect_exec_NAV held code .*; a copy of it orphaned earlier is in orphans\/generated\/architecture\/modules\/NAV_mod\/module\.c$/) }]);
    });

    it('a deleted file whose regions held only their defaults is generated again silently', () => {
        const dir = withCode();
        rmSync(join(dir, 'generated/architecture/modules/LOC_mod/module.c'));
        const r = writeTree(dir, [module('LOC'), module('NAV')]);
        expect([r.created, r.warnings]).toEqual([['generated/architecture/modules/LOC_mod/module.c'], []]);
    });

    it('the record follows a rename of the module (path and region IDs)', async () => {
        const dir = withCode();
        await renameInGeneratedTree(dir, 'NAV', 'NVX');
        const NVX = 'generated/architecture/modules/NVX_mod/module.c';
        expect(userCode(dir)).toEqual({ [NVX]: ['protect_exec_NVX'] });
        rmSync(join(dir, NVX));
        expect(writeTree(dir, [module('LOC'), module('NVX')]).warnings).toEqual([{ file: NVX, message: expect.stringMatching(/^was not there \(deleted\?\), though its protected region\(s\) protect_exec_NVX held code /) }]);
    });
});
