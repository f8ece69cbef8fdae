/**
 * How `contract run` reports a run a limit stopped (field test ft57b, defects 6, 7 and 10): the
 * service's line of the stop is shown without --verbose and kept in JSON's `output`; a module the
 * memory limit killed (SIGKILL: the kernel's OOM killer) is told as killed by that limit, not as
 * a crash; a --run-limit too short to start and stop the architecture is refused (exit 2).
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { JobEvent } from '@contract-studio/build-service';
import { runCli } from '../src/cli.js';
import { MIN_RUN_LIMIT_SECONDS, checkRunLimit, failureText, moduleFailures, problemLines } from '../src/commands/run.js';
import { makePrinter, type JobOptions, type JobOutcome } from '../src/job-runner.js';
import { capture } from './capture-io.js';

let root: string;
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-run-stop-'));
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

const MEMORY_STOP = 'memory limit 512 MiB reached: stopping the architecture as at the end of a run (what still runs after 1000 ms is killed)';
const MEMORY_HIT = { name: 'memory', value: 536870912, unit: 'bytes', mechanism: 'cgroup-v1' };

function line(step: 'prepare' | 'build' | 'run', source: string, text: string, stream: 'stdout' | 'stderr' | 'system' = source === 'service' ? 'system' : 'stderr'): JobEvent {
    return { type: 'line', seq: 0, t: 0, step, source, stream, line: text } as JobEvent;
}

/** The events of a memory-limit stop, printed as `contract run` prints them with `format` (no --verbose, no terminal). */
function printed(format: 'text' | 'json', verbose = false): { stdout: string; stderr: string; runLines: JobOutcome['runLines'] } {
    const io = capture(root);
    const runLines: JobOutcome['runLines'] = [];
    const opts = { dir: root, dirArg: '.', sandbox: 'bwrap', format, verbose, progress: false, runtime: undefined, cacheDir: undefined } as JobOptions;
    const print = makePrinter(opts, io, runLines, []);
    for (const e of [
        line('run', 'service', '$ make -C generated/architecture run'),
        line('run', 'launcher', 'all modules started'),
        line('run', 'service', MEMORY_STOP),
        line('run', 'launcher', 'stopping'),
        line('run', 'service', 'time: run 2512 ms'),
        line('run', 'service', 'the architecture did not stop within 1000 ms: killed'),
        line('run', 'service', 'cancel asked while the run was being stopped by the memory limit 512 MiB: it ends by the limit'),
    ]) print(e);
    return { stdout: io.stdout, stderr: io.stderr, runLines };
}

describe('the service\'s line of a stop by a limit (defect 6)', () => {
    it('is printed on stderr without --verbose, with the line of a stop not ended in its grace; its other lines are not', () => {
        const { stdout, stderr } = printed('text');
        // the launcher's lines on stderr, where it writes them, in their place among the service's
        expect(stderr).toBe(`contract-launch: all modules started\n${MEMORY_STOP}\ncontract-launch: stopping\nthe architecture did not stop within 1000 ms: killed\ncancel asked while the run was being stopped by the memory limit 512 MiB: it ends by the limit\n`);
        expect(stdout).toBe('');
    });

    it('is printed once with --verbose', () => {
        const { stderr } = printed('text', true);
        expect(stderr.split('\n').filter((l) => l === MEMORY_STOP)).toHaveLength(1);
    });

    it('is in the run\'s lines that --format json gives as `output`, in its place among the launcher\'s', () => {
        const { stdout, stderr, runLines } = printed('json');
        expect(stdout + stderr).toBe('');
        expect(runLines).toEqual([
            { source: 'launcher', stream: 'stderr', line: 'all modules started' },
            { source: 'service', stream: 'system', line: MEMORY_STOP },
            { source: 'launcher', stream: 'stderr', line: 'stopping' },
            { source: 'service', stream: 'system', line: 'the architecture did not stop within 1000 ms: killed' },
            { source: 'service', stream: 'system', line: 'cancel asked while the run was being stopped by the memory limit 512 MiB: it ends by the limit' },
        ]);
    });
});

describe('a module the memory limit killed (defect 7)', () => {
    const launcher = (...texts: string[]) => texts.map((t) => ({ source: 'launcher', stream: 'stderr', line: t }));
    const lines = launcher('module CTL (pid 21) died by signal 9 (Killed)', 'module MOT (pid 23) died by signal 11 (Segmentation fault)', 'FAILED: module CTL crashed', 'FAILED: module MOT crashed');

    it('is told as killed by the memory limit, not as crashed; JSON keeps `how` as the launcher said it and adds `killedBy` and `message`', () => {
        const failures = moduleFailures(lines, MEMORY_HIT);
        expect(failures).toEqual([
            { module: 'CTL', how: 'died by signal 9 (Killed)', killedBy: 'memory-limit', message: "CTL was killed by the memory limit (signal 9: the kernel's OOM killer, which kills the process using the most memory)" },
            { module: 'MOT', how: 'died by signal 11 (Segmentation fault)' },
        ]);
        expect(failures.map((f) => `module ${failureText(f)}`)).toEqual([
            "module CTL was killed by the memory limit (signal 9: the kernel's OOM killer, which kills the process using the most memory)",
            'module MOT crashed (died by signal 11 (Segmentation fault)): a bad pointer: NULL, freed, or past the end of an array',
        ]);
        // ORD's stuck report of it says the same
        expect(problemLines([{ kind: 'module-stuck', module: 'CTL', message: 'CTL has not finished release #6 after 100 periods: does its exec region set *stateindex = -1?' }], failures))
            .toEqual(["CTL has not finished release #6 after 100 periods: it was killed by the memory limit (signal 9: the kernel's OOM killer, which kills the process using the most memory)"]);
    });

    it('killed while the run stopped: said so too', () => {
        const [f] = moduleFailures(launcher('module CTL (pid 21) died by signal 9 (Killed) while the run stopped', 'FAILED: module CTL crashed'), MEMORY_HIT);
        expect(failureText(f!)).toBe("CTL was killed by the memory limit while the run stopped (signal 9: the kernel's OOM killer, which kills the process using the most memory)");
    });

    it('without the memory limit hit (another limit, or none), a signal 9 the launcher did not send is told as a kill, not a crash; the real-time CPU bound only in a real-time run', () => {
        for (const hit of [null, { name: 'processes' }]) {
            const [f] = moduleFailures(lines, hit, true);
            expect(f).toMatchObject({ module: 'CTL', how: 'died by signal 9 (Killed)', killedBy: 'sigkill' });
            expect(failureText(f!)).toBe("CTL was killed (a SIGKILL the launcher did not send: the kernel's at the real-time mode's CPU bound, or another process's)");
            const [g] = moduleFailures(lines, hit);
            expect(g).toMatchObject({ module: 'CTL', how: 'died by signal 9 (Killed)', killedBy: 'sigkill' });
            expect(failureText(g!)).toBe("CTL was killed (a SIGKILL the launcher did not send: the kernel's at a memory limit, or another process's)");
            const stuck = [{ kind: 'module-stuck', module: 'CTL', message: 'CTL has not finished release #6 after 100 periods: does its exec region set *stateindex = -1?' }];
            expect(problemLines(stuck, [g!])).toEqual(["CTL has not finished release #6 after 100 periods: it was killed (a SIGKILL the launcher did not send: the kernel's at a memory limit, or another process's)"]);
            expect(problemLines(stuck, [f!], true)).toEqual(["CTL has not finished release #6 after 100 periods: it was killed (a SIGKILL the launcher did not send: the kernel's at the real-time mode's CPU bound, or another process's)"]);
        }
    });

    it("the launcher's own `was killed` line is read as a kill whatever its exit line", () => {
        const [f, g] = moduleFailures(launcher('module CTL (pid 21) died by signal 9 (Killed)', 'FAILED: module CTL was killed (a SIGKILL the launcher did not send: the kernel\'s at a memory limit or the real-time CPU bound, or another process\'s)', 'FAILED: module MOT crashed'), MEMORY_HIT);
        expect(f).toMatchObject({ module: 'CTL', killedBy: 'memory-limit' });
        expect(g).toEqual({ module: 'MOT', how: 'crashed' });
    });
});

describe('--run-limit below what starting and stopping the architecture take (defect 10)', () => {
    it(`is refused under ${MIN_RUN_LIMIT_SECONDS} s, saying why; ${MIN_RUN_LIMIT_SECONDS} s and more are taken`, () => {
        for (const text of ['100ms', '1s', '1999ms']) expect(() => checkRunLimit(text)).toThrow(`bad --run-limit '${text}': at least 2s (the architecture needs about 1 s to start and 1 s to stop`);
        expect(checkRunLimit('2s')).toBe(2);
        expect(checkRunLimit('2000ms')).toBe(2);
    });

    it('exits 2 before any work, and --help says the minimum', async () => {
        const io = capture(root);
        expect(await runCli(['run', root, '--run-limit', '100ms'], io)).toBe(2);
        expect(io.stderr).toContain("contract run: bad --run-limit '100ms': at least 2s");
        const help = capture(root);
        expect(await runCli(['run', '--help'], help)).toBe(0);
        expect(help.stdout).toContain('at least 2s (the architecture needs about 1s to start and 1s to stop; a shorter one is refused, exit 2)');
    });
});
