import { describe, it, expect } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MAX_KEPT_MARKS, MonitorModel } from './monitor-model.js';
import { FOLDED_KINDS } from './apply-record.js';
import { scanLine, scanned } from './line-scan.js';
import { MAX_NAMES } from './monitor-state.js';
import { keptRequestsLine } from './panel-text.js';
import { recordedRunSteps } from './recorded-run.js';

// a supervisor's requests kept for a receiver's full mailbox (docs/runtime-api.md, queued sends)
const W = '2026-11-24T18:30:15.123456Z';
const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const BEGIN = `5100000000,${W},SUP,requests_kept,VEL,,0,request=STOP`;
const END = `7100000000,${W},SUP,requests_kept_end,VEL,,0,sent=4 failed=1 replaced=73 kept_ns=2000000000`;
/** Records between them, so that checkpoints and dropped chunks fall inside the streak. */
const filler = (from: number, n: number) => Array.from({ length: n }, (_, i) => `${from + i * 1000},${W},CAM,data_posted,VEL,0,8,to_port=0`);
const run = [
  `1590000000,${W},SUP,module_started,,,0,pid=7 priority=50`,
  ...filler(1600000000, 300),
  BEGIN,
  ...filler(5200000000, 300),
  `6000000000,${W},SUP,requests_kept,ARM,,0,request=SETPARAM`,
  ...filler(6100000000, 300),
  END,
  ...filler(7200000000, 300),
];
const t = (ns: number) => ns - 1590000000;

/** The three ways the Monitor reads a run: live lines read in place, parsed records, a recorded run's logs. */
function models(log: string[], opts = { checkpointEvery: 16 }): MonitorModel[] {
  const live = new MonitorModel(opts);
  log.forEach((l, i) => live.pushLine('SUP.csv', i + 2, l));
  const parsed = new MonitorModel(opts);
  parsed.pushAll(log.map((l, i) => parseRecordLine('SUP.csv', i + 2, l)));
  const steps = recordedRunSteps([{ name: 'SUP_1.csv', text: `${HEADER}\n${log.join('\n')}\n` }], 1000, opts);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return [live, parsed, step.value.model];
}

describe("a supervisor's requests kept for a receiver's full mailbox", () => {
  it('are parsed on the live fast path (a kind the fold uses), not only counted', () => {
    for (const line of [BEGIN, END]) {
      expect(scanLine(line, 0, line.length)).toBe(true);
      expect(FOLDED_KINDS.has(scanned.kind), scanned.kind).toBe(true);
    }
  });

  it('lists the receiver under its supervisor from requests_kept to requests_kept_end, live, parsed and recorded alike', () => {
    for (const m of models(run)) {
      const kept = (at: number) => [...(m.stateAt(at)?.supervisors.get('SUP')?.keptFor ?? [])];
      expect(kept(t(5100000000) - 1)).toEqual([]);
      expect(kept(t(5500000000))).toEqual([['VEL', { since: t(5100000000), request: 'STOP' }]]);
      expect(kept(t(6500000000))).toEqual([['VEL', { since: t(5100000000), request: 'STOP' }], ['ARM', { since: t(6000000000), request: 'SETPARAM' }]]);
      expect(kept(t(7100000000))).toEqual([['ARM', { since: t(6000000000), request: 'SETPARAM' }]]);
      expect([...m.live.supervisors.get('SUP')!.keptFor.keys()]).toEqual(['ARM']);
      // scrubbing back from the end (a checkpoint's copy, then the records after it) shows it again
      expect(kept(t(5500000000))).toEqual([['VEL', { since: t(5100000000), request: 'STOP' }]]);
    }
  });

  it('is shown again far back once the raw records there were dropped (its records are notable)', () => {
    const m = new MonitorModel({ checkpointEvery: 16, keepRecords: 64 });
    m.pushAll(run.map((l, i) => parseRecordLine('SUP.csv', i + 2, l)));
    expect(m.exactAt(t(5500000000))).toBe(false);
    expect(m.stateAt(t(5500000000))!.supervisors.get('SUP')!.keptFor.get('VEL')).toEqual({ since: t(5100000000), request: 'STOP' });
    expect(m.stateAt(t(7150000000))!.supervisors.get('SUP')!.keptFor.has('VEL')).toBe(false);
  });

  it('changes the supervisors (their list is drawn again), and ends with the supervisor', () => {
    const m = new MonitorModel();
    m.pushLine('SUP.csv', 2, BEGIN);
    const changes = m.live.supervisorChanges;
    m.pushLine('SUP.csv', 3, `5200000000,${W},SUP,requests_kept,ARM,,0,request=EVENT`);
    expect(m.live.supervisorChanges).toBeGreaterThan(changes);
    // an end for a receiver it keeps nothing for, or without a receiver: nothing changes
    const before = m.live.supervisorChanges;
    m.pushLine('SUP.csv', 4, `5300000000,${W},SUP,requests_kept_end,GRP,,0,sent=1 failed=0 replaced=0 kept_ns=5`);
    m.pushLine('SUP.csv', 5, `5300000001,${W},SUP,requests_kept,,,0,request=STOP`);
    expect(m.live.supervisorChanges).toBe(before);
    // a supervisor that crashed keeps nothing any more, whatever its log said last
    m.pushLine('SUP.csv', 6, `5400000000,${W},SUP,module_crashed,,,0,signal 11 (SIGSEGV) records=5`);
    expect(m.live.supervisors.get('SUP')!.keptFor.size).toBe(0);
    expect(m.live.supervisorChanges).toBeGreaterThan(before);
  });

  it('takes a name of the bound only while it is kept: a module slow now and then, streak after streak, never fills it', () => {
    const m = new MonitorModel();
    for (let i = 0; i < 3 * MAX_NAMES; i++) {
      m.pushLine('SUP.csv', 2 * i + 2, `${1000000 + 2 * i},${W},SUP,requests_kept,VEL,,0,request=SETPARAM`);
      m.pushLine('SUP.csv', 2 * i + 3, `${1000001 + 2 * i},${W},SUP,requests_kept_end,VEL,,0,sent=1 failed=0 replaced=0 kept_ns=1`);
    }
    expect(m.live.names).toBe(1); // SUP
    expect(m.live.namesPastBound).toBe(0);
    // a forged request name is cut (the panel shows it)
    m.pushLine('SUP.csv', 1, `9000000,${W},SUP,requests_kept,VEL,,0,request=${'X'.repeat(300)}`);
    expect(m.live.supervisors.get('SUP')!.keptFor.get('VEL')!.request).toHaveLength(40);
  });

  it("marks its beginning and its end in the story's words, live, parsed and recorded alike; a flood of them takes no mark from the rules", () => {
    const log = [
      BEGIN,
      END,
      ...Array.from({ length: MAX_KEPT_MARKS + 500 }, (_, i) => `${8000000000 + i * 1000},${W},SUP,requests_kept${i % 2 ? '_end' : ''},ARM,,0,${i % 2 ? 'sent=1 failed=0 replaced=0 kept_ns=1000' : 'request=SETPARAM'}`),
      `9100000000,${W},SUP,sup_rule,,,0,main.BEAT active cause=elapsed=1000000ns`,
    ];
    for (const m of models(log, { checkpointEvery: 64 })) {
      expect(m.marks.filter((k) => k.kind === 'kept').slice(0, 3).map((k) => `${k.where} ${k.label}`)).toEqual([
        "SUP VEL's mailbox is full: its STOP request is kept (tried again every 5 ms, for up to 2 s)",
        "SUP the requests kept for VEL's full mailbox ended after 2 s: 4 sent, 1 failed, 73 values replaced by later ones",
        "SUP ARM's mailbox is full: its SETPARAM request is kept (tried again every 5 ms, for up to 2 s)",
      ]);
      expect(m.marks.filter((k) => k.kind === 'kept')).toHaveLength(MAX_KEPT_MARKS);
      expect(m.marks.at(-1)).toMatchObject({ kind: 'rule', where: 'SUP' }); // the rule after the flood is marked
      expect(m.live.records).toBe(log.length);
    }
  });

  it("says in the supervisor's section for which receiver it keeps requests, since when, and the first one", () => {
    expect(keptRequestsLine('VEL', { since: 3.51e9, request: 'STOP' })).toBe('keeping requests for VEL: its mailbox is full since +3.510000 s (first: STOP)');
    expect(keptRequestsLine('VEL', { since: 0, request: '' })).toBe('keeping requests for VEL: its mailbox is full since +0.000000 s');
  });
});
