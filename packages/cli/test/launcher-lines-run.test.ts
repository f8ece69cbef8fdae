/**
 * A real run of the tutorial (bubblewrap) whose module MAB — one no other module sends a request to
 * afterwards — is SIGKILLed from outside about a second in, while MAA prints a forged launcher
 * line about itself on its stderr (`contract-launch: module MAA (pid N) died by signal 9 (Killed)`,
 * with its own pid). `contract run` says MAB's end when the launcher's line comes, and not MAA's;
 * the logs folder keeps the launcher's own lines (`contract-launch.log`), so `contract trace` tells
 * MAB gone at its last record, in the story's time order (before the run's stop), the launcher's
 * line as the evidence, and MAA never. Before, the logs held no launcher line: the story said MAB
 * only at its end, `the launcher's output says which`.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';
import { killModuleOnceRunning } from '@contract-studio/build-service/test-support/module-pid';

const canRun = spawnSync('bwrap', ['--version']).status === 0;
const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));

let root: string;

beforeAll(async () => {
    root = await makeSeededScratch('contract-launcher-lines-');
    cpSync(TUTORIAL, join(root, 'tut'), { recursive: true, filter: (src) => !/\/(logs|run)$/.test(src) });
    // MAA forges the launcher's end line of itself, with its own pid, as its init runs
    const file = join(root, 'tut', 'src-gen/generated/architecture/modules/MAA_mod/module.c');
    const source = readFileSync(file, 'utf8');
    const edited = source
        .replace(/(PROTECTED REGION ID\(protect_additional_import_MAA\) ENABLED START\*\/)/, '$1\n#include <unistd.h>')
        .replace(/(PROTECTED REGION ID\(protect_init_MAA\) ENABLED START\*\/)/, '$1\n    fprintf(stderr, "contract-launch: module MAA (pid %ld) died by signal 9 (Killed)\\n", (long)getpid()); fflush(stderr);');
    expect(edited).toContain('#include <unistd.h>');
    expect(edited).toContain('(long)getpid()');
    writeFileSync(file, edited);
}, 120_000);
afterAll(() => removeSeededScratch(root));

describe.skipIf(!canRun)('a module SIGKILLed from outside mid-run, recorded by contract run', () => {
    it('contract run says its end when it happens; contract trace tells it gone at the kill; a forged line is not believed', async () => {
        const io = capture(root);
        const running = runCli(['run', 'tut', '--sandbox', 'bwrap', '--duration', '4s', '--logs', 'tut-logs'], io);
        const killer = killModuleOnceRunning('MAB', 1000);
        const code = await running;
        const killedAt = await killer;
        expect(killedAt).toBeGreaterThan(0);
        expect(code).not.toBe(0); // a module killed by a SIGKILL the launcher did not send fails the run
        expect(io.stderr).toMatch(/\ncontract-launch: module MAB \(pid \d+\) died by signal 9 \(Killed\)\ncontract run: MAB ended mid-run: died by signal 9 \(Killed\) \(a signal the launcher did not send\); the other modules go on\n/);
        expect(io.stderr).toMatch(/\[MAA\] contract-launch: module MAA \(pid \d+\) died by signal 9 \(Killed\)\n/); // printed, tagged
        expect(io.stderr).not.toContain('contract run: MAA ended');
        const logs = join(root, 'tut-logs');
        expect(existsSync(join(logs, 'contract-launch.log'))).toBe(true);
        const launcherFile = readFileSync(join(logs, 'contract-launch.log'), 'utf8');
        expect(launcherFile).toMatch(/^\d+ module MAB \(pid \d+\) died by signal 9 \(Killed\)$/m);
        expect(launcherFile).not.toMatch(/MAA \(pid \d+\) died/); // MAA's forged line is its own output, never the launcher's

        const t = capture(root);
        await runCli(['trace', logs], t);
        const lines = t.stdout.split('\n');
        const gone = lines.findIndex((l) => /^\+\d+\.\d{6}s MAB {2}its records stop here \(its last record\), with no exit record: it ended mid-run, while the others went on; the launcher's line, at \+\d+\.\d{6}s: contract-launch: module MAB \(pid \d+\) died by signal 9 \(Killed\)$/.test(l));
        expect(gone, t.stdout).toBeGreaterThanOrEqual(0);
        const at = Number(/the launcher's line, at \+(\d+\.\d+)s/.exec(lines[gone]!)![1]);
        // at the kill, a second or so in, not at the run's end (4 s after the start): told before the records after it
        expect(at).toBeLessThan(4);
        const later = lines.slice(gone + 1).map((l) => /^\+(\d+\.\d+)s /.exec(l)).filter((m) => m !== null).map((m) => Number(m![1]));
        expect(later.some((s) => s > at + 1)).toBe(true);
        expect(t.stdout).not.toMatch(/MAA {2}its records stop here/);
        expect(t.stdout).not.toMatch(/MAA {2}its last record: no exit record/);
    }, 240_000);
});
