/**
 * `contract rename` of an enumeration (`Mode`) and of an enumeration member (`Mode.AUTO`): the
 * `.contract` files follow, the generated `common/Shared<Enum>.h` moves to the new name, and the
 * enumeration's C names in the user code of the protected regions (the type, its generated
 * functions `eq_Mode`..., its constants `Mode_AUTO`) are rewritten the way a datatype's are; what
 * is left (comments, strings, an `#include` of the old header) is listed. The project still builds.
 * A rename killed half-way is journaled and finished by the next generate.
 */
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { identifierRenames, parseRegions, renameIdentifiersInGeneratedTree, renameInGeneratedTree, sha256, writeRenameJournal } from '@contract-studio/codegen';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const COMMON = 'src-gen/generated/architecture/common';
const CTL = 'src-gen/generated/architecture/modules/CTL_mod/module.c';
/** User code of CTL's exec region: the enumeration's type, function and constants, and mentions in text. */
const USER_CODE = 'Mode seen = Mode_AUTO; if (eq_Mode(&seen, &mode) == 0) { seen = Mode_SAFE; } (void)seen; /* Mode_SAFE when not AUTO */ const char *why = "Mode_AUTO"; (void)why;';

let root: string;

function regions(file: string): Map<string, string> {
    const text = readFileSync(file, 'latin1');
    return new Map(parseRegions(text, file).regions.map((r) => [r.id, r.content]));
}

/** `contract new NAME` with an enumeration Mode used by CTL's parameter, generated, user code in CTL's exec region. */
async function projectWithEnumeration(name: string): Promise<string> {
    expect(await runCli(['new', name], capture(root))).toBe(0);
    const dir = join(root, name);
    writeFileSync(join(dir, 'datatype.contract'), `${readFileSync(join(dir, 'datatype.contract'), 'utf8')}enum Mode { AUTO, SAFE }\n`);
    const module2 = join(dir, 'module2.contract');
    writeFileSync(module2, readFileSync(module2, 'utf8').replace('parameters { Position goal = {1.0, 2.0, 0.0} :0; }', 'parameters { Position goal = {1.0, 2.0, 0.0} :0; Mode mode = Mode.AUTO :1; }'));
    const io = capture(root);
    expect(await runCli(['generate', name], io), io.stderr).toBe(0);
    const file = join(dir, CTL);
    const text = readFileSync(file, 'latin1');
    writeFileSync(file, text.replace('/*PROTECTED REGION ID(protect_exec_CTL) ENABLED START*/', `/*PROTECTED REGION ID(protect_exec_CTL) ENABLED START*/\n    ${USER_CODE}`), 'latin1');
    return dir;
}

beforeAll(async () => {
    root = await makeSeededScratch('contract-rename-enum-');
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('contract rename of an enumeration', () => {
    let dir: string;

    it('renames enumeration Mode to Drive: .contract files, common/SharedMode.h -> SharedDrive.h, its C names in the regions\' code', async () => {
        dir = await projectWithEnumeration('robot');
        expect(existsSync(join(dir, COMMON, 'SharedMode.h'))).toBe(true);
        const io = capture(root);
        expect(await runCli(['rename', 'robot', 'Mode', 'Drive'], io), io.stderr).toBe(0);
        expect(io.stdout).toContain('renamed enumeration Mode -> Drive: 3 occurrence(s) in 2 file(s)');
        expect(io.stdout).toContain('  generated/architecture/common/SharedMode.h -> generated/architecture/common/SharedDrive.h\n');
        expect(io.stdout).toMatch(/robot\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+: protected region protect_exec_CTL: 4 use\(s\) of Mode \(or its functions and constants\) renamed\n/);
        expect(io.stderr).toMatch(/generated robot\/src-gen: \d+ created, \d+ updated, \d+ kept, 0 orphaned, 0 error\(s\)/);
        // the comment and the string keep the old name: noted, not changed
        expect(io.stderr).toMatch(/note: robot\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+: protected region protect_exec_CTL mentions Mode_SAFE \(the old name\) in a comment: not changed\n/);
        expect(io.stderr).toMatch(/note: .*mentions Mode_AUTO \(the old name\) in a string or character literal: not changed\n/);
        expect(io.stderr).not.toContain('warning:');
        expect(readFileSync(join(dir, 'datatype.contract'), 'utf8')).toContain('enum Drive { AUTO, SAFE }');
        expect(readFileSync(join(dir, 'module2.contract'), 'utf8')).toContain('Drive mode = Drive.AUTO :1;');
        expect(existsSync(join(dir, COMMON, 'SharedMode.h'))).toBe(false);
        expect(readFileSync(join(dir, COMMON, 'SharedDrive.h'), 'latin1')).toContain('typedef enum Drive { Drive_AUTO = 0, Drive_SAFE = 1 } Drive;');
        expect(regions(join(dir, CTL)).get('protect_exec_CTL')).toContain(
            'Drive seen = Drive_AUTO; if (eq_Drive(&seen, &mode) == 0) { seen = Drive_SAFE; } (void)seen; /* Mode_SAFE when not AUTO */ const char *why = "Mode_AUTO"; (void)why;');
        expect(existsSync(join(dir, 'src-gen/orphans'))).toBe(false);
    }, 120_000);

    it('renames member Drive.SAFE to HALT: its constant in the regions\' code follows (not the bare word, not another member\'s)', async () => {
        const io = capture(root);
        expect(await runCli(['rename', 'robot', 'Drive.SAFE', 'HALT'], io), io.stderr).toBe(0);
        expect(io.stdout).toContain('renamed enumeration member SAFE -> HALT: 1 occurrence(s) in 1 file(s)');
        expect(io.stdout).toMatch(/CTL_mod\/module\.c:\d+: protected region protect_exec_CTL: 1 use\(s\) of Drive_SAFE renamed\n/);
        expect(io.stdout).not.toContain('path(s) moved');
        expect(io.stderr).toMatch(/, 0 orphaned, 0 error\(s\)/);
        expect(io.stderr).not.toContain('warning:');
        expect(readFileSync(join(dir, 'datatype.contract'), 'utf8')).toContain('enum Drive { AUTO, HALT }');
        expect(regions(join(dir, CTL)).get('protect_exec_CTL')).toContain('Drive seen = Drive_AUTO; if (eq_Drive(&seen, &mode) == 0) { seen = Drive_HALT; }');
        // an unknown member: what there is is listed, nothing changed
        const unknown = capture(root);
        expect(await runCli(['rename', 'robot', 'Drive.FAST', 'QUICK'], unknown)).toBe(1);
        expect(unknown.stderr).toBe("contract rename: enumeration Drive has no member 'FAST'; its members: AUTO, HALT; nothing was renamed\n");
    }, 120_000);

    it('the renamed project builds with gcc: the user code uses the new C names', async () => {
        const io = capture(root);
        expect(await runCli(['build', 'robot', '--sandbox', 'none'], io), io.stderr).toBe(0);
    }, 300_000);

    it('an #include of the old header in a region cannot be rewritten (it is a string): listed as a use in code, exit 1', async () => {
        const file = join(dir, CTL);
        writeFileSync(file, readFileSync(file, 'latin1').replace('/*PROTECTED REGION ID(protect_additional_import_CTL) ENABLED START*/', '/*PROTECTED REGION ID(protect_additional_import_CTL) ENABLED START*/\n#include "SharedDrive.h"'), 'latin1');
        const io = capture(root);
        expect(await runCli(['rename', 'robot', 'Drive', 'Gear'], io)).toBe(1);
        expect(io.stderr).toMatch(/warning: robot\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+: protected region protect_additional_import_CTL still uses SharedDrive \(the old name\) in an #include: change it by hand, the build fails until then\n/);
        expect(regions(join(dir, CTL)).get('protect_exec_CTL')).toContain('Gear seen = Gear_AUTO;');
    }, 120_000);

    it('killed after the tree was carried over, before the .contract files: the next generate finishes it, the user code renamed once', async () => {
        const killed = await projectWithEnumeration('killed');
        const contract = (f: string) => readFileSync(join(killed, f), 'utf8');
        const renamed = new Map([
            ['datatype.contract', contract('datatype.contract').replace('enum Mode {', 'enum Drive {')],
            ['module2.contract', contract('module2.contract').replace('Mode mode = Mode.AUTO', 'Drive mode = Drive.AUTO')],
        ]);
        // what `contract rename killed Mode Drive` journals, then does, up to where a SIGKILL stops it
        const srcGen = join(killed, 'src-gen');
        const identifiers = identifierRenames('enumeration', 'Mode', 'Drive', { members: ['AUTO', 'SAFE'] });
        writeRenameJournal(srcGen, {
            version: 1, kind: 'enumeration', oldName: 'Mode', newName: 'Drive', generatedNames: true, identifiers: [...identifiers],
            files: [...renamed].map(([path, after]) => ({ path, before: sha256(readFileSync(join(killed, path))), after })),
        });
        await renameInGeneratedTree(srcGen, 'Mode', 'Drive');
        renameIdentifiersInGeneratedTree(srcGen, identifiers);

        const io = capture(root);
        expect(await runCli(['generate', 'killed'], io), io.stderr).toBe(0);
        expect(io.stderr).toContain('finished the rename of enumeration Mode -> Drive that was interrupted (its journal src-gen/.contract-rename.json): 2 file(s) written, 0 already renamed');
        expect(io.stderr).toMatch(/, 0 orphaned, 0 error\(s\)/);
        for (const [f, text] of renamed) expect(contract(f)).toBe(text);
        expect(existsSync(join(srcGen, 'SharedMode.h'))).toBe(false);
        expect(existsSync(join(killed, COMMON, 'SharedDrive.h'))).toBe(true);
        expect(regions(join(killed, CTL)).get('protect_exec_CTL')).toContain('Drive seen = Drive_AUTO; if (eq_Drive(&seen, &mode) == 0) { seen = Drive_SAFE; }');
        expect(existsSync(join(srcGen, '.contract-rename.json'))).toBe(false);
    }, 120_000);
});
