import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseTrace, parseRecordLine, renderStory, type TraceRecord } from '@contract-studio/build-service/trace';
import { MAX_ERROR_MARKS, MAX_USER_MARKS, MonitorModel } from './monitor-model.js';
import { applyRecord } from './apply-record.js';
import { emptyState, histogramBucket, bucketStartNs, type MonitorState } from './monitor-state.js';
import { activeSchemas } from './active-schemas.js';
import { recordedRunSteps } from './recorded-run.js';
import { releaseLatenessText } from './panel-text.js';

// a real run of examples/tutorial (`contract run --duration 4s`, bwrap; recorded again 2026-12-04 when supervisors began to write their event schemas' activations)
const dir = fileURLToPath(new URL('./fixtures/tutorial-run', import.meta.url));
const tutorial = parseTrace(readdirSync(dir).map((name) => ({ name, text: readFileSync(join(dir, name), 'utf8') })));

const W = '2026-11-26T12:00:00.000000Z';
const line = (ns: number, module: string, event: string, peer: string, port: string, detail: string) =>
  parseRecordLine('x.csv', 2, `${ns},${W},${module},${event},${peer},${port},0,${detail.includes(',') || detail.includes('"') ? `"${detail.replace(/"/g, '""')}"` : detail}`);

/** The state the records up to t give, folded from scratch (the reference for stateAt). */
function naive(records: TraceRecord[], t: number): MonitorState {
  const m = new MonitorModel({ checkpointEvery: 1 << 30 });
  for (const r of records) {
    if (r.kind !== 'unknown' && m.t0 !== undefined && Number((r as { monoNs: string }).monoNs) - m.t0 > t) break;
    m.push(r);
  }
  return m.live;
}

/** JSON.stringify replacer: a Map as its entries. */
const withMaps = (_k: string, v: unknown) => (v instanceof Map ? [...v] : v);

describe('supervisorChanges', () => {
  it('moves with every record that changes the supervisors, and only with those', () => {
    const s = emptyState();
    let changed = 0, unchanged = 0;
    for (const r of tutorial) {
      const before = JSON.stringify(s.supervisors, withMaps), count = s.supervisorChanges;
      applyRecord(s, r, Number((r as { monoNs?: string }).monoNs ?? 0), 0);
      if (JSON.stringify(s.supervisors, withMaps) !== before) {
        changed++;
        expect(s.supervisorChanges, `${r.kind} ${JSON.stringify(r).slice(0, 200)}`).toBeGreaterThan(count);
      } else if (s.supervisorChanges === count) unchanged++;
    }
    expect(changed).toBeGreaterThan(20); // rules, functions, holds, schemas started by a rule
    expect(unchanged).toBeGreaterThan(tutorial.length / 2); // releases, data, events: the list is not redrawn
  });
});

describe('the end of a run', () => {
  it('ORD gone: no periodic schema is active any more, even when no supervisor could deactivate it', () => {
    // a new project's run: MIS.START activates goTo; at the end the launcher stops ORD first, and
    // MIS's undo finds no ORD to ask (its CSV has no deactivate)
    const model = new MonitorModel({ checkpointEvery: 4 });
    const records = [
      line(1_000_000, 'ORD', 'module_started', '', '', 'pid=14 priority=90'),
      line(2_000_000, 'ORD', 'scheduler', '', '', 'activate goTo'),
      line(900_000_000, 'ORD', 'module_exit', '', '', 'status=0 records=709'),
      line(900_500_000, 'MIS', 'sup_rule', '', '', 'mission.START inactive cause=stop'),
    ];
    model.pushAll(records);
    const catalogue = [{ name: 'goTo', kind: 'periodic' as const, modules: ['LOC', 'CTL'] }];
    expect(activeSchemas(model.stateAt(500_000_000 - 1_000_000), catalogue).map((x) => x.name)).toEqual(['goTo']);
    expect(activeSchemas(model.live, catalogue)).toEqual([]);
    expect(model.live.schemas.get('goTo')).toMatchObject({ active: false, since: 899_000_000, activations: 1 });
  });
});

describe('a run held until a later time (a simulation\'s session past its last record)', () => {
  it('moves the end, not the state; states before the last record are as they were', () => {
    const model = new MonitorModel({ checkpointEvery: 4 });
    model.pushAll([line(0, 'ORD', 'scheduler', '', '', 'activate goTo'), line(2_500_000, 'ORD', 'scheduler', '', '', 'deactivate goTo')]);
    const before = model.stateAt(1_000_000);
    const v = model.version;
    model.holdUntil(3_000_000);
    expect(model.end).toBe(3_000_000);
    expect(model.version).toBeGreaterThan(v);
    expect(model.stateAt(1_000_000)).toEqual(before);
    expect(model.live.schemas.get('goTo')).toMatchObject({ active: false });
    model.holdUntil(1_000); // never back
    expect(model.end).toBe(3_000_000);
  });
});

describe('monitor model on a recorded tutorial run', () => {
  const model = new MonitorModel({ checkpointEvery: 16 });
  model.pushAll(tutorial);
  const s = model.live;

  it('has SUP.action with FIRST then SECOND, each with its cause and time', () => {
    const sup = s.supervisors.get('SUP')!;
    expect(sup.functions.get('action')!.state).toBe('stopped');
    const first = model.marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.FIRST active'))!;
    const second = model.marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.SECOND active'))!;
    // the causes in the words of the rule rows and `contract trace`
    expect(first.label).toBe('action.FIRST active ← elapsed=1ms');
    expect(second.label).toBe('action.SECOND active ← MAA:2 = "disconnected"');
    expect(second.t).toBeGreaterThan(first.t);
    const firstOff = model.marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.FIRST inactive'))!;
    expect(firstOff.label).toBe('action.FIRST inactive ← MAA:2 = "disconnected"');
    const mid = model.stateAt(second.t + 5e6);
    expect(mid.supervisors.get('SUP')!.rules.get('action.SECOND')).toMatchObject({ active: true, cause: 'MAA:2 value="disconnected"', since: second.t });
    expect(mid.supervisors.get('SUP')!.rules.get('action.FIRST')!.active).toBe(false);
    expect(mid.supervisors.get('SUP')!.rules.get('action.SECOND')!.started).toContain('schemaCommande1');
    const before = model.stateAt(firstOff.t - 1);
    expect(before.supervisors.get('SUP')!.rules.get('action.FIRST')).toMatchObject({ active: true, cause: 'elapsed=1000000ns' });
    // the event schema FIRST activated (its record), then the modules it started (their holds)
    expect(before.supervisors.get('SUP')!.rules.get('action.FIRST')!.started).toEqual(['schemaReceptionMessage', 'MAA', 'MAB']);
    expect(before.supervisors.get('SUP')!.heldModules).toEqual(new Map([['MAA', 'action.FIRST'], ['MAB', 'action.FIRST']]));
  });

  it('knows which schemas were active, who activated them, and the periodic releases', () => {
    const catalogue = [
      { name: 'schemaReceptionMessage', kind: 'event', modules: ['MAA', 'MAB'] },
      { name: 'schemaCommande1', kind: 'periodic', modules: ['MSA', 'MSC', 'MSD'] },
    ];
    const second = model.marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.SECOND active'))!;
    const firstOff = model.marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.FIRST inactive'))!;
    expect(activeSchemas(model.stateAt(firstOff.t - 1), catalogue)).toEqual([{ name: 'schemaReceptionMessage', kind: 'event', by: 'SUP.action.FIRST' }]);
    const after = model.stateAt(second.t + 5e6);
    expect(activeSchemas(after, catalogue)).toEqual([{ name: 'schemaCommande1', kind: 'periodic', by: 'SUP.action.SECOND' }]);
    const p = s.periodic.get('schemaCommande1')!;
    expect(p.releases).toBe(6); // 2 cycles x 3 modules
    expect(p.lastCycle).toBe(1);
    expect(p.completions).toBe(2);
    expect(p.histogram.reduce((a, b) => a + b, 0)).toBe(2);
    // the largest response_ns of ORD's ord_complete records in the file
    const responses = [...readFileSync(join(dir, 'ORD.csv'), 'utf8').matchAll(/,ord_complete,.*response_ns=(\d+)/g)].map((m) => Number(m[1]));
    expect(responses).toHaveLength(2);
    expect(p.maxResponseNs).toBe(Math.max(...responses));
    expect(p.deadlineMisses).toBe(0);
    expect(s.eventFlows.get('MAA:0->MAB:0')!.count).toBe(4);
    // a supervisor's deliveries count as a module's: SUP took MAA's two connection_status events
    expect(s.eventFlows.get('MAA:2->SUP:2')!.count).toBe(2);
    expect(s.eventFlows.get('MAA:0->SUP:1')!.count).toBe(4);
    // SUP's actions and undos, as its log lists them: the supervisor action records (subscriptions,
    // parameters, schemaCommande1 asked of ORD, schemaReceptionMessage run by SUP itself: every
    // supervisor line but the readable ones), the holds and the priorities it set
    const sup = readFileSync(join(dir, 'SUP.csv'), 'utf8').split('\n');
    const actions = sup.filter((l) => /,SUP,supervisor,[A-Z]*,,0,"?(?!function |rule |refused: |ignored: |kept: |error: |warning: )/.test(l));
    expect(actions.filter((l) => l.includes('(event schema)'))).toHaveLength(2);
    expect(actions.length).toBeGreaterThan(5);
    const undos = actions.filter((l) => /,0,"?undo: /.test(l)).length;
    expect(undos).toBeGreaterThanOrEqual(3); // MAA:2, MAA:0 and MSC:1 unsubscribed, schemaCommande1 deactivated
    const of = (re: RegExp) => sup.filter((l) => re.test(l)).length;
    expect(s.supervisors.get('SUP')!.actionsDone).toBe(actions.length - undos + of(/,module_hold,.*,hold taken/) + of(/,flow_hold,.*,hold taken/) + of(/,module_priority,/));
    expect(s.supervisors.get('SUP')!.actionsUndone).toBe(undos + of(/,(module|flow)_hold,.*,last hold dropped/));
    expect(s.modules.get('MSC')!.runs).toBe(2);
  });

  it('gives the same states when fed the live channel\'s lines (kept as packed text) as when fed the records', () => {
    const lines = readdirSync(dir).flatMap((file) => readFileSync(join(dir, file), 'utf8').split('\n').map((text, i) => ({ file, line: i + 1, text })))
      .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
    const fed = new MonitorModel({ checkpointEvery: 16 });
    for (const l of lines) fed.pushLine(l.file, l.line, l.text);
    expect(fed.marks).toEqual(model.marks);
    for (const m of model.marks) {
      expect(fed.stateAt(m.t)).toEqual(model.stateAt(m.t));
      expect(fed.stateAt(m.t - 1)).toEqual(model.stateAt(m.t - 1));
    }
  });

  it('gives at every time the same state as folding the records up to it', () => {
    const times = tutorial.filter((r) => r.kind !== 'unknown').map((r) => Number((r as { monoNs: string }).monoNs) - model.t0!);
    for (const t of [0, ...times.filter((_, i) => i % 7 === 0), times[times.length - 1]! - 1]) {
      expect(model.stateAt(t)).toEqual(naive(tutorial, t));
    }
  });
});

describe('ORD\'s overruns', () => {
  // ORD's lines for SLW (PERIOD 200 ms): a cycle that skips 3 releases and finishes, one deactivated after
  // 1 skip (no count line), a held cycle restarted after 5 (its count, then the restart's own)
  const ORD_LOG = [
    '0,w,ORD,ord_release,G,,0,schema=SLW cycle=0 tick_ns=0 release_ns=0 release=1',
    '200000000,w,ORD,scheduler,,,0,"overrun: SLW cycle still running, release skipped"',
    '700000000,w,ORD,scheduler,,,0,overrun: SLW cycle ended after 3 skipped releases',
    '700000000,w,ORD,ord_complete,,,0,schema=SLW cycle=0 tick_ns=0 response_ns=700000000',
    '800000000,w,ORD,ord_release,G,,0,schema=SLW cycle=4 tick_ns=800000000 release_ns=800000000 release=2',
    '1000000000,w,ORD,scheduler,,,0,"overrun: SLW cycle still running, release skipped"',
    '1100000000,w,ORD,scheduler,,,0,deactivate SLW (activation #1 from SUP)',
    '1200000000,w,ORD,scheduler,,,0,activate SLW (activation #2 from SUP)',
    '1400000000,w,ORD,scheduler,,,0,"overrun: SLW cycle still running, release skipped"',
    '2400000000,w,ORD,scheduler,,,0,overrun: SLW cycle ended after 5 skipped releases',
    '2400000000,w,ORD,scheduler,,,0,"overrun: SLW cycle still held, restarted"',
    '2400000000,w,ORD,ord_release,G,,0,schema=SLW cycle=6 tick_ns=2400000000 release_ns=2400000000 release=3',
  ].map((l) => parseRecordLine('ORD_1.csv', 2, l));
  it('counts every skipped release, as ORD does, and knows while a cycle still overruns', () => {
    const model = new MonitorModel({ checkpointEvery: 2 });
    model.pushAll(ORD_LOG);
    const at = (ms: number) => model.stateAt(ms * 1e6).periodic.get('SLW')!;
    expect([at(100), at(300), at(700), at(1000), at(1100), at(1400), at(2400)].map((p) => [p.overruns, p.overrunning])).toEqual([
      [0, false], [1, true], [3, false], [4, true], [4, false], [5, true], [3 + 1 + 5 + 1, false],
    ]);
    expect(model.live.periodic.get('SLW')!.recentOverruns.map((x) => x.t)).toEqual([200e6, 1000e6, 1400e6, 2400e6]);
    // on the strip: each first skip, and the count of a cycle that skipped more
    expect(model.marks.filter((k) => k.kind === 'overrun').map((k) => k.label)).toEqual([
      'overrun: SLW cycle still running, release skipped', 'overrun: SLW cycle ended after 3 skipped releases',
      'overrun: SLW cycle still running, release skipped', 'overrun: SLW cycle still running, release skipped',
      'overrun: SLW cycle ended after 5 skipped releases', 'overrun: SLW cycle still held, restarted',
    ]);
    // the same count as `contract trace`'s story
    expect(renderStory(ORD_LOG).at(-1)).toContain(', 10 overruns, ');
    // ORD's missed ticks likewise: one line each, a running cycle's first, then its count at its end
    const late = new MonitorModel();
    late.pushAll(['missed tick of SLW (cycle 3)', 'missed tick of SLW (cycle 9)', 'missed ticks: SLW cycle ended after 6 missed ticks']
      .map((d, i) => parseRecordLine('ORD_1.csv', 2, `${(i + 1) * 1e9},w,ORD,scheduler,,,0,${d}`)));
    expect(late.live.periodic.get('SLW')!.missedTicks).toBe(7);
  });
});

describe('a deadline miss names what its cycle was waiting for', () => {
  // ORD's log of `contract trace`'s own example (build-service trace.test.ts): GRP does not finish
  // cycle 7, the schema is re-activated, its cycle 0 is held for GRP, then resumes with CAM late
  const ORD_LOG = [
    '1000000000,w,ORD,ord_release,CAM,,0,schema=pick cycle=7 tick_ns=1000000000 release_ns=1000000000 release=20',
    '1000000000,w,ORD,ord_release,GRP,,0,schema=pick cycle=7 tick_ns=1000000000 release_ns=1000000000 release=21',
    '1000000000,w,ORD,ord_release,ARM,,0,schema=other cycle=3 tick_ns=1000000000 release_ns=1000000000 release=5',
    '1001000000,w,ORD,ord_finished,CAM,,0,schema=pick cycle=7 release=20 response_ns=1000000',
    '1015000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=7 tick_ns=1000000000',
    '1016000000,w,ORD,scheduler,,,0,deactivate pick',
    '1017000000,w,ORD,scheduler,,,0,activate pick',
    '1017000000,w,ORD,scheduler,,,0,cycle of pick held: GRP still runs a release of an earlier activation',
    '1032000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=0 tick_ns=1017000000',
    '2100000000,w,ORD,scheduler,,,0,cycle of pick resumed',
    '2100000000,w,ORD,ord_release,CAM,,0,schema=pick cycle=0 tick_ns=1017000000 release_ns=2100000000 release=22',
    // PERIOD = CRITICAL_DELAY: the next cycle released before ORD writes the miss of this one
    '2101000000,w,ORD,ord_release,CAM,,0,schema=pick cycle=1 tick_ns=2101000000 release_ns=2101000000 release=23',
    '2101000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=0 tick_ns=1017000000',
    '2102000000,w,ORD,ord_finished,CAM,,0,schema=pick cycle=1 release=23 response_ns=1000000',
    '2102000000,w,ORD,ord_finished,CAM,,0,schema=pick cycle=0 release=22 response_ns=1000000',
    '2111000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=1 tick_ns=2101000000',
    '2111000000,w,ORD,ord_deadline_miss,,,0,schema=other cycle=3 tick_ns=1000000000',
  ];
  const expected = [
    'deadline miss (ORD:0) cycle 7 (not finished: GRP)',
    'deadline miss (ORD:0) cycle 0 (held: nothing released, GRP still runs an earlier release)',
    // its first release went out when the hold ended, 1.083 s after its tick
    'deadline miss (ORD:0) cycle 0 (not finished: CAM; ORD released the cycle 1083.0 ms after its tick)',
    'deadline miss (ORD:0) cycle 1', // nothing left unfinished in it: nothing named
    'deadline miss (ORD:0) cycle 3 (not finished: ARM)',
  ];
  const missLabels = (m: MonitorModel) => m.marks.filter((k) => k.kind === 'miss').map((k) => k.label);

  it('live lines read in place, parsed records and a recorded log give the same labels, as `contract trace` words them', () => {
    const live = new MonitorModel({ checkpointEvery: 16 });
    ORD_LOG.forEach((l, i) => live.pushLine('ORD.csv', i + 2, l));
    expect(missLabels(live)).toEqual(expected);
    const parsed = new MonitorModel({ checkpointEvery: 16 });
    parsed.pushAll(ORD_LOG.map((l, i) => parseRecordLine('ORD.csv', i + 2, l)));
    expect(missLabels(parsed)).toEqual(expected);
    const steps = recordedRunSteps([{ name: 'ORD_1.csv', text: `mono_ns,wall_time,module,event,peer,port,size,detail\n${ORD_LOG.join('\n')}\n` }], 1000);
    let step = steps.next();
    while (!step.done) step = steps.next();
    expect(missLabels(step.value.model)).toEqual(expected);
    // and `contract trace`'s story of the same log says the same (its own follower of the cycles)
    const told = renderStory(parseTrace([{ name: 'ORD_1.csv', text: `mono_ns,wall_time,module,event,peer,port,size,detail\n${ORD_LOG.join('\n')}\n` }]))
      .filter((l) => l.includes(' deadline miss ')).map((l) => l.replace(/^.* deadline miss \(ORD:0\): \w+ cycle /, 'deadline miss (ORD:0) cycle '));
    expect(told).toEqual(expected);
  });

  it('a cycle ORD released past (or nearly at) the CRITICAL_DELAY its miss names blames ORD, not the module, as contract trace says, live, parsed and recorded', () => {
    // the field test's fastLoop (CRITICAL_DELAY 800 µs): ENC released 826 µs after the tick, the miss 7 µs later
    const log = [
      '5000826000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=67 tick_ns=5000000000 release_ns=5000826000 release=1',
      '5000833000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=67 tick_ns=5000000000 critical_delay_ns=800000',
      '5001780000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=68 tick_ns=5001000000 release_ns=5001780000 release=2',
      '5001800000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=68 tick_ns=5001000000 critical_delay_ns=800000',
      '5002050000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=69 tick_ns=5002000000 release_ns=5002050000 release=3',
      '5002800000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=69 tick_ns=5002000000 critical_delay_ns=800000',
    ];
    const want = [
      'deadline miss (ORD:0) cycle 67 (ORD late: it released the cycle 826 µs after its tick, past CRITICAL_DELAY 800 µs, leaving ENC no time)',
      'deadline miss (ORD:0) cycle 68 (ORD late: it released the cycle 780 µs after its tick, 20 µs before CRITICAL_DELAY 800 µs, leaving ENC 20 µs)',
      'deadline miss (ORD:0) cycle 69 (not finished: ENC)',
    ];
    const live = new MonitorModel({ checkpointEvery: 16 });
    log.forEach((l, i) => live.pushLine('ORD.csv', i + 2, l));
    expect(missLabels(live)).toEqual(want);
    const parsed = new MonitorModel({ checkpointEvery: 16 });
    parsed.pushAll(log.map((l, i) => parseRecordLine('ORD.csv', i + 2, l)));
    expect(missLabels(parsed)).toEqual(want);
    const text = `mono_ns,wall_time,module,event,peer,port,size,detail\n${log.join('\n')}\n`;
    const steps = recordedRunSteps([{ name: 'ORD_1.csv', text }], 1000);
    let step = steps.next();
    while (!step.done) step = steps.next();
    expect(missLabels(step.value.model)).toEqual(want);
    const told = renderStory(parseTrace([{ name: 'ORD_1.csv', text }]))
      .filter((l) => l.includes(' deadline miss ')).map((l) => l.replace(/^.* deadline miss \(ORD:0\): \w+ cycle /, 'deadline miss (ORD:0) cycle '));
    expect(told).toEqual(want);
  });

  it('a module whose own ack came by the deadline is not blamed for ORD reading it late (the auditor\'s slow cycle 152), live, parsed and recorded, as contract trace says', () => {
    const T = 7_000_000_000;
    const ord = [
      `${T + 1_724_000},w,ORD,ord_release,HOG,,0,schema=slow cycle=152 tick_ns=${T} release_ns=${T + 1_724_000} release=684`,
      `${T + 1_730_000},w,ORD,ord_release,ARM,,0,schema=slow cycle=152 tick_ns=${T} release_ns=${T + 1_730_000} release=685`,
      `${T + 10_010_000},w,ORD,ord_deadline_miss,,,0,schema=slow cycle=152 tick_ns=${T} critical_delay_ns=10000000`,
      `${T + 13_820_000},w,ORD,ack_received,HOG,,0,ACK_FINISHED id=684`,
      `${T + 13_822_000},w,ORD,ord_finished,HOG,,0,schema=slow cycle=152 release=684 response_ns=13822000`,
    ];
    const hog = [
      `${T + 1_750_000},w,HOG,request_received,ORD,,0,START`,
      `${T + 1_751_000},w,HOG,run_started,ORD,,0,activation=152`,
      `${T + 2_240_000},w,HOG,run_finished,,,0,activation=152 cpu_ns=2100000 ACK_FINISHED`,
      `${T + 2_250_000},w,HOG,ack_sent,ORD,,0,ACK_FINISHED id=684`,
    ];
    const want = ['deadline miss (ORD:0) cycle 152 (not finished: ARM; HOG finished at +2.250 ms (its ack sent), ORD had not read it at the deadline, 7.75 ms later: ORD was late reading it; ' +
      'ORD released the cycle 1.724 ms after its tick, of CRITICAL_DELAY 10 ms)'];
    // the live lines come as the logs grow: HOG's before ORD's miss
    const byTime = [...ord.map((l) => ['ORD.csv', l] as const), ...hog.map((l) => ['HOG.csv', l] as const)].sort((a, b) => Number(a[1].split(',')[0]) - Number(b[1].split(',')[0]));
    const live = new MonitorModel({ checkpointEvery: 16 });
    byTime.forEach(([f, l], i) => live.pushLine(f, i + 2, l));
    expect(missLabels(live)).toEqual(want);
    const parsed = new MonitorModel({ checkpointEvery: 16 });
    parsed.pushAll(byTime.map(([f, l], i) => parseRecordLine(f, i + 2, l)));
    expect(missLabels(parsed)).toEqual(want);
    const head = 'mono_ns,wall_time,module,event,peer,port,size,detail\n';
    const files = [{ name: 'ORD_1.csv', text: `${head}${ord.join('\n')}\n` }, { name: 'HOG_1.csv', text: `${head}${hog.join('\n')}\n` }];
    const steps = recordedRunSteps(files, 1000);
    let step = steps.next();
    while (!step.done) step = steps.next();
    expect(missLabels(step.value.model)).toEqual(want);
    const told = renderStory(parseTrace(files))
      .filter((l) => l.includes(' deadline miss ')).map((l) => l.replace(/^.* deadline miss \(ORD:0\): \w+ cycle /, 'deadline miss (ORD:0) cycle '));
    expect(told).toEqual(want);
  });

  it('counts how late ORD released each cycle (its first release only), live, parsed and recorded alike, and says it as the panel does', () => {
    // cycle 0 on its tick + 30 µs, cycle 1 + 900 µs (its second module released later: not counted again), cycle 2 + 40 µs
    const log = [
      '30000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=0 tick_ns=0 release_ns=30000 release=1',
      '1900000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=1 tick_ns=1000000 release_ns=1900000 release=2',
      '1950000,w,ORD,ord_release,CUR,,0,schema=fastLoop cycle=1 tick_ns=1000000 release_ns=1950000 release=3',
      '2040000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=2 tick_ns=2000000 release_ns=2040000 release=4',
    ];
    const figures = (m: MonitorModel) => {
      const p = m.stateAt(Number.MAX_SAFE_INTEGER).periodic.get('fastLoop')!;
      return { cycles: p.lateCycles, max: p.maxLateNs, text: releaseLatenessText(p) };
    };
    const want = { cycles: 3, max: 900_000, text: ' · release lateness p50 ≤ 42.2 µs, p99 ≤ 900 µs, max 900 µs' };
    const live = new MonitorModel({ checkpointEvery: 16 });
    log.forEach((l, i) => live.pushLine('ORD.csv', i + 2, l));
    expect(figures(live)).toEqual(want);
    const parsed = new MonitorModel({ checkpointEvery: 16 });
    parsed.pushAll(log.map((l, i) => parseRecordLine('ORD.csv', i + 2, l)));
    expect(figures(parsed)).toEqual(want);
    const steps = recordedRunSteps([{ name: 'ORD_1.csv', text: `mono_ns,wall_time,module,event,peer,port,size,detail\n${log.join('\n')}\n` }], 1000);
    let step = steps.next();
    while (!step.done) step = steps.next();
    expect(figures(step.value.model)).toEqual(want);
    // ORD's priority record says whether the run was real-time (shown under Active schemas, as contract trace tells it)
    for (const [detail, said] of [['SCHED_FIFO 90', 'SCHED_FIFO 90'], ['nice 1 (priority 90)', 'nice 1 (priority 90)']] as const) {
      const m = new MonitorModel({ checkpointEvery: 16 });
      m.pushLine('ORD.csv', 2, `1000,w,ORD,priority,,,0,${detail}`);
      m.pushLine('MSC.csv', 2, '2000,w,MSC,priority,,,0,SCHED_FIFO 50');
      expect(m.stateAt(Number.MAX_SAFE_INTEGER).ordPriority).toBe(said);
    }
    // a simulation releases on its ticks: nothing to say
    const onTicks = new MonitorModel({ checkpointEvery: 16 });
    onTicks.pushLine('ORD.csv', 2, '0,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=0 tick_ns=0 release_ns=0 release=1');
    expect(figures(onTicks).text).toBe('');
  });

  it('a cycle held for a module ORD said is no longer running: "never finished", as contract trace says, live and parsed', () => {
    // GRP crashed: ORD's stuck record says it is gone before the held cycle misses its deadline
    const log = [...ORD_LOG];
    log.splice(7, 0, '1016500000,w,ORD,scheduler,,,0,stuck: GRP has not finished release #21 after 10 periods: it is no longer running (it crashed or was killed) (pick)');
    const gone = 'deadline miss (ORD:0) cycle 0 (held: nothing released, GRP never finished an earlier release: it is no longer running)';
    const live = new MonitorModel({ checkpointEvery: 16 });
    log.forEach((l, i) => live.pushLine('ORD.csv', i + 2, l));
    expect(missLabels(live)[1]).toBe(gone);
    const parsed = new MonitorModel({ checkpointEvery: 16 });
    parsed.pushAll(log.map((l, i) => parseRecordLine('ORD.csv', i + 2, l)));
    expect(missLabels(parsed)[1]).toBe(gone);
    const told = renderStory(parseTrace([{ name: 'ORD_1.csv', text: `mono_ns,wall_time,module,event,peer,port,size,detail\n${log.join('\n')}\n` }]))
      .filter((l) => l.includes(' deadline miss ')).map((l) => l.replace(/^.* deadline miss \(ORD:0\): \w+ cycle /, 'deadline miss (ORD:0) cycle '));
    expect(told[1]).toBe(gone);
  });

  it('marks a module\'s own records (ContractLog under a name of its own), live, parsed and recorded alike; a flood of them takes no mark from the rules', () => {
    const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
    const log = [
      `1000000000,${W},MAA,gripper_closed,,,0,force=12.5 N`,
      `1000500000,${W},MAA,homed,,,0,`,
      `1000600000,${W},MAA,gripper_opened,MAB,2,16,width=40 mm`,
      `1000700000,${W},MAA,tare,,0,0,`,
      `1000800000,${W},MAA,${'x'.repeat(64)},SUP,1,8,${'d'.repeat(300)}`,
      ...Array.from({ length: MAX_USER_MARKS + 500 }, (_, i) => `${1001000000 + i * 1000},${W},MAA,tick,,,0,n=${i}`),
      `1100000000,${W},SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns`,
    ];
    const userLabels = (m: MonitorModel) => m.marks.filter((k) => k.kind === 'user').slice(0, 5).map((k) => `${k.where} ${k.label}`);
    const live = new MonitorModel({ checkpointEvery: 64 });
    log.forEach((l, i) => live.pushLine('MAA.csv', i + 2, l));
    const parsed = new MonitorModel({ checkpointEvery: 64 });
    parsed.pushAll(log.map((l, i) => parseRecordLine('MAA.csv', i + 2, l)));
    const steps = recordedRunSteps([{ name: 'MAA_1.csv', text: `${HEADER}\n${log.join('\n')}\n` }], 1000);
    let step = steps.next();
    while (!step.done) step = steps.next();
    for (const m of [live, parsed, step.value.model]) {
      // the story's words (contract trace): the peer, port and size it was logged with when given, after a detail cut short
      expect(userLabels(m)).toEqual(['MAA gripper_closed: force=12.5 N', 'MAA homed', 'MAA gripper_opened: width=40 mm (peer MAB, port 2, 16 bytes)', 'MAA tare (port 0)',
        `MAA ${'x'.repeat(64)}: ${'d'.repeat(80)} (peer SUP, port 1, 8 bytes)`]);
      expect(m.marks.filter((k) => k.kind === 'user')).toHaveLength(MAX_USER_MARKS);
      expect(m.marks.at(-1)).toMatchObject({ kind: 'rule', where: 'SUP' }); // the rule after the flood is marked
      expect(m.live.unknownLines).toBe(0);
      expect(m.recordCount).toBe(log.length);
    }
  });

  it('marks the run\'s errors (a request not sent, a supervisor\'s request kept and failed, its hold), live, parsed and recorded alike; a flood of them takes no mark from the rules', () => {
    const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
    const full = 'mailbox full: the module did not read its requests in time';
    const log = [
      `1000000000,${W},SUP,supervisor,ASY,,0,undo: stop module ASY`,
      `1000000100,${W},SUP,module_hold,ASY,,0,last hold dropped (stop kept: its mailbox is full)`,
      `3000000000,${W},SUP,error,,,0,STOP request to ASY: ${full} (Resource temporarily unavailable; its mailbox stayed full for 2 s; SUP kept the request meanwhile)`,
      `3000000100,${W},SUP,supervisor,ASY,,0,error: not sent: STOP request to ASY (kept 2 s for its full mailbox): ${full}`,
      `3000000200,${W},SUP,module_hold,ASY,,0,stop failed: it had been kept for its full mailbox (it still runs)`,
      ...Array.from({ length: MAX_ERROR_MARKS + 500 }, (_, i) => `${3001000000 + i * 1000},${W},SUP,error,,,0,SETPARAM request to CTL: unknown module (no mailbox in the run directory) (No such file or directory)`),
      `3100000000,${W},SUP,sup_rule,,,0,main.BEAT active cause=elapsed=1000000ns`,
    ];
    const errorLabels = (m: MonitorModel) => m.marks.filter((k) => k.kind === 'error').slice(0, 3).map((k) => `${k.where} ${k.label}`);
    const live = new MonitorModel({ checkpointEvery: 64 });
    log.forEach((l, i) => live.pushLine('SUP.csv', i + 2, l));
    const parsed = new MonitorModel({ checkpointEvery: 64 });
    parsed.pushAll(log.map((l, i) => parseRecordLine('SUP.csv', i + 2, l)));
    const steps = recordedRunSteps([{ name: 'SUP_1.csv', text: `${HEADER}\n${log.join('\n')}\n` }], 1000);
    let step = steps.next();
    while (!step.done) step = steps.next();
    for (const m of [live, parsed, step.value.model]) {
      expect(errorLabels(m)).toEqual([
        `SUP error: STOP request to ASY: ${full} (Resource temporarily unavailable; its mailbox stayed full for 2 s; SUP kept the request meanwhile)`,
        `SUP error: not sent: STOP request to ASY (kept 2 s for its full mailbox): ${full}`,
        'SUP ASY: stop failed: it had been kept for its full mailbox (it still runs)',
      ]);
      expect(m.marks.filter((k) => k.kind === 'error')).toHaveLength(MAX_ERROR_MARKS);
      expect(m.marks.at(-1)).toMatchObject({ kind: 'rule', where: 'SUP' }); // the rule after the flood is marked
      expect(m.live.records).toBe(log.length);
    }
  });

  it('stays bounded on a hostile trace: thousands of schemas and modules, long names', () => {
    const m = new MonitorModel({ checkpointEvery: 64 });
    for (let i = 0; i < 2000; i++) m.pushLine('ORD.csv', i, `${1000 + i},w,ORD,ord_release,M${i},,0,schema=S${i % 500} cycle=1 tick_ns=1 release_ns=1 release=1`);
    for (let i = 0; i < 100; i++) m.pushLine('ORD.csv', i, `${5000 + i},w,ORD,ord_release,${'X'.repeat(60)}${i},,0,schema=S0 cycle=1 tick_ns=1 release_ns=1 release=1`);
    m.pushLine('ORD.csv', 1, '9000,w,ORD,ord_deadline_miss,,,0,schema=S0 cycle=1 tick_ns=1');
    m.pushLine('ORD.csv', 1, '9001,w,ORD,ord_deadline_miss,,,0,schema=S499 cycle=1 tick_ns=1');
    const [s0, s499] = missLabels(m);
    expect(s0).toMatch(/^deadline miss \(ORD:0\) cycle 1 \(not finished: M0, M1000, .*…\)$/);
    expect(s0!.length).toBeLessThan(240);
    expect(s499).toBe('deadline miss (ORD:0) cycle 1'); // past the bound of schemas followed: not named, not wrong
    expect((m as unknown as { waits: Map<string, unknown> }).waits.size).toBe(64);
  });
});

describe('monitor model, values of the extension types', () => {
  it('shows a rule cause whose value is a scan (float[180] in a datatype), an enum member or a bool as the trace wrote it', () => {
    const m = new MonitorModel({ checkpointEvery: 16 });
    const scan = 'OBS:1 value={ranges=[5,5,5,5,5,5,5,5,5,5,...],mode=AUTO,blocked=true}';
    m.pushAll([line(1000, 'MIS', 'sup_rule', '', '', `mission.AHEAD active cause=${scan}`),
      line(2000, 'MIS', 'sup_rule', '', '', 'mission.MODE active cause=DRV:0 value=SAFESTOP'),
      line(3000, 'MIS', 'sup_rule', '', '', 'mission.FLAG active cause=OBS:2 value=true')]);
    const rules = m.live.supervisors.get('MIS')!.rules;
    expect(rules.get('mission.AHEAD')).toMatchObject({ active: true, cause: scan });
    expect(rules.get('mission.MODE')).toMatchObject({ active: true, cause: 'DRV:0 value=SAFESTOP' });
    expect(rules.get('mission.FLAG')).toMatchObject({ active: true, cause: 'OBS:2 value=true' });
  });
});

describe('monitor model, long and hostile runs', () => {
  const schemaRun = (cycles: number, periodNs: number) => {
    const out: TraceRecord[] = [line(1000, 'SUP', 'sup_rule', '', '', 'f.R active cause=elapsed=1000000ns')];
    for (let c = 0; c < cycles; c++) {
      const tick = 10_000 + c * periodNs;
      out.push(line(tick, 'ORD', 'ord_release', 'M', '', `schema=S cycle=${c} tick_ns=${tick} release_ns=${tick} release=${c + 1}`));
      out.push(line(tick + 1, 'M', 'run_started', 'ORD', '', `activation=${c + 1}`));
      out.push(line(tick + 300, 'M', 'run_finished', 'ORD', '', `activation=${c + 1} cpu_ns=41000 ACK_FINISHED`));
      out.push(line(tick + 400, 'ORD', 'ord_complete', '', '', `schema=S cycle=${c} tick_ns=${tick} response_ns=${400 + (c % 50) * 1000}`));
      if (c % 1000 === 999) out.push(line(tick + 500, 'ORD', 'ord_deadline_miss', '', '', `schema=S cycle=${c} tick_ns=${tick}`));
      if (c === cycles / 2) out.push(line(tick + 600, 'SUP', 'sup_rule', '', '', 'f.R inactive cause=ORD:0 value="S"'));
    }
    return out;
  };

  it('keeps memory bounded (raw records dropped, notable kept) and rule states exact far back', () => {
    const recs = schemaRun(60_000, 1_000_000); // a 1 kHz schema for 60 s
    const model = new MonitorModel({ checkpointEvery: 1024, keepRecords: 50_000 });
    model.pushAll(recs);
    expect(model.recordCount).toBe(recs.length);
    expect((model as unknown as { kept: number }).kept).toBeLessThanOrEqual(50_000 + 1024);
    expect(model.live.periodic.get('S')).toMatchObject({ releases: 60_000, completions: 60_000, deadlineMisses: 60 });
    expect(model.marks.filter((m) => m.kind === 'miss').length).toBe(60);
    // far back (raw records gone): rules exact, counters at most one checkpoint behind
    const early = model.stateAt(20e9);
    expect(model.exactAt(20e9)).toBe(false);
    expect(early.supervisors.get('SUP')!.rules.get('f.R')!.active).toBe(true);
    const lateRule = model.stateAt(40e9).supervisors.get('SUP')!.rules.get('f.R')!;
    expect(lateRule).toMatchObject({ active: false, cause: 'ORD:0 value="S"' });
    expect(Math.abs(early.periodic.get('S')!.releases - 20_000)).toBeLessThanOrEqual(1024);
    // recent: exact
    expect(model.exactAt(59.5e9)).toBe(true);
    expect(model.stateAt(59.5e9)).toEqual(naive(recs, 59.5e9));
  });

  it('scrubs back quickly on a long run', () => {
    const model = new MonitorModel();
    model.pushAll(schemaRun(20_000, 1_000_000));
    const t0 = performance.now();
    for (let i = 0; i < 200; i++) model.stateAt(Math.random() * 20e9);
    expect((performance.now() - t0) / 200).toBeLessThan(20); // generous: a functional bound, the figure is in the bench
  });

  it('never throws on hostile lines and holds time monotonic', () => {
    const model = new MonitorModel({ checkpointEvery: 16 });
    const junk = ['', 'x', ',,,,,,,', '99999999999999999999,w,M,sup_rule,,,0,"bad', '5,w,M,ord_complete,,,0,schema= response_ns=abc',
      '5,w,ORD,scheduler,,,0,activate', '1,w,SUP,sup_rule,,,0,f.R active cause=' + 'x'.repeat(5000), '3,w,M,event_received,,,0,from_port=1',
      '2,w,M,data_posted,P,,0,to_port=1', '7,w,SUP,module_hold,,,0,hold taken', '4,w,ORD,request_received,SUP,,0,START ' + 'y'.repeat(300)];
    for (let i = 0; i < 500; i++) model.pushLine('h.csv', i, junk[i % junk.length]!);
    let last = 0;
    for (let t = 0; t < 10; t += 0.5) {
      const s = model.stateAt(t);
      expect(s.t).toBeGreaterThanOrEqual(last);
      last = s.t;
    }
    expect(model.live.unknownLines).toBeGreaterThan(0);
  });

  it('buckets response times on a log scale', () => {
    expect(histogramBucket(0)).toBe(0);
    expect(histogramBucket(999)).toBe(0);
    expect(histogramBucket(1000)).toBe(1);
    expect(bucketStartNs(histogramBucket(1e6))).toBeLessThanOrEqual(1e6);
    expect(bucketStartNs(histogramBucket(1e6) + 1)).toBeGreaterThan(1e6);
    const s = emptyState();
    applyRecord(s, line(1, 'ORD', 'ord_complete', '', '', 'schema=S cycle=0 tick_ns=1 response_ns=1e99'), 0, 0);
    expect(s.periodic.get('S')).toBeUndefined(); // not a number: ignored
  });
});

describe('a supervisor\'s actions counted once', () => {
  const W = '2026-12-04T20:00:00.000000Z';
  const fold = (lines: string[]) => {
    const s = emptyState();
    lines.forEach((l, i) => applyRecord(s, parseRecordLine('SUP.csv', i + 2, l), i, 0));
    return s.supervisors.get('SUP')!;
  };
  it('a log with a line per module start, flow connect and priority claim counts the lines, not the hold and priority records after them', () => {
    const sup = fold([
      `1,${W},SUP,supervisor,,,0,activate schema watch (event schema)`,
      `2,${W},SUP,supervisor,MAA,,0,connect MAA:0 =* MAB:0`,
      `3,${W},SUP,flow_hold,flow-MAA-0-MAB-0,,0,hold taken`,
      `4,${W},SUP,supervisor,MAA,,0,start module MAA (priority 30)`,
      `5,${W},SUP,module_hold,MAA,,0,hold taken (started it)`,
      `6,${W},SUP,module_priority,MAA,,0,nice level for priority 30 (was 30)`,
      `7,${W},SUP,supervisor,MAA,,0,set priority of MAA to 10 (claim #3)`,
      `8,${W},SUP,module_priority,MAA,,0,nice level for priority 10 (was 30)`,
      `9,${W},SUP,supervisor,MAA,,0,undo: release priority claim #3 on MAA`,
      `10,${W},SUP,module_priority,MAA,,0,nice level for priority 30 (was 10)`,
      `11,${W},SUP,supervisor,,,0,undo: deactivate schema watch (event schema)`,
      `12,${W},SUP,supervisor,MAA,,0,undo: disconnect MAA:0 =* MAB:0`,
      `13,${W},SUP,flow_hold,flow-MAA-0-MAB-0,,0,last hold dropped (disconnected)`,
      `14,${W},SUP,supervisor,MAA,,0,undo: stop module MAA`,
      `15,${W},SUP,module_hold,MAA,,0,last hold dropped (stopped)`,
    ]);
    expect([sup.actionsDone, sup.actionsUndone]).toEqual([4, 4]);
    expect([...sup.heldModules.keys(), ...sup.heldFlows.keys()]).toEqual([]);
  });
  it('a module and a flow kept for another supervisor are no longer held by the one that let them go', () => {
    const sup = fold([
      `1,${W},SUP,supervisor,,,0,activate schema watch (event schema)`,
      `2,${W},SUP,supervisor,MAA,,0,connect MAA:0 =* MAB:0`,
      `3,${W},SUP,flow_hold,flow-MAA-0-MAB-0,,0,hold taken`,
      `4,${W},SUP,module_hold,MAA,,0,hold taken (it was running)`,
      `5,${W},SUP,supervisor,,,0,undo: deactivate schema watch (event schema)`,
      `6,${W},SUP,supervisor,MAA,,0,undo: disconnect MAA:0 =* MAB:0`,
      `7,${W},SUP,flow_hold,flow-MAA-0-MAB-0,,0,hold dropped (kept connected: used by 1 other supervisor(s))`,
      `8,${W},SUP,module_hold,MAA,,0,hold dropped (kept running: still used by 1 other supervisor(s))`,
    ]);
    expect([...sup.heldModules.keys(), ...sup.heldFlows.keys()]).toEqual([]);
    expect([sup.actionsDone, sup.actionsUndone]).toEqual([2, 2]);
  });
  it('a module its rule took a hold on that was running already (another supervisor started it) is listed, said shared, not started by it', () => {
    const s = emptyState();
    [`1,${W},SUP,sup_rule,,,0,action.R active cause=elapsed=1000000ns`,
      `2,${W},SUP,supervisor,,,0,activate schema watch (event schema)`,
      `3,${W},SUP,module_hold,MAA,,0,hold taken (it was running)`,
      `4,${W},SUP,supervisor,MAB,,0,start module MAB (priority 30)`,
      `5,${W},SUP,module_hold,MAB,,0,hold taken (started it)`,
    ].forEach((l, i) => applyRecord(s, parseRecordLine('SUP.csv', i + 2, l), i, 0));
    // docs/watching-a-run.md: `→ MAA, MAB`: the schemas it asked ORD for and the modules it took a hold on
    expect(s.supervisors.get('SUP')!.rules.get('action.R')!.started).toEqual(['watch', 'MAA (shared)', 'MAB']);
  });
  it('a log of an older version, without those lines, counts its holds and priorities', () => {
    const sup = fold([
      `1,${W},SUP,supervisor,,,0,activate schema watch (event schema)`,
      `3,${W},SUP,flow_hold,flow-MAA-0-MAB-0,,0,hold taken`,
      `5,${W},SUP,module_hold,MAA,,0,hold taken (started it)`,
      `8,${W},SUP,module_priority,MAA,,0,nice level for priority 10 (was 30)`,
      `11,${W},SUP,supervisor,,,0,undo: deactivate schema watch (event schema)`,
      `13,${W},SUP,flow_hold,flow-MAA-0-MAB-0,,0,last hold dropped (disconnected)`,
    ]);
    expect([sup.actionsDone, sup.actionsUndone]).toEqual([4, 2]);
    expect([...sup.heldModules.keys()]).toEqual(['MAA']);
  });
});

describe('a module that crashed', () => {
  it('its module_crashed record ends it as an exit does: not alive, not running; ORD\'s crash ends the periodic schemas', () => {
    const s = emptyState();
    const lines = [
      '1000,w,MSC,module_started,,,0,pid=7 priority=40',
      '1000,w,ORD,module_started,,,0,pid=8 priority=90',
      '1100,w,ORD,scheduler,,,0,activate loop (activation #1 from SUP)',
      '1200,w,MSC,run_started,ORD,,0,activation=1',
      '1300,w,MSC,module_crashed,,,0,signal 11 (SIGSEGV) records=3',
    ];
    lines.forEach((l, i) => applyRecord(s, parseRecordLine('MSC.csv', i + 2, l), 1000 + i, 1000));
    expect(s.modules.get('MSC')).toMatchObject({ alive: false, running: false });
    applyRecord(s, parseRecordLine('ORD.csv', 9, '1400,w,ORD,module_crashed,,,0,signal 6 (SIGABRT) records=9'), 1400, 1000);
    expect(s.modules.get('ORD')!.alive).toBe(false);
    expect([...s.schemas.values()].some((sc) => sc.active)).toBe(false);
  });
});
