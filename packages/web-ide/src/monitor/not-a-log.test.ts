import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { NOT_A_LOG_WHY } from '@contract-studio/build-service/trace';
import { recordedRunSteps } from './recorded-run.js';
import type { MonitorModel } from './monitor-model.js';
import { notSupervisorText, notSupervisors, supervisorRows } from './supervisor-rows.js';
import { activationsFromLogs } from '../views/run-logs.js';

/**
 * What a module's code may write to fool the readers of a run (docs/runtime-api.md "Whose
 * records, and their times"), on a real run's logs (the tutorial, fixtures/tutorial-run, under the
 * names the runtime gives them): a file of its own in the logs folder named as ORD's log, with no
 * header (the runtime begins every log with it), and supervisor lines appended to its own log.
 */
const dir = fileURLToPath(new URL('./fixtures/tutorial-run', import.meta.url));
const DATE = '4-Dec-2026-05h49m24s';
const real = readdirSync(dir).filter((f) => f.endsWith('.csv')).map((f) => ({ name: `${f.slice(0, -4)}_${DATE}.csv`, text: readFileSync(join(dir, f), 'utf8') }));
const FORGED = 'ORD_4-Dec-2026-05h49m59s.csv';
/** ORD's deadline miss, its clock consistent with ORD's log (between its first cycles). */
const MISS = '52092900000000,2026-12-04T05:49:27.253000Z,ORD,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=3 tick_ns=52092787155629';
/** What MSC's code appends to its own log (MSC: a synchronous module of schemaCommande1, ORD runs it). */
const MSC = `MSC_${DATE}.csv`;
const SUPERVISOR_LINES = [
  '52094200000000,2026-12-04T05:49:28.553000Z,MSC,supervisor,,,0,function <img src=x onerror=alert(1)>() started',
  '52094200000100,2026-12-04T05:49:28.553000Z,MSC,sup_rule,,,0,rule <b>X</b>.Y active',
];
const withLines = (name: string, extra: string[]) => real.map((f) => (f.name === name ? { ...f, text: `${f.text}${extra.join('\n')}\n` } : f));

function replay(files: { name: string; text: string }[]): { model: MonitorModel; leftOut: string[] } {
  const steps = recordedRunSteps(files, 1000);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value;
}

describe('a file named as ORD\'s log that does not begin with the runtime\'s header', () => {
  it('replayed: refused whole and said first, not as ORD\'s second log; no deadline miss of ORD', () => {
    const clean = replay(real);
    const { model, leftOut } = replay([...real, { name: FORGED, text: `${MISS}\n` }]);
    expect(leftOut).toEqual([`${FORGED}: ${NOT_A_LOG_WHY}`]);
    const misses = (m: MonitorModel) => m.live.periodic.get('schemaCommande1')!.deadlineMisses;
    expect(misses(model)).toBe(misses(clean.model));
    expect(model.marks.filter((x) => x.kind === 'miss')).toEqual(clean.model.marks.filter((x) => x.kind === 'miss'));
    expect(model.live.records).toBe(clean.model.live.records);
    expect(model.live.unknownLines).toBe(clean.model.live.unknownLines + 1); // its line 1, as `contract trace` counts it
  });

  it('said before the other notes of the replay (two logs of one module, lines that are no record)', () => {
    const { leftOut } = replay([...withLines(MSC, ['junk']), { name: FORGED, text: `${MISS}\n` }, { name: `MSC_${DATE.replace('24s', '25s')}.csv`, text: real.find((f) => f.name === MSC)!.text }]);
    expect(leftOut[0]).toBe(`${FORGED}: ${NOT_A_LOG_WHY}`);
    expect(leftOut[1]).toMatch(/^MSC: 2 logs of it/);
  });

  it('the Timeline: said as a file that is no log, not as ORD\'s second log', () => {
    const { errors } = activationsFromLogs([...real, { name: FORGED, text: `${MISS}\n` }]);
    expect(errors).toEqual([`${FORGED}: not a ContrACT CSV log (missing mono_ns/module/event columns)`]); // not ORD's second log
  });
});

describe('supervisor lines a plain module appends to its own log', () => {
  const lanes = (files: { name: string; text: string }[], model?: Parameters<typeof activationsFromLogs>[1]) => {
    const { acts } = activationsFromLogs(files, model);
    return [...new Set(acts.map((a) => a.module))].sort();
  };

  it('the Timeline keeps its lane and its bars: without a model (ORD ran it), and with the model (a synchronous module)', () => {
    const clean = activationsFromLogs(real).acts.filter((a) => a.module === 'MSC');
    expect(clean.length).toBeGreaterThan(0);
    const forged = withLines(MSC, SUPERVISOR_LINES);
    expect(lanes(forged)).toEqual(lanes(real));
    expect(activationsFromLogs(forged).acts.filter((a) => a.module === 'MSC')).toEqual(clean);
    const model = { supervisors: new Set(['SUP', 'GLB']), modules: new Set(['MSA', 'MSB', 'MSC', 'MSD', 'MAA', 'MAB']) };
    expect(activationsFromLogs(forged, model).acts.filter((a) => a.module === 'MSC')).toEqual(clean);
    // a real supervisor's function lines still make its bars
    expect(activationsFromLogs(forged, model).acts.filter((a) => a.module === 'SUP')).toEqual(activationsFromLogs(real).acts.filter((a) => a.module === 'SUP'));
  });

  it('the Monitor does not list among the supervisors a module the model says is none; it says its records once', () => {
    const { model } = replay(withLines(MSC, SUPERVISOR_LINES));
    const s = model.live;
    const catalogue = new Map([['SUP', new Map([['action', ['FIRST']]])]]);
    const modules = new Map([['MSC', 'synchronous module'], ['MSA', 'synchronous module']]);
    expect(supervisorRows(catalogue, s, modules).map((r) => r.name)).not.toContain('MSC');
    expect(supervisorRows(catalogue, s, modules).map((r) => r.name)).toContain('SUP');
    expect(notSupervisors(catalogue, s, modules)).toEqual([{ name: 'MSC', is: 'synchronous module' }]);
    expect(notSupervisorText('MSC', 'synchronous module')).toBe('MSC: supervisor records in its log, not taken for a supervisor\'s: the model says MSC is a synchronous module (its code wrote them into its log?)');
  });
});
