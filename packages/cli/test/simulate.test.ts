/**
 * `contract simulate`: the tutorial's scenarios pass (exit 0), a wrong expectation fails (exit 1)
 * with the step's line and the expected and actual state, scenario and usage errors exit 2,
 * `--format json` gives every step's record and `--format junit` a JUnit report.
 */
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const REPO = fileURLToPath(new URL('../../../', import.meta.url));
const TUTORIAL = join(REPO, 'examples', 'tutorial');
const cache = mkdtempSync(join(tmpdir(), 'contract-simulate-cli-'));
afterAll(() => rmSync(cache, { recursive: true, force: true }));
const scenario = (name: string) => join(TUTORIAL, 'scenarios', name);

// the command loads the simulator (and the language) when it runs, not when the CLI starts: the
// first test pays that load, longer than vitest's default 5 s on a loaded 2-core machine
describe('contract simulate', { timeout: 60_000 }, () => {
    it('passes the tutorial scenarios (exit 0), each step and rule change printed', async () => {
        const io = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), scenario('mission.scenario'), '--cache', cache], io)).toBe(0);
        expect(io.stdout).toContain('+ SUP.action.SECOND active  <- MAA:2 value="disconnected"');
        expect(io.stdout).toContain('- GLB.mission.SINGLE inactive  <- SUP:1 value="commutation"');
        expect(io.stdout).toMatch(/\n2 passed, 0 failed\n$/);
    });

    it('a wrong expectation exits 1, naming the step, the expected and the actual state; junit and json say it too', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-wrong-'));
        const file = join(dir, 'wrong.scenario');
        writeFileSync(file, readFileSync(scenario('commutation.scenario'), 'utf8').replace('expect rule SUP.action.FOURTH active', 'expect rule SUP.action.FOURTH inactive'));
        const line = readFileSync(file, 'utf8').split('\n').findIndex((l) => l.includes('FOURTH inactive')) + 1;
        const io = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'wrong.scenario', '--cache', cache], io)).toBe(1);
        expect(io.stdout).toContain(`FAIL   1200ms  expect rule SUP.action.FOURTH inactive`);
        expect(io.stdout).toContain(`wrong.scenario:${line}: at 1200ms (expect rule SUP.action.FOURTH inactive): expected rule SUP.action.FOURTH inactive, but it is active`);
        expect(io.stdout).toMatch(/\n0 passed, 1 failed\n$/);

        const junit = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'wrong.scenario', '--cache', cache, '--format', 'junit'], junit)).toBe(1);
        expect(junit.stdout).toMatch(/^<\?xml version="1.0" encoding="UTF-8"\?>\n<testsuites name="contract simulate" tests="19" failures="1">/);
        expect(junit.stdout).toContain(`<failure message="wrong.scenario:${line}: at 1200ms`);

        const json = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'wrong.scenario', '--cache', cache, '--format', 'json'], json)).toBe(1);
        const out = JSON.parse(json.stdout) as { scenarios: Array<{ passed: boolean; failures: Array<{ line: number; expected: string; actual: string }>; steps: Array<{ timeNs: number; rules: unknown[]; schemas: string[]; locals: unknown[] }> }> };
        expect(out.scenarios[0]!.passed).toBe(false);
        expect(out.scenarios[0]!.failures).toMatchObject([{ line, expected: 'rule SUP.action.FOURTH inactive', actual: 'active' }]);
        const step = out.scenarios[0]!.steps.find((s) => s.timeNs === 300_000_000 && s.rules.length > 0)!;
        expect(step.schemas).toEqual(['schemaCommande1']);
        expect(step.locals.length).toBe(4);
        rmSync(dir, { recursive: true });
    });

    it('scenario errors exit 2 with file:line:col, nothing simulated; usage errors exit 2', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-bad-'));
        writeFileSync(join(dir, 'bad.scenario'), 'start SUP.action()\nexpect rule SUP.action.NOPE active\n');
        const io = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'bad.scenario', '--cache', cache], io)).toBe(2);
        expect(io.stderr).toContain("bad.scenario:2:24: error: SUP.action has no rule 'NOPE' (rules: FIRST, SECOND, THIRD, FOURTH, RECEPTION) [scenario-unknown-rule]");
        expect(io.stdout).toBe('');
        expect(await runCli(['simulate', TUTORIAL], capture(dir))).toBe(2);
        expect(await runCli(['simulate', TUTORIAL, 'bad.scenario', '--format', 'xml'], capture(dir))).toBe(2);
        const missing = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'none.scenario', '--cache', cache], missing)).toBe(2);
        expect(missing.stderr).toContain('none.scenario: error: cannot read this scenario');
        rmSync(dir, { recursive: true });
    });
});
