/** `contract check`: output formats, exit codes, usage errors — on real files. */
import { spawnSync } from 'node:child_process';
import { cpSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture as captureIn, type CapturedIO } from './capture-io.js';

const REPO = fileURLToPath(new URL('../../../', import.meta.url));
const TUTORIAL = join(REPO, 'examples/tutorial');

const capture = (cwd = REPO): CapturedIO => captureIn(cwd);

let bad: string;
beforeAll(() => {
    bad = mkdtempSync(join(tmpdir(), 'contract-check-'));
    mkdirSync(join(bad, 'sub'));
    writeFileSync(join(bad, 'types.contract'), 'datatype T {int a = 1.5};\n');
    writeFileSync(join(bad, 'sub/mod.contract'), 'import "../types.contract";\nsynchronous module msa {\n  scheduling { C=1ms; }\n  data flows { out :0 T x; }\n}\n');
    writeFileSync(join(bad, 'warn.contract'), 'import "types.contract";\nimport "types.contract";\ndatatype U {T t};\n');
});
afterAll(() => rmSync(bad, { recursive: true, force: true }));

describe('contract check', () => {
    it('exits 0 and prints a summary on the clean tutorial', async () => {
        const io = capture();
        expect(await runCli(['check', 'examples/tutorial'], io)).toBe(0);
        expect(io.stdout).toBe('');
        expect(io.stderr).toBe('0 errors, 0 warnings, 0 hints in 13 files\n');
    });

    it('prints gcc-like text lines and exits 1 on errors', async () => {
        const io = capture(bad);
        expect(await runCli(['check', '.'], io)).toBe(1);
        const lines = io.stdout.trim().split('\n');
        expect(lines).toContain("sub/mod.contract:2:20 error module-name-format Module name 'msa' must be exactly three upper-case letters (A-Z), e.g. 'MSA'.");
        expect(lines).toContain("types.contract:1:21 error value-type-mismatch Expected an int (integer literal) for 'a', found the real 1.5 (a real cannot be an int).");
        expect(lines.some((l) => /^warn\.contract:2:8 warning import-duplicate /.test(l))).toBe(true);
        expect(io.stderr).toMatch(/^2 errors, 1 warning, 0 hints in 3 files/);
    });

    it('prints JSON with paths relative to DIR and 1-based positions', async () => {
        const io = capture();
        expect(await runCli(['check', bad, '--format', 'json'], io)).toBe(1);
        const parsed = JSON.parse(io.stdout) as { diagnostics: Array<Record<string, unknown>> };
        expect(parsed.diagnostics).toContainEqual({
            file: 'sub/mod.contract', line: 2, column: 20, severity: 'error', code: 'module-name-format',
            message: "Module name 'msa' must be exactly three upper-case letters (A-Z), e.g. 'MSA'."
        });
        expect(Object.keys(parsed.diagnostics[0]!)).toEqual(['file', 'line', 'column', 'severity', 'code', 'message']);
        expect(io.stderr).toBe('');
    });

    it('exits 0 when there are only warnings, and supports --format=json', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-warn-'));
        try {
            writeFileSync(join(dir, 'a.contract'), 'import "b.contract";\nimport "b.contract";\ndatatype A {B b};\n');
            writeFileSync(join(dir, 'b.contract'), 'datatype B {int x};\n');
            const io = capture();
            expect(await runCli(['check', dir, '--format=json'], io)).toBe(0);
            const parsed = JSON.parse(io.stdout) as { diagnostics: Array<{ severity: string; code: string }> };
            expect(parsed.diagnostics.map((d) => `${d.severity} ${d.code}`)).toEqual(['warning import-duplicate']);
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('checks a folder of several projects project by project (docs/codegen.md "Where a project is")', async () => {
        // field test: `contract serve` of a folder of 7 projects showed 84 "defined more than once" errors
        const dir = mkdtempSync(join(tmpdir(), 'contract-projects-'));
        try {
            for (const copy of ['a', 'b']) cpSync(TUTORIAL, join(dir, copy), { recursive: true, filter: (src) => !src.includes('/src-gen') });
            writeFileSync(join(dir, 'b/types2.contract'), 'datatype TypeA {float i = 0.0};\n');
            const io = capture(dir);
            expect(await runCli(['check', '.'], io)).toBe(1);
            // the duplicate within b only, named by its path in b; a is clean although it defines TypeA too
            expect(io.stdout.trim().split('\n')).toEqual([
                "b/datatype.contract:2:10 error type-duplicate-name Datatype 'TypeA' is defined more than once in the project (also in types2.contract); datatype names are unique across the project.",
                "b/types2.contract:1:10 error type-duplicate-name Datatype 'TypeA' is defined more than once in the project (also in datatype.contract); datatype names are unique across the project."
            ]);
            expect(io.stderr).toBe('2 errors, 0 warnings, 0 hints in 27 files of 2 projects (a/, b/), each checked alone\n');
            rmSync(join(dir, 'b/types2.contract'));
            const clean = capture(dir);
            expect(await runCli(['check', '.'], clean)).toBe(0);
            expect(clean.stdout).toBe('');
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('writes SARIF 2.1.0', async () => {
        const io = capture();
        expect(await runCli(['check', bad, '--format', 'sarif'], io)).toBe(1);
        const sarif = JSON.parse(io.stdout) as { version: string; runs: Array<{ results: Array<{ ruleId: string; locations: Array<{ physicalLocation: { artifactLocation: { uri: string } } }> }> }> };
        expect(sarif.version).toBe('2.1.0');
        expect(sarif.runs[0]!.results.map((r) => r.ruleId)).toContain('module-name-format');
        expect(sarif.runs[0]!.results.map((r) => r.locations[0]!.physicalLocation.artifactLocation.uri)).toContain('sub/mod.contract');
    });

    it('exits 2 on bad usage with a message', async () => {
        for (const args of [['check'], ['check', 'a', 'b'], ['check', TUTORIAL, '--format', 'xml'], ['check', TUTORIAL, '--bogus'],
            ['check', 'no/such/dir'], ['check', join(TUTORIAL, 'datatype.contract')], ['frobnicate'], []]) {
            const io = capture();
            expect(await runCli(args, io), args.join(' ')).toBe(2);
            expect(io.stderr.length, args.join(' ')).toBeGreaterThan(0);
        }
    });

    it('prints help and version', async () => {
        const help = capture();
        expect(await runCli(['--help'], help)).toBe(0);
        expect(help.stdout).toContain('check');
        const usage = capture();
        expect(await runCli(['check', '--help'], usage)).toBe(0);
        expect(usage.stdout).toContain('usage: contract check DIR');
        const version = capture();
        expect(await runCli(['--version'], version)).toBe(0);
        expect(version.stdout).toMatch(/^contract \d+\.\d+\.\d+/);
    });

    it('runs as a process through bin/contract.js with the documented exit codes', () => {
        const bin = join(REPO, 'packages/cli/bin/contract.js');
        const ok = spawnSync(process.execPath, [bin, 'check', 'examples/tutorial', '--format', 'json'], { cwd: REPO, encoding: 'utf8' });
        expect(ok.status).toBe(0);
        expect(JSON.parse(ok.stdout)).toEqual({ diagnostics: [] });
        const fail = spawnSync(process.execPath, [bin, 'check', bad], { cwd: REPO, encoding: 'utf8' });
        expect(fail.status).toBe(1);
        const usage = spawnSync(process.execPath, [bin, 'check'], { cwd: REPO, encoding: 'utf8' });
        expect(usage.status).toBe(2);
    }, 30_000);
});
