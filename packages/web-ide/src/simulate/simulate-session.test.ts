/**
 * The Simulate panel's pure parts: the session grown into a scenario text (times never go back,
 * hostile input refused, the text parses with the simulator's own parser, the saved text carries
 * the shown state as expectations) and the steps turned into the Monitor's trace records.
 */
import { describe, it, expect } from 'vitest';
import { parseScenario } from '@contract-studio/language/scenario';
import type { SimulateStep } from '../../server/api-types.js';
import { MonitorModel } from '../monitor/monitor-model.js';
import { ScenarioSession } from './scenario-session.js';
import { stepsToTrace } from '@contract-studio/simulator/trace';

const step = (over: Partial<SimulateStep>): SimulateStep => ({ line: 0, source: '', timeNs: 0, kind: 'event', ok: true, rules: [], actions: [], schemas: [], locals: [], ...over });

describe('ScenarioSession', () => {
  it('grows a scenario text that the simulator parses: start at 0, steps at the session time, until now', () => {
    const s = new ScenarioSession();
    expect(s.inject('MAA:2 "x"')).toMatch(/start/);
    expect(s.begin({ supervisor: 'SUP', fn: 'action', params: 'consigne = {1.0, 2.0, 3.0}' })).toBeUndefined();
    expect(s.advance('+1ms')).toBeUndefined();
    expect(s.inject('MAA:2 connection_status = "disconnected"')).toBeUndefined();
    expect(s.advance('1.5s')).toBeUndefined();
    expect(s.inject('crash MSC')).toBeUndefined();
    expect(s.inject('finish MAB')).toBeUndefined();
    expect(s.text('t')).toBe('scenario t\nuntil 1500ms\nstart SUP.action(consigne = {1.0, 2.0, 3.0})\nt=1ms MAA:2 connection_status = "disconnected"\nt=1500ms crash MSC\nt=1500ms finish MAB\n');
    const parsed = parseScenario(s.text());
    expect(parsed.diagnostics).toEqual([]);
    expect(parsed.steps.map((x) => [x.kind, x.atNs, x.span.line])).toEqual([['start', 0, 3], ['event', 1_000_000, 4], ['crash', 1_500_000_000, 5], ['finish', 1_500_000_000, 6]]);
    s.undo();
    s.undo();
    expect(s.lines).toHaveLength(1);
    // every step directive of the parser but start is injectable; start and header lines are not
    const started = () => {
      const x = new ScenarioSession();
      x.begin({ supervisor: 'SUP', fn: 'action', params: '' });
      return x;
    };
    for (const d of ['stop SUP.action', 'crash MSC', 'finish MAB', 'exec MSC 2ms', 'expect rule SUP.action.FIRST active']) expect(started().inject(d)).toBeUndefined();
    for (const d of ['start SUP.action()', 'scenario x', 'until 1s']) expect(started().inject(d)).toMatch(/^a step:/);
  });

  it('grows a session again from its snapshot, through the same checks; anything else is refused and changes nothing', () => {
    const s = new ScenarioSession();
    s.begin({ supervisor: 'SUP', fn: 'action', params: 'consigne = {1.0, 2.0, 3.0}' });
    s.advance('1ms');
    s.inject('MAA:2 "disconnected"');
    s.advance('2ms');
    s.inject('finish MAB');
    s.advance('6ms');
    const kept = JSON.parse(JSON.stringify({ project: 'p', ...s.snapshot() }));
    const again = new ScenarioSession();
    expect(again.restore(kept)).toBeUndefined();
    expect(again.text()).toBe(s.text());
    expect(again.nowNs).toBe(6_000_000);
    // hostile or damaged storage: refused with a reason, the session as it was
    const other = new ScenarioSession();
    other.begin({ supervisor: 'GLB', fn: 'mission', params: '' });
    const bad: unknown[] = [
      null, 'x', 42, {}, { ...kept, start: { supervisor: 'SUP', fn: 'a b', params: '' } },
      { ...kept, start: { ...kept.start, params: 'x = 1\nstop SUP.action' } },
      { ...kept, lines: [{ atNs: 1e6, text: 'MAA:2 "a"\nuntil 9s' }] },
      { ...kept, lines: [{ atNs: 2e6, text: 'MAA:2 "a"' }, { atNs: 1e6, text: 'MAA:2 "b"' }] }, // time going back
      { ...kept, lines: [{ atNs: 1e6, text: 'until 9s' }] },
      { ...kept, nowNs: 1e6 }, // before its last step
      { ...kept, nowNs: 1e30 },
      { ...kept, lines: Array.from({ length: 2_001 }, () => ({ atNs: 0, text: 'MAA:2 "a"' })) },
      { ...kept, lines: [{ atNs: '1ms', text: 'MAA:2 "a"' }] },
    ];
    for (const b of bad) expect(other.restore(b), JSON.stringify(b)?.slice(0, 80)).toBeTruthy();
    expect(other.text()).toBe('scenario simulation session\nuntil 0\nstart GLB.mission()\n');
  });

  it('refuses times going back, non-times, several lines, comments and unknown directives', () => {
    const s = new ScenarioSession();
    expect(s.begin({ supervisor: 'SUP', fn: 'a b', params: '' })).toBeTruthy();
    expect(s.begin({ supervisor: 'SUP', fn: 'action', params: 'x = 1\nstop SUP.action' })).toBeTruthy();
    s.begin({ supervisor: 'SUP', fn: 'action', params: '' });
    s.advance('2ms');
    expect(s.advance('1ms')).toMatch(/backwards/);
    expect(s.advance('soon')).toMatch(/not a time/);
    expect(s.advance('+100000000s')).toMatch(/one day/);
    expect(s.inject('MAA:2 "a"\nstart SUP.action')).toMatch(/one line/);
    expect(s.inject('t=0 MAA:2 "a"')).toBeTruthy();
    expect(s.inject('until 5s')).toBeTruthy();
    expect(s.inject('')).toBeTruthy();
    expect(s.lines).toEqual([]);
    expect(s.nowNs).toBe(2_000_000);
    expect(s.text()).toBe('scenario simulation session\nuntil 2ms\nstart SUP.action()\n');
  });

  it('saves the shown state as expectations at the session time', () => {
    const s = new ScenarioSession();
    s.begin({ supervisor: 'SUP', fn: 'action', params: '' });
    s.advance('1ms');
    const steps = [step({ rules: [{ timeNs: 1e6, supervisor: 'SUP', function: 'action', rule: 'FIRST', active: true, cause: 'elapsed=1000000ns' }] }),
      step({ kind: 'end', rules: [{ timeNs: 1e6, supervisor: 'SUP', function: 'action', rule: 'FIRST', active: false, cause: 'x' }], schemas: ['S1'] })];
    const text = s.withExpectations(steps, { periodic: new Map() });
    expect(text).toContain('expect at 1ms rule SUP.action.FIRST inactive\nexpect at 1ms schema S1 active\n');
    expect(parseScenario(text).diagnostics).toEqual([]);
  });
});

describe('Save as scenario with deadline misses and overruns', () => {
  const rec = (kind: string, detail: string) => ({ timeNs: 1, module: 'ORD', kind, peer: '', detail });
  it('pins each released periodic schema\'s deadline misses and overruns, 0 included; none when records were left out', () => {
    const s = new ScenarioSession();
    s.begin({ supervisor: 'MIS', fn: 'mission', params: '' });
    s.advance('30ms');
    const steps = [
      step({ records: [rec('ord_release', 'schema=goTo cycle=0 tick_ns=1 release_ns=1 release=1'), rec('ord_release', 'schema=other cycle=0 tick_ns=1 release_ns=1 release=2')] }),
      step({ kind: 'end', records: [rec('ord_deadline_miss', 'schema=goTo cycle=0 tick_ns=1 missing=CTL'), rec('scheduler', 'schema=goTo'), rec('ord_release', 'schema=goTo cycle=1 tick_ns=2 release_ns=2 release=3')] }),
    ];
    // as the Simulate panel does: the Monitor's state of the same steps
    const shown = (list: SimulateStep[]) => {
      const model = new MonitorModel();
      model.pushAll(stepsToTrace(list));
      return model.live;
    };
    const text = s.withExpectations(steps, shown(steps));
    expect(text).toContain('expect at 30ms deadline misses goTo == 1\nexpect at 30ms overruns goTo == 0\nexpect at 30ms deadline misses other == 0\nexpect at 30ms overruns other == 0\n');
    expect(parseScenario(text).diagnostics).toEqual([]);
    // a step whose records were cut: no count (it could be wrong)
    const cut = [steps[0]!, { ...steps[1]!, dropped: 3 }];
    expect(s.withExpectations(cut, shown(cut))).not.toMatch(/deadline misses|overruns/);
  });
});

describe('ScenarioSession.nextChange', () => {
  it('finds the first rule change or action after now, in any step of a look-ahead run', () => {
    const steps = [step({ rules: [{ timeNs: 0, supervisor: 'S', function: 'f', rule: 'A', active: true, cause: 'started' }] }),
      step({ kind: 'end', actions: [{ timeNs: 5e6, who: 'ORD', what: 'x' }], rules: [{ timeNs: 1e6, supervisor: 'S', function: 'f', rule: 'B', active: true, cause: 'elapsed=1000000ns' }] })];
    expect(ScenarioSession.nextChange(steps, 0)).toBe(1e6);
    expect(ScenarioSession.nextChange(steps, 1e6)).toBe(5e6);
    expect(ScenarioSession.nextChange(steps, 5e6)).toBeUndefined();
  });

  it('finds the engines\' own records too: a release with no rule change or action goes before a later rule change', () => {
    const steps = [step({ kind: 'end',
      rules: [{ timeNs: 72e6, supervisor: 'S', function: 'f', rule: 'B', active: true, cause: 'elapsed=1000000ns' }],
      records: [{ timeNs: 50e6, seq: 1, module: 'ORD', kind: 'ord_release', peer: 'CLS', detail: '' }, { timeNs: 62e6, seq: 2, module: 'ORD', kind: 'ord_release', peer: 'CLS', detail: '' }] })];
    expect(ScenarioSession.nextChange(steps, 50e6)).toBe(62e6);
    expect(ScenarioSession.nextChange(steps, 62e6)).toBe(72e6);
    expect(ScenarioSession.nextChange(steps, 0)).toBe(50e6);
  });

  it('a look-ahead text runs later than now without moving the session', () => {
    const s = new ScenarioSession();
    s.begin({ supervisor: 'SUP', fn: 'action', params: '' });
    expect(s.text('x', 10e9)).toBe('scenario x\nuntil 10s\nstart SUP.action()\n');
    expect(s.nowNs).toBe(0);
  });
});

describe('stepsToTrace', () => {
  it('gives the Monitor the rules with their causes, the functions and the schemas at the virtual times', () => {
    const steps = [
      step({ kind: 'start', source: 'start SUP.action', timeNs: 0 }),
      step({ timeNs: 1_000_000, schemas: ['schemaReceptionMessage'], rules: [{ timeNs: 1_000_000, supervisor: 'SUP', function: 'action', rule: 'FIRST', active: true, cause: 'elapsed=1000000ns' }] }),
      step({ timeNs: 2_000_000, schemas: ['schemaCommande1'], rules: [
        { timeNs: 2_000_000, supervisor: 'SUP', function: 'action', rule: 'FIRST', active: false, cause: 'MAA:2 value="disconnected"' },
        { timeNs: 2_000_000, supervisor: 'SUP', function: 'action', rule: 'SECOND', active: true, cause: 'MAA:2 value="disconnected"' }] }),
    ];
    const model = new MonitorModel();
    model.pushAll(stepsToTrace(steps));
    const sup = model.live.supervisors.get('SUP')!;
    expect(sup.functions.get('action')?.state).toBe('running');
    expect(sup.rules.get('action.SECOND')).toMatchObject({ active: true, cause: 'MAA:2 value="disconnected"', since: 2_000_000 });
    expect(sup.rules.get('action.FIRST')?.active).toBe(false);
    expect(model.live.schemas.get('schemaCommande1')?.active).toBe(true);
    expect(model.live.schemas.get('schemaReceptionMessage')?.active).toBe(false);
    const at1 = model.stateAt(1_500_000);
    expect(at1.supervisors.get('SUP')!.rules.get('action.FIRST')?.active).toBe(true);
    expect(at1.schemas.get('schemaReceptionMessage')?.active).toBe(true);
  });
});
