/**
 * The Timeline's modules gone by the launcher's own end lines, from a real recorded run
 * (fixtures/killed-trace-run: MAB SIGKILLed in a bwrap run of the tutorial), read the two ways the
 * Timeline reads it: the trace file `contract run --trace` wrote (its `launcher_line` items) and the
 * logs folder (its contract-launch.log): the same module, time and words; with the pid rule (a line
 * naming another pid is not taken) and the modules that exited at the run's end not taken. And the
 * way its last Build & Run source reads them: the job's log, whose launcher lines carry the
 * service's wall time only, put on the records' clock as the Monitor's replay of the job puts them.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { launcherLinesOfFile, traceFileToLogs } from '@contract-studio/build-service/trace';
import { activationsFromLogs } from './run-logs.js';
import { endGoneActivations, goneFromLauncherLines } from './gone-activations.js';
import { applyLauncherLines, launcherLinesOf, launcherLinesOnRecordClock } from '../monitor/job-launcher-lines.js';
import { recordedRunSteps, type RecordedRun } from '../monitor/recorded-run.js';

const DIR = join(__dirname, 'fixtures', 'killed-trace-run');
const KILLED = { module: 'MAB', at: 24434157137311, words: 'contract-launch: module MAB (pid 65) died by signal 9 (Killed)' };

const folderLogs = () => readdirSync(DIR).filter((f) => f.endsWith('.csv')).sort().map((name) => ({ name, text: readFileSync(join(DIR, name), 'utf8') }));
const folderLines = () => launcherLinesOfFile(readFileSync(join(DIR, 'contract-launch.log'), 'utf8')).map((l) => ({ monoNs: String(l.monoNs), line: l.line }));

describe("the Timeline's modules gone by the launcher's lines (a real run)", () => {
  it('reads the trace file\'s launcher_line items as the folder\'s contract-launch.log: MAB gone at the line\'s time', () => {
    const file = traceFileToLogs('run.jsonl', readFileSync(join(DIR, 'run.jsonl'), 'utf8'));
    expect(file.launcherLines?.length).toBe(9);
    expect(goneFromLauncherLines(file.files, file.launcherLines)).toEqual([KILLED]);
    expect(goneFromLauncherLines(folderLogs(), folderLines())).toEqual([KILLED]);
    // without the lines (before: the trace file's were not read) nothing is said
    expect(goneFromLauncherLines(file.files, undefined)).toEqual([]);
  });

  it('takes a line only with the pid of the module\'s own module_started', () => {
    const forged = [{ monoNs: '24433000000000', line: 'module ORD (pid 99) died by signal 9 (Killed)' }, { monoNs: '24433000000001', line: 'module NOPE (pid 65) died by signal 9 (Killed)' }];
    expect(goneFromLauncherLines(folderLogs(), forged)).toEqual([]);
    expect(goneFromLauncherLines(folderLogs(), [{ monoNs: '24433000000000', line: 'module ORD (pid 61) died by signal 9 (Killed)' }]))
      .toEqual([{ module: 'ORD', at: 24433000000000, words: 'contract-launch: module ORD (pid 61) died by signal 9 (Killed)' }]);
  });

  it("ends a bar still running at the line's time, and leaves finished ones", () => {
    const logs = folderLogs();
    const gone = goneFromLauncherLines(logs, folderLines());
    // as recorded: MAB's last run had ended before the kill
    const { acts } = activationsFromLogs(logs);
    const before = acts.filter((a) => a.module === 'MAB').map((a) => a.end);
    expect(endGoneActivations(acts, gone)).toBe(0);
    expect(acts.filter((a) => a.module === 'MAB').map((a) => a.end)).toEqual(before);
    // its log cut after its last run_started (killed inside that run): the bar ends at the line's time
    const cut = logs.map((l) => (l.name.startsWith('MAB_') ? { ...l, text: l.text.slice(0, l.text.lastIndexOf('\n', l.text.lastIndexOf(',run_finished,')) + 1) } : l));
    const open = activationsFromLogs(cut).acts;
    const last = open.filter((a) => a.module === 'MAB').pop()!;
    expect(last.end).toBeUndefined();
    expect(endGoneActivations(open, gone)).toBe(1);
    expect(last.end).toBe(KILLED.at);
    expect(last.gone).toBe(KILLED.words);
  });
});

/**
 * The run's job log as the build service writes it (`<t ISO> run launcher stderr | <line>`, GET
 * /api/jobs/:id/log): each of the launcher's lines of contract-launch.log at its wall time (the
 * first record's wall_time, plus the line's mono_ns less that record's), plus `more` lines.
 */
function jobLog(more: string[] = []): string {
  const logs = folderLogs();
  const first = logs.map((f) => f.text.split('\n')[1]!.split(',')).sort((a, b) => (BigInt(a[0]!) < BigInt(b[0]!) ? -1 : 1))[0]!;
  const wall = (mono: string) => new Date(Date.parse(first[1]!) + Number(BigInt(mono) - BigInt(first[0]!)) / 1e6).toISOString();
  return [...folderLines().map((l) => `${wall(l.monoNs)} run launcher stderr | ${l.line}`), ...more].join('\n');
}

describe("the Timeline's last Build & Run: the launcher's lines of the job's log (wall time)", () => {
  it('marks MAB gone at the line\'s time on the records\' clock, the moment the Monitor\'s replay of the job shows it', () => {
    const logs = folderLogs();
    const lines = launcherLinesOf(jobLog());
    expect(lines.length).toBe(9);
    const gone = goneFromLauncherLines(logs, launcherLinesOnRecordClock(logs, lines));
    expect(gone.map((g) => [g.module, g.words])).toEqual([[KILLED.module, KILLED.words]]);
    // the job log's times are the service's, to the millisecond: the line's own time within one
    expect(Math.abs(gone[0]!.at - KILLED.at)).toBeLessThan(1e6);
    // the Monitor's replay of the same logs and lines: its mark at the same time (its time 0 the first record)
    const steps: Generator<void, RecordedRun> = recordedRunSteps(logs, 7, { checkpointEvery: 64 });
    let step = steps.next();
    while (!step.done) step = steps.next();
    const model = step.value.model;
    applyLauncherLines(model, logs, lines);
    const marks = model.marks.filter((k) => k.kind === 'crash');
    expect(marks.map((k) => k.where)).toEqual([KILLED.module]);
    expect(marks[0]!.t + model.t0!).toBe(gone[0]!.at);
  });

  it("takes only the launcher's own line naming the module's own pid", () => {
    const logs = folderLogs();
    const t = '2026-12-07T20:44:18.000Z';
    const forged = launcherLinesOf([
      `${t} run launcher stderr | module ORD (pid 99) died by signal 9 (Killed)`,
      `${t} run MAA stderr | module ORD (pid 61) died by signal 9 (Killed)`,
      `${t} run launcher stdout | module ORD (pid 61) died by signal 9 (Killed)`,
    ].join('\n'));
    expect(goneFromLauncherLines(logs, launcherLinesOnRecordClock(logs, forged))).toEqual([]);
    const own = launcherLinesOf(`${t} run launcher stderr | module ORD (pid 61) died by signal 9 (Killed)`);
    expect(goneFromLauncherLines(logs, launcherLinesOnRecordClock(logs, own)).map((g) => g.module)).toEqual(['ORD']);
    // no log begins with a record: no time line to put the lines on, none taken
    expect(launcherLinesOnRecordClock([{ name: 'ORD_1.csv', text: 'mono_ns,wall_time,module,event,peer,port,size,detail\n' }], own)).toEqual([]);
  });

  it("ends MAB's bar still running at the line's time", () => {
    // its log cut after its last run_started (killed inside that run)
    const logs = folderLogs().map((l) => (l.name.startsWith('MAB_') ? { ...l, text: l.text.slice(0, l.text.lastIndexOf('\n', l.text.lastIndexOf(',run_finished,')) + 1) } : l));
    const gone = goneFromLauncherLines(logs, launcherLinesOnRecordClock(logs, launcherLinesOf(jobLog())));
    const { acts } = activationsFromLogs(logs);
    const last = acts.filter((a) => a.module === 'MAB').pop()!;
    expect(endGoneActivations(acts, gone)).toBe(1);
    expect(last.end).toBe(gone[0]!.at);
    expect(last.gone).toBe(KILLED.words);
  });
});
