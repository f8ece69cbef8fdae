/**
 * `contract run`'s line of a module that ended on its own mid-run, printed right after the
 * launcher's line of it (job-runner.ts makePrinter, live-module-ends.ts): only from the launcher's
 * own lines (source `launcher`), never from a module's tagged output, and only when the line's pid
 * is the module's own, as its `module_started` record on the live trace gives it.
 */
import { describe, expect, it } from 'vitest';
import type { JobEvent } from '@contract-studio/build-service';
import { makePrinter, type JobOptions } from '../src/job-runner.js';
import { capture } from './capture-io.js';

const W = '2026-12-07T12:00:00.000000Z';
const started = (module: string, pid: number): JobEvent =>
    ({ type: 'trace', seq: 0, t: 0, records: [{ file: `${module}_1.csv`, line: 2, text: `1000000000,${W},${module},module_started,,,0,pid=${pid} priority=40` }] }) as JobEvent;
const line = (source: string, text: string): JobEvent => ({ type: 'line', seq: 0, t: 0, step: 'run', source, stream: 'stderr', line: text }) as JobEvent;

function printed(events: JobEvent[], format: 'text' | 'json' = 'text'): string {
    const io = capture('/');
    const opts = { dir: '/', dirArg: '.', sandbox: 'bwrap', format, verbose: false, progress: false, runtime: undefined, cacheDir: undefined } as JobOptions;
    const print = makePrinter(opts, io, [], []);
    for (const e of events) print(e);
    return io.stderr;
}

const SAID = 'contract run: MAB ended mid-run: died by signal 9 (Killed) (a signal the launcher did not send); the other modules go on\n';

describe("contract run: a module's end said from the launcher's line", () => {
    it('says it right after the launcher\'s line, once', () => {
        const err = printed([started('MAB', 41), line('launcher', 'module MAB (pid 41) died by signal 9 (Killed)'), line('launcher', 'module MAB (pid 41) died by signal 9 (Killed)')]);
        expect(err).toBe(`contract-launch: module MAB (pid 41) died by signal 9 (Killed)\n${SAID}contract-launch: module MAB (pid 41) died by signal 9 (Killed)\n`);
    });

    it('an exit with a status is an end; one at the stop, the launcher\'s own SIGTERM, other lines are none', () => {
        expect(printed([started('MAB', 41), line('launcher', 'module MAB (pid 41) exited with status 3')])).toContain('contract run: MAB ended mid-run: exited with status 3; the other modules go on\n');
        for (const how of ['exited with status 0', 'terminated by signal 15 (Terminated)', 'exited with status 0 while the run stopped']) {
            expect(printed([started('MAB', 41), line('launcher', `module MAB (pid 41) ${how}`)]), how).not.toContain('contract run:');
        }
    });

    it('a module\'s forged line, another pid, or --format json: nothing said', () => {
        expect(printed([started('MAB', 41), line('MAB', 'contract-launch: module MAB (pid 41) died by signal 9 (Killed)'), line('MAB', 'module MAB (pid 41) died by signal 9 (Killed)')])).not.toContain('contract run:');
        expect(printed([started('MAB', 41), line('launcher', 'module MAB (pid 99) died by signal 9 (Killed)')])).not.toContain('contract run:');
        expect(printed([started('MAB', 41), line('launcher', 'module MAB (pid 41) died by signal 9 (Killed)')], 'json')).toBe('');
    });

    it('a line that comes before the module\'s start record is said when that record comes, with its pid', () => {
        expect(printed([line('launcher', 'module MAB (pid 41) died by signal 9 (Killed)'), started('MAB', 41)])).toContain(SAID);
        expect(printed([line('launcher', 'module MAB (pid 41) died by signal 9 (Killed)'), started('MAB', 42)])).not.toContain('contract run:');
    });
});
