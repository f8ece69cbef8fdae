/**
 * Where a module crashed, as `contract run` tells it: the module's crash report (its frames as
 * offsets) is not printed but with --verbose, as the service's frames mapped to the code; the
 * service's crash-site line makes `module EST crashed (...) at FILE:LINE ...`.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { JobEvent } from '@contract-studio/build-service';
import { makePrinter, SANDBOX_PIDS_NOTE, type JobOptions, type JobOutcome } from '../src/job-runner.js';
import { failureText, moduleFailures } from '../src/commands/run-problems.js';
import { capture } from './capture-io.js';

let root: string;
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-crash-site-'));
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

const SITE = ' at src-gen/generated/architecture/modules/EST_mod/module.c:248 in its protected region protect_exec_EST (_exec_module_state)';
const line = (source: string, text: string, stream = 'stderr'): JobEvent => ({ type: 'line', seq: 0, t: 0, step: 'run', source, stream, line: text }) as JobEvent;
const EVENTS = [
    line('EST', '==contract-crash== module EST signal 11 SIGSEGV addr 0x0'),
    line('EST', '==contract-crash== frame 0 exe 0x40d8'),
    line('EST', '==contract-crash== end 1 frames'),
    line('launcher', 'module EST (pid 21) died by signal 11 (Segmentation fault)'),
    line('launcher', 'FAILED: module EST crashed'),
    line('service', `EST crashed${SITE}`, 'system'),
    line('service', 'EST crash frame #0 _exec_module_state at src-gen/generated/architecture/modules/EST_mod/module.c:248', 'system'),
];

function printed(verbose: boolean): { stderr: string; runLines: JobOutcome['runLines'] } {
    const io = capture(root);
    const opts = { dir: root, dirArg: '.', sandbox: 'bwrap', format: 'text', verbose, progress: false, runtime: undefined, cacheDir: undefined } as JobOptions;
    const runLines: JobOutcome['runLines'] = [];
    const print = makePrinter(opts, io, runLines, []);
    for (const e of EVENTS) print(e);
    return { stderr: io.stderr, runLines };
}

describe('a crash site in contract run', () => {
    it('names the site after how the module ended', () => {
        const { runLines } = printed(false);
        const failures = moduleFailures(runLines);
        expect(failures).toEqual([{ module: 'EST', how: 'died by signal 11 (Segmentation fault)', site: SITE }]);
        expect(failureText(failures[0]!)).toBe(`EST crashed (died by signal 11 (Segmentation fault))${SITE}: a bad pointer: NULL, freed, or past the end of an array`);
    });

    it('the crash report and the frames only with --verbose', () => {
        const plain = printed(false).stderr;
        expect(plain).not.toContain('==contract-crash==');
        expect(plain).not.toContain('crash frame');
        expect(plain).toContain('contract-launch: FAILED: module EST crashed');
        const verbose = printed(true).stderr;
        expect(verbose).toContain('[EST] ==contract-crash== frame 0 exe 0x40d8');
        expect(verbose).toContain('EST crash frame #0 _exec_module_state at src-gen/generated/architecture/modules/EST_mod/module.c:248');
    });

    it('after the launcher\'s run directory line, says the pids are the sandbox\'s (bwrap, docker, auto), not with the none sandbox', () => {
        const said = (sandbox: string): string => {
            const io = capture(root);
            const print = makePrinter({ dir: root, dirArg: '.', sandbox, format: 'text', verbose: false, progress: false, runtime: undefined, cacheDir: undefined } as JobOptions, io, [], []);
            print(line('launcher', 'run directory /work/run'));
            print(line('launcher', 'module SRT (pid 54) died by signal 9 (Killed)'));
            return io.stderr;
        };
        for (const sandbox of ['bwrap', 'docker', 'auto']) {
            expect(said(sandbox)).toBe(`contract-launch: run directory /work/run\n${SANDBOX_PIDS_NOTE}\ncontract-launch: module SRT (pid 54) died by signal 9 (Killed)\n`);
        }
        expect(SANDBOX_PIDS_NOTE).toContain('not the host\'s');
        expect(said('none')).not.toContain('pid namespace');
    });

    it('a module\'s own line that reads like the service\'s is not its site', () => {
        const failures = moduleFailures([
            { source: 'EST', stream: 'stderr', line: 'EST crashed at /etc/passwd:1' },
            { source: 'launcher', stream: 'stderr', line: 'module EST (pid 21) died by signal 11 (Segmentation fault)' },
            { source: 'launcher', stream: 'stderr', line: 'FAILED: module EST crashed' },
        ]);
        expect(failures).toEqual([{ module: 'EST', how: 'died by signal 11 (Segmentation fault)' }]);
    });
});

describe('a module that ended with a status in contract run', () => {
    it('whose init region returned 0 did not start: said so, not as a crash; another exit with a status failed', () => {
        const failures = moduleFailures([
            { source: 'MAB', stream: 'stderr', line: 'MAB: its init region returned 0 (false): the module does not start' },
            { source: 'launcher', stream: 'stderr', line: 'module MAB (pid 63) exited with status 255' },
            { source: 'launcher', stream: 'stderr', line: 'module CTL (pid 64) exited with status 3' },
            { source: 'launcher', stream: 'stderr', line: 'FAILED: module MAB crashed' },
            { source: 'launcher', stream: 'stderr', line: 'FAILED: module CTL crashed' },
        ]);
        expect(failures.map(failureText)).toEqual(['MAB did not start: its init region returned 0 (exited with status 255)', 'CTL failed (exited with status 3)']);
    });
});

