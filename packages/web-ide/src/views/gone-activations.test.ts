/**
 * The Timeline's modules gone by the launcher's own end lines, from a real recorded run
 * (fixtures/killed-trace-run: MAB SIGKILLed in a bwrap run of the tutorial), read the two ways the
 * Timeline reads it: the trace file `contract run --trace` wrote (its `launcher_line` items) and the
 * logs folder (its contract-launch.log): the same module, time and words; with the pid rule (a line
 * naming another pid is not taken) and the modules that exited at the run's end not taken.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { launcherLinesOfFile, traceFileToLogs } from '@contract-studio/build-service/trace';
import { activationsFromLogs } from './run-logs.js';
import { endGoneActivations, goneFromLauncherLines } from './gone-activations.js';

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
