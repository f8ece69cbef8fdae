/**
 * The field test's 7-module project (fixtures/manip-run: its README says what was kept of the
 * real run's logs and of its simulation's trace file): supervisors MIS (function mission) and MNP
 * (function manipulate), periodic schema armLoop, event schema safetyNet (EST, GRP). MNP's rule
 * ARMON activates armLoop (activation #4) and safetyNet, sharing EST, which MIS's BOOT started;
 * GRAB then AGAIN asks ORD for armLoop again (#5): refused (conflict, ORD:1), AGAIN ends on it
 * and its undo is ignored by ORD (not this activation). What the Monitor shows of it is what
 * `contract trace` tells: in a folder's replay, and in a trace file's, in the file's order.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { StoryTeller, recordOfJsonLine, traceFileToLogs, type LogFile } from '@contract-studio/build-service/trace';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import type { MonitorModel } from './monitor-model.js';
import { activeSchemas, type SchemaInfo } from './active-schemas.js';

const dir = fileURLToPath(new URL('./fixtures/manip-run', import.meta.url));
const logs: LogFile[] = readdirSync(dir).filter((n) => n.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(dir, name), 'utf8') }));
const simText = readFileSync(join(dir, 'sim1.jsonl'), 'utf8');

const CATALOGUE: SchemaInfo[] = [
  { name: 'armLoop', kind: 'periodic', modules: ['ARM'] },
  { name: 'baseLoop', kind: 'periodic', modules: ['LDR', 'ODM', 'PLN'] },
  { name: 'safetyNet', kind: 'event', modules: ['EST', 'GRP'] },
];

function built(steps: Generator<void, RecordedRun>): MonitorModel {
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

/** The folder's replay (its logs merged by time, as `contract trace logs` reads them). */
const folder = () => built(recordedRunSteps(logs, 7, { checkpointEvery: 16 }));
/** The simulation's trace file replayed as the Monitor replays a trace file: its logs, folded in the file's order. */
function simulation(withOrder = true): MonitorModel {
  const t = traceFileToLogs('sim1.jsonl', simText);
  return built(recordedRunSteps(t.files, 7, { checkpointEvery: 16 }, undefined, withOrder ? t.order : undefined));
}

/** The state `s` seconds after the run's first record. */
const at = (m: MonitorModel, s: number) => m.stateAt(Math.round(s * 1e9));
const by = (m: MonitorModel, s: number) => Object.fromEntries(activeSchemas(at(m, s), CATALOGUE).map((a) => [a.name, a.by]));

describe('the field test\'s manipulator run in the Monitor (fixtures/manip-run)', () => {
  // the real run: ARMON at +0.119885 s, ORD activates #4 at +0.120059, AGAIN's #5 refused at +0.424444,
  // ORD deactivates #4 at +2.639007; the simulation: +0.007, +0.313, +2.527
  for (const [what, model, times] of [
    ['a folder of its logs', folder, [0.2, 0.4245, 0.5, 1.0, 2.2, 2.6]],
    ['its simulation\'s trace file', simulation, [0.1, 0.3131, 0.5, 1.0, 2.2, 2.52]],
  ] as const) {
    it(`shows armLoop with the rule whose request ORD serves (ARMON's #4), not AGAIN's refused #5: ${what}`, () => {
      const m = model();
      for (const s of times) expect(by(m, s).armLoop, `+${s} s`).toBe('MNP.manipulate.ARMON');
      // AGAIN's row never says it started armLoop (ORD refused its request)
      for (const s of times) expect(at(m, s).supervisors.get('MNP')!.rules.get('manipulate.AGAIN')?.started ?? [], `+${s} s`).toEqual([]);
    });

    it(`shows safetyNet with MNP's ARMON, whose action activated it, not MIS's BOOT, which started EST: ${what}`, () => {
      const m = model();
      for (const s of times) expect(by(m, s).safetyNet, `+${s} s`).toBe('MNP.manipulate.ARMON');
    });

    it(`lists what ARMON started and the modules it took a hold on, EST shared: ${what}`, () => {
      const m = model();
      const started = at(m, 1.0).supervisors.get('MNP')!.rules.get('manipulate.ARMON')!.started;
      expect([...started].sort()).toEqual(['EST (shared)', 'GRP', 'armLoop', 'safetyNet']);
    });

    it(`marks ORD's ignored undo of the refused activation after that undo, as contract trace tells it: ${what}`, () => {
      const labels = model().marks.map((x) => `${x.where}: ${x.label}`);
      const conflict = labels.indexOf('armLoop: conflict: armLoop shares a module with active armLoop (ORD:1)');
      const ignored = labels.indexOf('armLoop: ignored: deactivate armLoop (not this activation)');
      expect(conflict).toBeGreaterThanOrEqual(0);
      expect(ignored).toBeGreaterThan(conflict);
      expect(labels.indexOf('MNP: manipulate.AGAIN inactive ← ORD:1 = "armLoop"')).toBeGreaterThan(conflict);
    });
  }

  it('replays a simulation\'s trace file in the file\'s order, causes before effects at one time, as contract trace tells it', () => {
    // what `contract trace sim1.jsonl` tells, in its order: each told record's module and words
    const teller = new StoryTeller();
    const story = simText.split('\n').map((l, i) => recordOfJsonLine('sim1.jsonl', i + 1, l)).flatMap((r) => (r ? [teller.tell(r)] : [])).filter((l): l is string => !!l);
    const told = (s: string) => story.findIndex((l) => l.includes(s));
    expect(told('ORD  conflict: armLoop')).toBeLessThan(told('MNP  rule manipulate.AGAIN inactive'));
    expect(told('ORD  deadline miss (ORD:0): armLoop cycle 40')).toBeLessThan(told('MIS  rule mission.MISS active'));
    for (const withOrder of [true, false]) {
      const labels = simulation(withOrder).marks.map((x) => `${x.where}: ${x.label}`);
      const pos = (s: string) => labels.findIndex((l) => l.startsWith(s));
      const inOrder = [
        pos('armLoop: conflict') < pos('MNP: manipulate.AGAIN inactive ← ORD:1'),
        pos('armLoop: deadline miss (ORD:0) cycle 40') < pos('MIS: mission.MISS active ← ORD:0'),
        pos('armLoop: deadline miss (ORD:0) cycle 40') < pos('MNP: manipulate.LATE active ← ORD:0'),
      ];
      // merged by time then log name (the logs' order), MIS and MNP came before ORD at one time
      expect(inOrder, withOrder ? 'in the file\'s order' : 'merged by time').toEqual(withOrder ? [true, true, true] : [false, false, false]);
    }
  });

  it('folds a trace file\'s records in the file\'s order, each record once', () => {
    const t = traceFileToLogs('sim1.jsonl', simText);
    const lines = simText.split('\n').filter((l) => l && !l.includes('"kind":"sim_start"'));
    expect(t.order.length).toBe(lines.length);
    expect(simulation().recordCount).toBe(lines.length);
    // each entry names the log of its line's module
    lines.forEach((l, i) => expect(t.files[t.order[i]!]!.name.startsWith(`${JSON.parse(l).module}_`)).toBe(true));
  });
});
