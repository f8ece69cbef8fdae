/**
 * `contract generate` on a hostile project folder (docs/codegen.md, "What generate refuses"): a
 * manifest naming host files, and symlinks planted in src-gen. Real CLI, real files and links.
 */
import { cpSync, existsSync, lstatSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));


let base: string;
let victimDir: string;
let victim: string;
const VICTIM_TEXT = 'x\n/*PROTECTED REGION ID(stolen) ENABLED START*/host_secret/*PROTECTED REGION END*/\n';

/** A copy of the tutorial's sources in base/<name>. */
function project(name: string): string {
    const dir = join(base, name);
    mkdirSync(dir);
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) cpSync(join(TUTORIAL, f), join(dir, f));
    return dir;
}

async function generate(dir: string): Promise<{ status: number; stdout: string; stderr: string }> {
    const io = capture(base);
    const status = await runCli(['generate', relative(base, dir)], io);
    return { status, stdout: io.stdout, stderr: io.stderr };
}

beforeAll(() => {
    base = mkdtempSync(join(tmpdir(), 'contract-generate-hostile-'));
    victimDir = join(base, 'victim');
    mkdirSync(victimDir);
    victim = join(victimDir, 'important.txt');
    writeFileSync(victim, VICTIM_TEXT);
});
afterAll(() => rmSync(base, { recursive: true, force: true }));

describe('contract generate on a hostile project folder', () => {
    it('drops manifest entries that leave src-gen (with a warning naming them) and never deletes the host file they name', async () => {
        const p = project('p');
        expect((await generate(p)).status).toBe(0);
        const manifestFile = join(p, 'src-gen', '.contract-manifest.json');
        const manifest = JSON.parse(readFileSync(manifestFile, 'utf8')) as { files: Record<string, unknown> };
        const entries = [
            '../'.repeat(16) + victim.slice(1),
            victim,
            'generated/../../../victim/important.txt',
            '..\\..\\victim\\important.txt',
            '../../victim/important.txt\u0000',
        ];
        for (const e of entries) manifest.files[e] = {};
        writeFileSync(manifestFile, JSON.stringify(manifest));
        const r = await generate(p);
        expect(r.status, r.stderr).toBe(0);
        expect(r.stdout).not.toMatch(/removed|orphaned/);
        expect(readFileSync(victim, 'utf8')).toBe(VICTIM_TEXT);
        for (const e of entries) expect(r.stderr).toContain(`warning: ${join('p', 'src-gen')}/.contract-manifest.json: entry ${JSON.stringify(e)} dropped (`);
        expect(existsSync(join(p, 'src-gen', 'orphans'))).toBe(false);
    }, 120_000);

    it('refuses a src-gen that is a symlink (exit 1, a clear error, nothing written into its target)', async () => {
        const p = project('p2');
        const outside = join(base, 'outside2');
        mkdirSync(outside);
        symlinkSync(outside, join(p, 'src-gen'));
        const r = await generate(p);
        expect(r.status).toBe(1);
        expect(r.stderr).toMatch(/error: \(output\): cannot write .*p2\/src-gen: .*p2\/src-gen is a symbolic link \(-> .*outside2\): refused, the generator never reads, writes or deletes through a link/);
        expect(readdirSync(outside)).toEqual([]);
    }, 120_000);

    it('refuses a symlinked folder inside src-gen (src-gen/generated -> elsewhere), naming it once', async () => {
        const p = project('p3');
        const outside = join(base, 'outside3');
        mkdirSync(outside);
        mkdirSync(join(p, 'src-gen'));
        symlinkSync(outside, join(p, 'src-gen', 'generated'));
        const r = await generate(p);
        expect(r.status).toBe(1);
        const errors = r.stderr.split('\n').filter((l) => l.startsWith('error: '));
        expect(errors).toEqual([expect.stringMatching(/^error: p3\/src-gen\/generated: generated is a symbolic link \(-> .*outside3\): refused, .*; 52 file\(s\) not read, written or deleted: generated\/architecture\/Makefile, /)]);
        expect(readdirSync(outside)).toEqual([]);
    }, 120_000);

    it('does not overwrite or read a host file that a generated file was replaced by a link to', async () => {
        const p = project('p4');
        expect((await generate(p)).status).toBe(0);
        const moduleC = join(p, 'src-gen', 'generated', 'architecture', 'modules', 'MAA_mod', 'module.c');
        rmSync(moduleC);
        symlinkSync(victim, moduleC);
        const r = await generate(p);
        expect(r.status).toBe(1);
        expect(r.stderr).toMatch(/error: p4\/src-gen\/generated\/architecture\/modules\/MAA_mod\/module\.c: .*is a symbolic link .*; left untouched/);
        expect(readFileSync(victim, 'utf8')).toBe(VICTIM_TEXT);
        expect(lstatSync(moduleC).isSymbolicLink()).toBe(true);
        expect(existsSync(join(p, 'src-gen', 'orphans'))).toBe(false);
    }, 120_000);
});
