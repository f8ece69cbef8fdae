/**
 * A module killed from outside (SIGKILL: no record of its end) shown gone as soon as a record says
 * so, and ORD killed shown ended with its schemas at its last record: the real runs of
 * fixtures/killed-ord-sortloop-run and fixtures/killed-module-run (their READMEs), replayed from
 * their logs and fed record by record as a live run is.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { LogFile } from '@contract-studio/build-service/trace';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import { MonitorModel } from './monitor-model.js';
import { activeSchemas } from './active-schemas.js';
import { crashedModulesText } from './panel-text.js';
import type { MonitorState } from './monitor-state.js';

function logsOf(name: string): LogFile[] {
  const dir = fileURLToPath(new URL(`./fixtures/${name}`, import.meta.url));
  return readdirSync(dir).filter((n) => n.endsWith('.csv')).map((n) => ({ name: n, text: readFileSync(join(dir, n), 'utf8') }));
}

function built(logs: LogFile[], whole = true): MonitorModel {
  const steps: Generator<void, RecordedRun> = recordedRunSteps(logs, 7, { checkpointEvery: 64 }, undefined, undefined, whole);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

/** The logs' records in time order, each with its log and line (as the live trace channel brings them). */
function liveLines(logs: LogFile[]): Array<{ file: string; line: number; text: string; mono: bigint }> {
  return logs.flatMap((f) => f.text.split('\n').map((text, i) => ({ file: f.name, line: i + 1, text, mono: /^\d+,/.test(text) ? BigInt(text.split(',')[0]!) : -1n })))
    .filter((l) => l.mono >= 0n).sort((a, b) => (a.mono < b.mono ? -1 : a.mono > b.mono ? 1 : 0));
}

const CATALOGUE = [{ name: 'sortLoop', kind: 'periodic', modules: ['CAM', 'SRT', 'BLT'] }];
const running = (s: MonitorState) => [...s.modules].filter(([, m]) => m.running).map(([n]) => n);

describe('ORD killed (its log ends with no exit record)', () => {
  const logs = logsOf('killed-ord-sortloop-run');
  const ordLog = logs.find((l) => l.name.startsWith('ORD_'))!;
  const ordLines = ordLog.text.trim().split('\n');
  const t0 = Number(liveLines(logs)[0]!.mono);
  const ordLast = Number(ordLines[ordLines.length - 1]!.split(',')[0]) - t0;

  it('a replay of logs read in part (past the replay\'s bound): ORD\'s log ending there says nothing of ORD (sortLoop still shown active, no mark)', () => {
    // without the one record that says ORD has ended (SUP's STOP to it, 'not sent, it has ended'): only the logs' end could say it
    const unsaid = logs.map((l) => ({ ...l, text: l.text.split('\n').filter((line) => !line.includes('it has ended')).join('\n') }));
    const cut = built(unsaid, false);
    expect(activeSchemas(cut.stateAt(cut.end), CATALOGUE).map((a) => a.name)).toEqual(['sortLoop']);
    expect(cut.marks.filter((m) => m.label.startsWith('ORD gone'))).toEqual([]);
    // the same logs whole: their end is the run's, ORD's missing exit record is said
    const whole = built(unsaid);
    expect(activeSchemas(whole.stateAt(whole.end), CATALOGUE)).toEqual([]);
    expect(whole.marks.filter((m) => m.label.startsWith('ORD gone'))).toHaveLength(1);
  });

  it('a replay shows sortLoop ended, and ORD not running, from ORD\'s last record on, with a mark there', () => {
    const model = built(logs);
    expect(model.end - ordLast).toBeGreaterThan(2e9); // the other modules ran 2.4 s longer
    const before = model.stateAt(ordLast - 1);
    expect(activeSchemas(before, CATALOGUE).map((a) => a.name)).toEqual(['sortLoop']);
    for (const t of [ordLast, ordLast + 1e9, model.end]) {
      const s = model.stateAt(t);
      expect(activeSchemas(s, CATALOGUE)).toEqual([]);
      expect(s.schemas.get('sortLoop')!.since).toBe(ordLast);
      expect(running(s)).not.toContain('ORD');
    }
    const marks = model.marks.filter((m) => m.kind === 'schema' && m.label.startsWith('ORD gone'));
    expect(marks).toEqual([{ t: ordLast, kind: 'schema', where: 'sortLoop', label: expect.stringMatching(/sortLoop is shown ended here/) }]);
    // the marks stay in time order (a view finds them by binary search)
    expect(model.marks.every((m, i) => i === 0 || model.marks[i - 1]!.t <= m.t)).toBe(true);
  });

  it('live, shows it as soon as SUP\'s record says ORD has ended, at ORD\'s last record, before the job ends', () => {
    const model = new MonitorModel({ checkpointEvery: 64 });
    const lines = liveLines(logs);
    const sign = lines.findIndex((l) => l.text.includes('STOP request to ORD: not sent, it has ended'));
    expect(sign).toBeGreaterThan(0);
    for (const l of lines.slice(0, sign)) model.pushLine(l.file, l.line, l.text);
    expect(activeSchemas(model.live, CATALOGUE).map((a) => a.name)).toEqual(['sortLoop']); // no sign yet
    model.pushLine(lines[sign]!.file, lines[sign]!.line, lines[sign]!.text);
    expect(activeSchemas(model.live, CATALOGUE)).toEqual([]);
    expect(activeSchemas(model.stateAt(ordLast + 5e8), CATALOGUE)).toEqual([]);
    expect(activeSchemas(model.stateAt(ordLast - 1), CATALOGUE).map((a) => a.name)).toEqual(['sortLoop']);
    expect(crashedModulesText(model.live.modules)).toMatch(/^⚠ ORD gone at \+\S+ s: SUP: STOP request to ORD: not sent, it has ended/);
  });

  it('live without such a record, shows it when the job ends', () => {
    const model = new MonitorModel({ checkpointEvery: 64 });
    for (const l of liveLines(logs)) if (!l.text.includes('not sent, it has ended')) model.pushLine(l.file, l.line, l.text);
    expect(activeSchemas(model.live, CATALOGUE).map((a) => a.name)).toEqual(['sortLoop']);
    model.recordsEnded();
    expect(activeSchemas(model.live, CATALOGUE)).toEqual([]);
    expect(model.live.schemas.get('sortLoop')!.since).toBe(ordLast);
  });

  it('an ORD that exited is left to its exit record', () => {
    const model = built(logsOf('tutorial-run'));
    expect(model.marks.filter((m) => m.label.startsWith('ORD gone'))).toEqual([]);
  });
});

describe('a module SIGKILLed from outside (no record of its end)', () => {
  const logs = logsOf('killed-module-run');
  const lines = liveLines(logs);
  const sign = lines.findIndex((l) => /ORD,error,.*START request to SRT: module not running/.test(l.text));
  const srtLast = lines.filter((l) => l.file.startsWith('SRT_')).at(-1)!;

  it('live, is flagged at ORD\'s first record saying it is gone, 24 ms after its last record, as a crash is', () => {
    expect(Number(lines[sign]!.mono - srtLast.mono) / 1e6).toBeLessThan(30);
    const model = new MonitorModel({ checkpointEvery: 64 });
    for (const l of lines.slice(0, sign)) model.pushLine(l.file, l.line, l.text);
    expect(crashedModulesText(model.live.modules)).toBe('');
    model.pushLine(lines[sign]!.file, lines[sign]!.line, lines[sign]!.text);
    const t = Number(lines[sign]!.mono) - Number(lines[0]!.mono);
    expect(crashedModulesText(model.live.modules)).toBe(`⚠ SRT gone at +${(t / 1e9).toFixed(6)} s: ORD: START request to SRT: module not running (its mailbox is stale) (Connection refused)`);
    expect(running(model.live)).not.toContain('SRT');
    expect(model.marks.filter((m) => m.kind === 'crash')).toEqual([{ t, kind: 'crash', where: 'SRT', label: expect.stringMatching(/^SRT gone: ORD: START request to SRT: module not running/) }]);
  });

  it('a replay says it once (ORD\'s later stuck record adds nothing), and not before the sign', () => {
    const model = built(logs);
    const crash = model.marks.filter((m) => m.kind === 'crash');
    expect(crash.map((m) => m.where)).toEqual(['SRT']);
    expect(crashedModulesText(model.stateAt(crash[0]!.t - 1).modules)).toBe('');
    expect(crashedModulesText(model.stateAt(model.end).modules)).toMatch(/^⚠ SRT gone at/);
  });
});
