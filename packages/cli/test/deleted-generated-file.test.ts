/**
 * The lab field test's defects (docs/codegen.md "A generated file deleted", "Orphans"), with real
 * gcc, make and ld in the bwrap sandbox:
 * - generate once, write code in protect_exec_CTL, build (never generate again), delete
 *   CTL's module.c: the build, the run, then generate, bring that code back from the last generation's copy
 *   (src-gen/.contract-regions.json) and say so; they were silent and generated the defaults;
 * - a copy spoiled: generate says so and that the deleted file's code is lost (the build recorded it);
 * - a helper function written outside the regions, moved to src-gen/orphans/ by generate: the
 *   link error missing it names that copy and how to bring it back.
 */
import { existsSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const CTL = 'src-gen/generated/architecture/modules/CTL_mod/module.c';
const COPY = 'src-gen/.contract-regions.json';
const LAB_CODE = 'static int lab_steps = 0; lab_steps++; (void)lab_steps; /* the student\'s code */';

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-lost-');
}, 240_000);
afterAll(() => removeSeededScratch(root));

/** A new project, generated once, with the student's code written in protect_exec_CTL (no generate after). */
async function labProject(name: string): Promise<string> {
    expect(await runCli(['new', name], capture(root))).toBe(0);
    expect(await runCli(['generate', name], capture(root))).toBe(0);
    const file = join(root, name, CTL);
    const text = readFileSync(file, 'utf8');
    writeFileSync(file, text.replace('//TODO : implement the activity of one period, one state per call', LAB_CODE));
    return join(root, name);
}

describe('a generated file deleted after code was written and built (never generated again)', () => {
    it('the build records the code; after the deletion the build, the run and generate restore it from the copy and say so', async () => {
        const dir = await labProject('lab');
        const built = capture(root);
        expect(await runCli(['build', 'lab'], built)).toBe(0);
        expect(JSON.parse(readFileSync(join(dir, 'src-gen/.contract-manifest.json'), 'utf8')).userCode).toEqual({ 'generated/architecture/modules/CTL_mod/module.c': ['protect_exec_CTL'] });
        expect(readFileSync(join(dir, COPY), 'utf8')).toContain('lab_steps++');
        rmSync(join(dir, CTL));
        const restored = /restored 1 protected region\(s\) of src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c \(protect_exec_CTL\) from the last generation's copy/;
        const rebuilt = capture(root);
        expect(await runCli(['build', 'lab'], rebuilt)).toBe(0);
        expect(rebuilt.stderr + rebuilt.stdout).toMatch(restored);
        expect(existsSync(join(dir, CTL))).toBe(false); // a build writes no generated file of the project
        const ran = capture(root);
        expect(await runCli(['run', 'lab', '--duration', '2s'], ran)).toBe(0);
        expect(ran.stderr + ran.stdout).toMatch(restored);
        const generated = capture(root);
        expect(await runCli(['generate', 'lab'], generated)).toBe(0);
        expect(generated.stderr + generated.stdout).toMatch(restored);
        expect(readFileSync(join(dir, CTL), 'utf8')).toContain(LAB_CODE);
    }, 240_000);

    it('a copy spoiled (not JSON): generate says so and that the deleted file\'s code is not back, as the build recorded it', async () => {
        const dir = await labProject('lab-spoiled');
        expect(await runCli(['build', 'lab-spoiled'], capture(root))).toBe(0);
        writeFileSync(join(dir, COPY), '{ not json');
        rmSync(join(dir, CTL));
        const generated = capture(root);
        expect(await runCli(['generate', 'lab-spoiled'], generated)).toBe(0);
        const said = generated.stderr + generated.stdout;
        expect(said).toContain(`${COPY}: unreadable (`);
        expect(said).toMatch(/module\.c: was not there \(deleted\?\), though its protected region\(s\) protect_exec_CTL held code when it was last generated: generated anew with the defaults, without that code/);
        expect(readFileSync(join(dir, CTL), 'utf8')).not.toContain('lab_steps');
        expect(existsSync(join(dir, COPY))).toBe(false); // written anew: no file holds code now
    }, 240_000);
});

describe('a helper function moved to src-gen/orphans/: the link error says where it went', () => {
    it('undefined reference to `clamp`: names the orphans copy and how to bring it back', async () => {
        const dir = await labProject('lab-helper');
        const file = join(dir, CTL);
        let text = readFileSync(file, 'utf8');
        text = text.replace(/(protect_internal_functions_decl_CTL\) ENABLED START\*\/\n)\/\/TODO/, '$1double clamp(double v, double lo, double hi);');
        text = text.replace(LAB_CODE, 'double kept = clamp(2.0, 0.0, 1.0); (void)kept;');
        text = text.replace(/(\/\*PROTECTED REGION ID\(protect_internal_functions_impl_CTL\))/, 'double clamp(double v, double lo, double hi)\n{\n    return v < lo ? lo : v > hi ? hi : v;\n}\n\n$1');
        writeFileSync(file, text);
        const generated = capture(root);
        expect(await runCli(['generate', 'lab-helper'], generated)).toBe(0);
        expect(generated.stderr).toContain('edited outside its protected regions');
        const built = capture(root);
        expect(await runCli(['build', 'lab-helper'], built)).toBe(1);
        expect(built.stderr + built.stdout).toMatch(/undefined reference to [`‘']clamp['’]; `clamp` is defined in src-gen\/orphans\/generated\/architecture\/modules\/CTL_mod\/module\.c, where `contract generate` moved code written outside the protected regions: move its definition into a protected region/);
    }, 240_000);
});
