import { spawnSync } from 'node:child_process';
import { cpSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { tempDir } from './test-support/temp-dir.js';

const ROOT = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..');
const BIN = join(ROOT, 'packages', 'cli', 'bin', 'contract.js');

function contract(...args: string[]): { status: number | null; stdout: string; stderr: string } {
    const r = spawnSync(process.execPath, [BIN, ...args], { encoding: 'utf8' });
    return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

describe('contract generate (the CLI command of packages/cli/src/commands/generate.ts)', () => {
    let dir: string;
    let cleanup: () => void;
    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-cli-'));
        for (const f of readdirSync(join(ROOT, 'examples', 'tutorial'))) if (f.endsWith('.contract')) cpSync(join(ROOT, 'examples', 'tutorial', f), join(dir, f));
    }, 120_000);
    afterAll(() => cleanup());

    it('creates DIR/src-gen, then keeps everything on a second run', () => {
        const first = contract('generate', dir);
        expect(first.status).toBe(0);
        expect(first.stdout).toMatch(/^created: 52$/m);
        expect(first.stdout).toContain('  generated/architecture/modules/MAA_mod/module.c');
        const second = contract('generate', dir);
        expect(second.status).toBe(0);
        expect(second.stdout).toMatch(/^kept \(unchanged\): 52$/m);
        expect(second.stderr).toContain('0 created, 0 updated, 52 kept, 0 orphaned, 0 error(s)');
    }, 120_000);

    it('names orphaned user code when a port (and with it _react_to_event) disappears', () => {
        const maa = join(dir, 'src-gen', 'generated', 'architecture', 'modules', 'MAB_mod', 'module.c');
        writeFileSync(maa, readFileSync(maa, 'utf8').replace(/(ID\(protect_event_MAB\) ENABLED START\*\/)[\s\S]*?(\/\*PROTECTED REGION END)/, '$1\n    handle_message();\n    $2'));
        writeFileSync(join(dir, 'amodule2.contract'), 'import "datatype.contract";\nasynchronous module MAB{\n}\n');
        writeFileSync(join(dir, 'aschema1.contract'), readFileSync(join(dir, 'aschema1.contract'), 'utf8').replace(/MAA:0 =\* MAB:0;.*\n/, ''));
        const r = contract('generate', dir, '-o', join(dir, 'src-gen'));
        expect(r.status, r.stderr).toBe(0);
        expect(r.stdout).toContain('copied to orphans/ (code moved aside, or lines this generator does not write): 1\n  orphans/generated/architecture/modules/MAB_mod/module.c');
        expect(r.stderr).toMatch(/warning: .*MAB_mod\/module\.c.*protect_event_MAB moved to orphans\//);
        expect(readFileSync(join(dir, 'src-gen', 'orphans', 'generated', 'architecture', 'modules', 'MAB_mod', 'module.c'), 'utf8')).toContain('handle_message();');
    }, 120_000);

    it('refuses a model with errors (exit 1, nothing written) and reports malformed files (exit 1, file left untouched)', () => {
        writeFileSync(join(dir, 'broken.contract'), 'datatype Broken { nope x };\n');
        const refused = contract('generate', dir);
        expect(refused.status).toBe(1);
        expect(refused.stderr).toContain('the model has errors, nothing was generated');
        writeFileSync(join(dir, 'broken.contract'), '');

        const msc = join(dir, 'src-gen', 'generated', 'architecture', 'modules', 'MSC_mod', 'module.c');
        const broken = readFileSync(msc, 'utf8').replace('/*PROTECTED REGION ID(protect_exit_MSC) ENABLED START*/', '/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/');
        writeFileSync(msc, broken);
        const r = contract('generate', dir);
        expect(r.status).toBe(1);
        expect(r.stderr).toMatch(/error: .*MSC_mod\/module\.c:\d+: (nested|duplicate) protected region .*left untouched/);
        expect(readFileSync(msc, 'utf8')).toBe(broken);
    }, 120_000);

    it('exits 2 on bad usage', () => {
        expect(contract('generate').status).toBe(2);
        expect(contract('generate', join(dir, 'missing')).status).toBe(2);
    }, 120_000);
});
