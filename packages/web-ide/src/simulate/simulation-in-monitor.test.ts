import { describe, it, expect } from 'vitest';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import type { SimulateStep } from '../../server/api-types.js';
import { MonitorModel } from '../monitor/monitor-model.js';
import { activeSchemas } from '../monitor/active-schemas.js';
import { stepsToTrace } from '@contract-studio/simulator/trace';

// the steps of a real simulation of examples/tutorial's scenarios/mission.scenario as POST
// /api/simulate answers them: GLB.mission activates SUP.action, MAA:2 "disconnected" at 300 ms
// (SECOND, schemaCommande1), MSC:1 at 1 s (FOURTH, schemaCommande2, SUP.action stopped). Recorded
// with the current simulator by scripts/record-mission-steps.mjs (run it again after a change of
// the simulator's records: `npm run build:server -w packages/web-ide && node
// packages/web-ide/scripts/record-mission-steps.mjs`)
const steps = JSON.parse(readFileSync(fileURLToPath(new URL('./fixtures/tutorial-mission-steps.json', import.meta.url)), 'utf8')) as SimulateStep[];
const releasesIn = (schema: string) => steps.flatMap((s) => s.log ?? []).filter((l) => l.who === 'ORD' && l.line.endsWith(`(${schema})`) && l.line.startsWith('release ')).length;

function fold(ss: SimulateStep[]): MonitorModel {
  const model = new MonitorModel({ checkpointEvery: 8 });
  model.pushAll(stepsToTrace(ss));
  return model;
}

describe('a simulation in the Monitor', () => {
  for (const withLog of [true, false]) {
    it(`has the functions a supervisor activated, their holds, START requests and action counts${withLog ? '' : ' (an answer without the engines\' lines)'}`, () => {
      const model = fold(withLog ? steps : steps.map(({ log: _log, ...s }) => s));
      const at = (t: number) => model.stateAt(t);
      // SUP.action was started by GLB's rule SINGLE (`activate supervisor SUP.action`), not by a step
      expect(at(1.5e6).supervisors.get('SUP')?.functions.get('action')?.state).toBe('running');
      expect(at(1.5e6).supervisors.get('GLB')?.functions.get('mission')?.state).toBe('running');
      expect(model.live.supervisors.get('SUP')?.functions.get('action')?.state).toBe('stopped');
      // FIRST started its event schema and holds its modules MAA and MAB, SECOND asked ORD for schemaCommande1
      const first = at(100e6);
      expect([...first.supervisors.get('SUP')!.rules.get('action.FIRST')!.started].sort()).toEqual(['MAA', 'MAB', 'schemaReceptionMessage']);
      expect(activeSchemas(first, [{ name: 'schemaReceptionMessage', kind: 'event', modules: ['MAA', 'MAB'] }])).toEqual([{ name: 'schemaReceptionMessage', kind: 'event', by: 'SUP.action.FIRST' }]);
      const second = at(500e6);
      expect(second.supervisors.get('SUP')!.rules.get('action.SECOND')?.started).toContain('schemaCommande1');
      expect(second.schemas.get('schemaCommande1')).toMatchObject({ active: true, by: 'SUP.action.SECOND' });
      // the actions counted: holds, requests, subscriptions done; holds dropped, unsubscriptions undone
      const sup = model.live.supervisors.get('SUP')!;
      expect(sup.actionsDone).toBeGreaterThan(5);
      expect(sup.actionsUndone).toBeGreaterThan(3);
      expect(model.live.supervisors.get('GLB')!.actionsDone).toBeGreaterThanOrEqual(2); // activate supervisor, subscribe
      expect(model.live.supervisors.get('GLB')!.actionsUndone).toBeGreaterThanOrEqual(2); // stop SUP.action, unsubscribe
      expect(model.marks.filter((m) => m.kind === 'function').map((m) => m.where)).toContain('SUP'); // on the time line's strip too
    });
  }

  it('has ORD\'s releases, their cycles counted from 0 at each activation', () => {
    const model = fold(steps);
    expect(releasesIn('schemaCommande1')).toBeGreaterThan(0);
    const p = model.live.periodic.get('schemaCommande1')!;
    expect(p.releases).toBe(releasesIn('schemaCommande1'));
    expect(p.lastCycle).toBe(0); // MSA, MSC, MSD released once each: one cycle
    expect(p.lastRelease).toBe(301_500_000);
    expect(model.live.periodic.get('schemaCommande2')?.releases).toBe(releasesIn('schemaCommande2'));
    expect(model.stateAt(300_200_000).periodic.get('schemaCommande1')?.releases).toBe(1);
  });

  it('has a deadline miss ORD sent, on the cycle it was in, and a crash', () => {
    const model = fold([
      { line: 1, source: 'start SUP.f', timeNs: 0, kind: 'start', ok: true, message: '', rules: [], schemas: ['S'], locals: [], actions: [],
        log: [{ timeNs: 0, who: 'ORD', line: 'activate S' }, { timeNs: 0, who: 'ORD', line: 'release CTL (S)' }, { timeNs: 10e6, who: 'ORD', line: 'release CTL (S)' },
          { timeNs: 12e6, who: 'ORD', line: 'deadline miss: S (ORD:0)' }] },
      { line: 2, source: 'crash CTL', timeNs: 20e6, kind: 'crash', ok: true, message: '', rules: [], schemas: ['S'], locals: [],
        actions: [{ timeNs: 12e6, who: 'ORD', what: 'ORD:0 "S" (deadline miss) to every supervisor' }, { timeNs: 20e6, who: 'CTL', what: 'crashed' }], log: [] },
    ]);
    expect(model.live.periodic.get('S')).toMatchObject({ releases: 2, lastCycle: 1, deadlineMisses: 1, recentMisses: [{ t: 12e6, cycle: 1 }] });
    expect(model.live.modules.get('CTL')?.alive).toBe(false);
    expect(model.live.unknownLines).toBe(0);
  });

  it('has the harness\'s typed records: module runs, cycles completed with their response times, event receipts', () => {
    const model = fold(steps);
    // schemaCommande1 at 300 ms: MSA (0.5 ms), then MSC (1 ms), then MSD (1 ms), by precedence
    expect(model.stateAt(300_200_000).modules.get('MSA')).toMatchObject({ running: true, runs: 1 });
    expect(model.stateAt(301_000_000).modules.get('MSA')?.running).toBe(false);
    expect(model.stateAt(301_000_000).modules.get('MSC')?.running).toBe(true);
    const p = model.live.periodic.get('schemaCommande1')!;
    expect(p).toMatchObject({ completions: 1, lastResponseNs: 2_500_000, maxResponseNs: 2_500_000, deadlineMisses: 0 });
    expect(p.histogram.reduce((a, b) => a + b, 0)).toBe(1);
    // MAA:2 "disconnected" received by SUP on its port 2; SUP's notification received by GLB
    expect(model.live.eventFlows.get('MAA:2->SUP:2')?.count).toBe(1);
    expect(model.live.eventFlows.get('SUP:1->GLB:0')?.count).toBe(1);
    // with their values, as the current simulator writes them (a fixture of an older one had none)
    expect(model.live.eventFlows.get('MAA:2->SUP:2')).toMatchObject({ lastValue: '"disconnected"' });
    expect(model.live.eventFlows.get('SUP:1->GLB:0')).toMatchObject({ lastValue: '"commutation"' });
    expect(model.live.unknownLines).toBe(0);
    // an answer without them (an older server): the releases still come from ORD's lines, nothing else does
    const older = fold(steps.map(({ records: _r, ...s }) => s));
    expect(older.live.periodic.get('schemaCommande1')?.releases).toBe(p.releases);
    expect(older.live.periodic.get('schemaCommande1')?.completions).toBe(0);
    expect(older.live.modules.get('MSA')?.runs ?? 0).toBe(0);
  });

  it('takes a deadline miss from its typed record once, on the cycle the harness names', () => {
    const rec = (timeNs: number, module: string, kind: string, peer: string, detail: string) => ({ timeNs, module, kind, peer, detail });
    const model = fold([
      { line: 1, source: 'start SUP.f', timeNs: 0, kind: 'start', ok: true, message: '', rules: [], schemas: ['S'], locals: [],
        actions: [{ timeNs: 12e6, who: 'ORD', what: 'ORD:0 "S" (deadline miss) to every supervisor' }],
        log: [{ timeNs: 0, who: 'ORD', line: 'activate S' }, { timeNs: 0, who: 'ORD', line: 'release CTL (S)' }, { timeNs: 12e6, who: 'ORD', line: 'deadline miss: S (ORD:0)' }],
        records: [
          rec(0, 'ORD', 'ord_release', 'CTL', 'schema=S cycle=0 tick_ns=0 release_ns=0 release=1'),
          rec(0, 'CTL', 'run_started', 'ORD', 'activation=1'),
          rec(10e6, 'ORD', 'ord_release', 'CTL', 'schema=S cycle=1 tick_ns=10000000 release_ns=10000000 release=2'),
          rec(12e6, 'ORD', 'ord_deadline_miss', '', 'schema=S cycle=1 tick_ns=10000000'),
        ] },
    ]);
    expect(model.live.periodic.get('S')).toMatchObject({ releases: 2, lastCycle: 1, deadlineMisses: 1, recentMisses: [{ t: 12e6, cycle: 1 }] });
    expect(model.live.modules.get('CTL')?.running).toBe(true);
  });
});
