/**
 * Which of the build service's own lines `contract build` / `run` print (field test ft58c, defects
 * 4 and 5): the line of a command waiting for another on the same project is printed in every
 * mode (in CI stderr is no terminal: before, the wait was silent); the `time: <step> N ms` lines
 * only with --verbose (a terminal's progress lines printed them too).
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { JobEvent } from '@contract-studio/build-service';
import { makePrinter, reportBuild, type JobOptions, type JobOutcome } from '../src/job-runner.js';
import { capture } from './capture-io.js';

let root: string;
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'contract-service-lines-'));
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

const WAIT = 'waiting for the other command using this project (pid 4242, contract run) to finish ...';

function service(step: 'prepare' | 'build', text: string): JobEvent {
    return { type: 'line', seq: 0, t: 0, step, source: 'service', stream: 'system', line: text } as JobEvent;
}

/** stderr of the printer fed the service's lines of a prepare step, in a mode. */
function stderrOf(mode: { format?: 'text' | 'json'; verbose?: boolean; progress?: boolean }): string {
    const io = capture(root);
    const opts = { dir: root, dirArg: '.', sandbox: 'bwrap', format: mode.format ?? 'text', verbose: !!mode.verbose, progress: !!mode.progress, runtime: undefined, cacheDir: undefined } as JobOptions;
    const print = makePrinter(opts, io, [], []);
    for (const e of [service('prepare', 'time: sandbox choice (probe) 16 ms'), service('prepare', WAIT), service('prepare', 'generated 23 files'), service('build', 'time: runtime (sources hash) 4 ms')]) print(e);
    return io.stderr;
}

describe('the service\'s lines', () => {
    it('a command waiting for another says for whom in every mode: CI (no terminal), JSON, a terminal, --verbose', () => {
        expect(stderrOf({})).toBe(`${WAIT}\n`);
        expect(stderrOf({ format: 'json' })).toBe(`${WAIT}\n`);
        expect(stderrOf({ progress: true })).toContain(`${WAIT}\n`);
        expect(stderrOf({ verbose: true }).split('\n').filter((l) => l === WAIT)).toHaveLength(1);
    });

    it('`time:` lines only with --verbose, on a terminal too; the other progress lines stay', () => {
        const terminal = stderrOf({ progress: true });
        expect(terminal).not.toMatch(/^time: /m);
        expect(terminal).toContain('generated 23 files\n');
        expect(stderrOf({ verbose: true })).toBe(`time: sandbox choice (probe) 16 ms\n${WAIT}\ngenerated 23 files\ntime: runtime (sources hash) 4 ms\n`);
    });
});

describe('the service\'s real-time mode line', () => {
    const REALTIME = 'real-time mode: SCHED_FIFO up to 99 (inherited-fifo); cpu.rt_runtime_us 40000 per 100000 on each CPU (cgroup-v1-rt); RLIMIT_RTTIME 0.5 s / 1 s';
    it('is printed once in every mode (docs/sandbox.md: the job\'s first lines say it), not only with --verbose', () => {
        for (const mode of [{}, { format: 'json' as const }, { progress: true }, { verbose: true }]) {
            const io = capture(root);
            const opts = { dir: root, dirArg: '.', sandbox: 'bwrap', format: mode.format ?? 'text', verbose: !!mode.verbose, progress: !!mode.progress, runtime: undefined, cacheDir: undefined } as JobOptions;
            const print = makePrinter(opts, io, [], []);
            print(service('prepare', REALTIME));
            print(service('prepare', 'generated 23 files'));
            expect(io.stderr.split('\n').filter((l) => l === REALTIME), JSON.stringify(mode)).toHaveLength(1);
            expect(io.stdout).toBe('');
        }
    });
});

describe('the service\'s line of each prepare problem', () => {
    it('is not printed as it comes, in any mode: the closing lines print each once, at its path from here (prepareErrors)', () => {
        const lines = [
            'robot/sched.contract:3:7: error: unknown module MON',
            'src-gen/.contract-rename.json: error: an interrupted rename left its journal here: ...',
            'src-gen/generated/architecture/modules/MSC_mod/module.c:12: error: protected region(s) protect_init_MSC not ENABLED',
            '(manifest): warning: note',
            'the project has 2 error(s): nothing generated',
        ];
        for (const mode of [{}, { verbose: true }, { progress: true }]) {
            const io = capture(root);
            const opts = { dir: root, dirArg: '.', sandbox: 'bwrap', format: 'text', verbose: !!(mode as { verbose?: boolean }).verbose, progress: !!(mode as { progress?: boolean }).progress, runtime: undefined, cacheDir: undefined } as JobOptions;
            const print = makePrinter(opts, io, [], []);
            for (const l of lines) print(service('prepare', l));
            expect(io.stderr, JSON.stringify(mode)).toBe('');
        }
    });
});

describe('a warning of the job said by a line of its log too (a real-time run throttled, a build\'s output cut)', () => {
    const THROTTLED = 'the architecture was throttled by its real-time CPU budget about 99 times (4.33 s in all): the sandbox gives ...';
    const CUT = "the build's stdout was cut at the output limit (4 KiB per stream, outputBytesPerStream): ...";
    it('is printed once, among the closing lines, in every mode: without --verbose, with it, on a terminal', () => {
        for (const mode of [{ verbose: false, progress: false }, { verbose: true, progress: false }, { verbose: false, progress: true }]) {
            const io = capture(root);
            const opts = { dir: root, dirArg: '.', sandbox: 'bwrap', format: 'text', ...mode, runtime: undefined, cacheDir: undefined } as JobOptions;
            const warnings: string[] = [];
            const print = makePrinter(opts, io, [], [], () => warnings);
            // the service adds each to the job's warnings, then logs its line (job.ts)
            warnings.push(CUT);
            print(service('build', `warning: ${CUT}`));
            warnings.push(THROTTLED);
            print({ type: 'line', seq: 0, t: 0, step: 'run', source: 'service', stream: 'system', line: `warning: ${THROTTLED}` } as JobEvent);
            print({ type: 'line', seq: 0, t: 0, step: 'run', source: 'service', stream: 'system', line: 'warning: the run\'s logs could not be collected: EIO' } as JobEvent);
            const outcome = {
                job: { sandboxName: 'bwrap', warnings, prepareDiagnostics: [], foreignMakefiles: [], status: 'succeeded' },
                result: { ok: true, message: 'run finished (exit 0)', step: 'run', issues: [], durations_ms: { prepare: 1900, build: 900, run: 10000 } },
                runLines: [], buildTail: [],
            } as unknown as JobOutcome;
            reportBuild(opts, outcome, io);
            const said = (w: string) => io.stderr.split('\n').filter((l) => l === `warning: ${w}`).length;
            expect(said(THROTTLED), JSON.stringify(mode)).toBe(1);
            expect(said(CUT), JSON.stringify(mode)).toBe(1);
            // a warning line that is no warning of the job is printed as before (--verbose, a terminal)
            expect(said("the run's logs could not be collected: EIO"), JSON.stringify(mode)).toBe(mode.verbose || mode.progress ? 1 : 0);
        }
    });
});
