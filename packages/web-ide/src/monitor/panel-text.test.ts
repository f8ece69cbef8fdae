import { describe, it, expect } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { NOT_IN_MODEL_LONG, flowDropText, followButton, notReleasedText, ruleTexts, schedulingText, timeReadout } from './panel-text.js';
import { MonitorModel } from './monitor-model.js';
import { histogramMarkers } from './response-histogram.js';
import { markTooltip } from './marks-strip.js';
import { RemoteMonitorModel, type FollowerPort } from './remote-model.js';
import { emptyState } from './monitor-state.js';
import type { FromFollower, ToFollower } from './live-follow-protocol.js';

describe('the time readout', () => {
  it('following a live run, it runs with the run\'s clock through a quiet stretch and says where the state shown is', () => {
    // the tutorial's quiet stretch: the last record at +4.13 s, the run at +20.1 s
    expect(timeReadout({ t: 4.13e9, end: 4.13e9, following: true, runClock: 20.1e9, exact: true })).toBe('+20.1 s · live (last record +4.130000 s)');
    // never before the last record (a record that came a little ahead of the estimate)
    expect(timeReadout({ t: 4.13e9, end: 4.13e9, following: true, runClock: 4.0e9, exact: true })).toBe('+4.1 s · live (last record +4.130000 s)');
  });

  it('following a live run before its first record (its build, its init): it says it waits for that record, no time', () => {
    expect(timeReadout({ t: 0, end: 0, following: true, runClock: undefined, exact: true })).toBe('waiting for the run\'s first record · live');
  });

  it('paused, scrubbed or replayed: the cursor and the run\'s end, as before', () => {
    expect(timeReadout({ t: 1.5e9, end: 4.13e9, following: false, exact: true })).toBe('+1.500000 s / +4.130000 s');
    expect(timeReadout({ t: 0, end: 0, following: false, exact: true })).toBe('+0.000000 s / +0.000000 s');
    expect(timeReadout({ t: 1e9, end: 60e9, following: false, exact: false })).toBe('+1.000000 s / +60.000000 s · counters approximate this far back');
  });
});

describe("a live run's clock (RemoteMonitorModel.runClock)", () => {
  const snapshot = (end: number, count: number): FromFollower => ({ type: 'snapshot', live: emptyState(), end, count, missed: 0, marks: [], ended: false, problems: [], foldMs: 0 });

  it('goes on with the page\'s clock from the arrival of the records, never backwards, never before the last record', () => {
    let now = 1000; // performance.now(), ms
    const port: FollowerPort = { postMessage: (_m: ToFollower) => undefined, onmessage: null };
    const model = new RemoteMonitorModel(port, null, { now: () => now });
    const deliver = (m: FromFollower) => port.onmessage!({ data: m } as MessageEvent<FromFollower>);
    expect(model.runClock(now)).toBeUndefined(); // no record yet
    deliver(snapshot(0, 0));
    expect(model.runClock(now)).toBeUndefined();
    deliver(snapshot(4.13e9, 500)); // the last record of a burst arrives at page time 1000 ms
    expect(model.runClock(1000)).toBe(4.13e9);
    // 16 s without a record: the clock goes on, the last record stays where it was
    now = 17_000;
    expect(model.runClock(17_000)).toBeCloseTo(20.13e9, -3);
    expect(model.end).toBe(4.13e9);
    // a batch that came late (its records were written long before): the clock does not go back
    now = 18_000;
    deliver(snapshot(4.5e9, 510));
    expect(model.runClock(18_000)).toBeCloseTo(21.13e9, -3);
    // a batch that came sooner after its records than any before: the estimate moves up to it
    now = 18_100;
    deliver(snapshot(21.5e9, 520));
    expect(model.runClock(18_100)).toBeCloseTo(21.5e9, -3);
    expect(model.runClock(18_600)).toBeCloseTo(22.0e9, -3);
  });
});

describe('the follow button and the rules say their state in words, not as pressed toggles', () => {
  it('the follow button names what it does', () => {
    expect(followButton(true, true)).toMatchObject({ text: '❚❚ Pause', label: 'Pause' });
    expect(followButton(true, false)).toMatchObject({ text: '⇥ Follow', label: 'Follow live' });
    expect(followButton(false, true)).toMatchObject({ text: '⇥ End', label: 'Go to the end' });
    expect(followButton(false, false)).toMatchObject({ text: '⇥ End', label: 'Go to the end' });
    for (const [live, follow] of [[true, true], [true, false], [false, true], [false, false]] as const) {
      const b = followButton(live, follow);
      // the name holds the words on the button (a speech user says what they see)
      expect(b.label.toLowerCase()).toContain(b.text.replace(/^\S+ /, '').toLowerCase());
      expect(b).not.toHaveProperty('pressed');
    }
  });

  it("a rule's row says whether it is active, since when and why, and what a click does; a rule the model lost says so", () => {
    const second = { active: true, since: 2.010325e9, cause: 'MAA:2 value="disconnected"', started: ['schemaCommande1'] };
    expect(ruleTexts('action', 'SECOND', second, false)).toEqual({
      shown: '← MAA:2 = "disconnected" → schemaCommande1',
      label: 'SECOND, active since +2.010325 s ← MAA:2 = "disconnected" → schemaCommande1',
      title: 'action.SECOND active since +2.010325 s ← MAA:2 = "disconnected" → schemaCommande1 · click to open it in its .contract file',
    });
    // inactive: what it started is no longer said; the row says `off`
    expect(ruleTexts('action', 'FIRST', { ...second, active: false }, false)).toMatchObject({ shown: 'off ← MAA:2 = "disconnected"', label: 'FIRST, inactive since +2.010325 s ← MAA:2 = "disconnected"' });
    expect(ruleTexts('action', 'THIRD', undefined, false)).toEqual({ shown: '', label: 'THIRD, not active yet', title: 'action.THIRD: not active yet · click to open it in its .contract file' });
    const gone = ruleTexts('action', 'OLD', second, true);
    expect(gone.label).toBe(`OLD, active since +2.010325 s ← MAA:2 = "disconnected" → schemaCommande1, ${NOT_IN_MODEL_LONG}`);
    expect(gone.title).toContain(`· ${NOT_IN_MODEL_LONG}: click to open its function`);
    // its function (or its whole supervisor) gone too: the tooltip promises nothing to open
    const orphan = ruleTexts('mission', 'SINGLE', undefined, true, true);
    expect(orphan.label).toBe(`SINGLE, not active yet, ${NOT_IN_MODEL_LONG}`);
    expect(orphan.title).toBe(`mission.SINGLE: not active yet · ${NOT_IN_MODEL_LONG}, and so is its function: nothing to open`);
  });
});

describe('the histogram\'s CRITICAL_DELAY and PERIOD', () => {
  const W = 320;
  const xOf = (ns: number) => 2 + Math.log10(ns / 1e3) * 50; // 50 px a decade from 1 µs
  const measure = (text: string) => text.length * 5.5;
  const overlap = (a: { labelX: number; label: string; row: number }, b: { labelX: number; label: string; row: number }) =>
    a.row === b.row && a.labelX < b.labelX + measure(b.label) && b.labelX < a.labelX + measure(a.label);

  it('equal (a control loop: PERIOD = CRITICAL_DELAY): one line, one label that says both', () => {
    const markers = histogramMarkers(10e6, 10e6, xOf, W, measure);
    expect(markers).toHaveLength(1);
    expect(markers[0]).toMatchObject({ label: 'PERIOD = CRITICAL_DELAY', color: '#e06c75', row: 0 });
    expect(markers[0]!.labelX + measure(markers[0]!.label)).toBeLessThanOrEqual(W); // whole on the canvas
  });

  it('apart, close or far, either one greater: two lines, labels that meet neither each other nor the other line, whole on the canvas', () => {
    const pairs = [[50e6, 100e6], [1e6, 1.001e9], [1e9, 1e9 * 1.5], [800e3, 1e6], [1e6, 800e3], [1e6, 1.1e6], [1e6, 1e3], [1.5e9, 1e9]];
    for (const [cd, period] of pairs) {
      const markers = histogramMarkers(cd, period, xOf, W, measure);
      const what = `CRITICAL_DELAY ${cd} PERIOD ${period}: ${JSON.stringify(markers)}`;
      expect(markers.map((m) => m.label).sort(), what).toEqual(['CRITICAL_DELAY', 'PERIOD']);
      expect(overlap(markers[0]!, markers[1]!), what).toBe(false);
      for (const m of markers) {
        expect(m.labelX, what).toBeGreaterThanOrEqual(0);
        expect(m.labelX + measure(m.label), what).toBeLessThanOrEqual(W);
        // the label covers no line, its own nor the other
        for (const line of markers) expect(line.x < m.labelX || line.x > m.labelX + measure(m.label), what).toBe(true);
      }
    }
    // close on the log axis (PERIOD 1 ms, CRITICAL_DELAY 800 µs): both on the top row, away from each other
    const [period, cd] = histogramMarkers(800e3, 1e6, xOf, W, measure);
    expect(cd!.labelX + measure(cd!.label)).toBeLessThan(cd!.x);
    expect(period!.labelX).toBeGreaterThan(period!.x);
    expect([cd!.row, period!.row]).toEqual([0, 0]);
  });

  it('two lines squeezed at the edge: the whole labels on two rows, else shortened', () => {
    // both near the right edge: PERIOD's label cannot go right of its line, nor left (over CRITICAL_DELAY's line): it goes beyond it, on the row under
    const squeezed = histogramMarkers(1e9, 1.5e9, xOf, W, measure);
    expect(squeezed.map((m) => [m.label, m.row]), JSON.stringify(squeezed)).toEqual([['PERIOD', 1], ['CRITICAL_DELAY', 0]]);
    // no room for the whole labels anywhere (a canvas 60 px wide): CD and P
    const narrow = histogramMarkers(1e6, 1.3e6, (ns) => 50 + Math.log10(ns / 1e6) * 20, 60, measure);
    expect(narrow.map((m) => m.label)).toEqual(['P', 'CD']);
    expect(narrow[0]!.row !== narrow[1]!.row || !overlap(narrow[0]!, narrow[1]!)).toBe(true);
  });

  it('one of them unknown: only the other', () => {
    expect(histogramMarkers(undefined, 1e9, xOf, W, measure).map((m) => m.label)).toEqual(['PERIOD']);
    expect(histogramMarkers(1e9, undefined, xOf, W, measure).map((m) => m.label)).toEqual(['CRITICAL_DELAY']);
    expect(histogramMarkers(undefined, undefined, xOf, W, measure)).toEqual([]);
  });
});

describe('the timeline strip\'s tooltip', () => {
  it('names the marks under the pointer, a miss with what its cycle waited for', () => {
    const miss = { t: 2.21e9, kind: 'miss' as const, where: 'velocityLoop', label: 'deadline miss (ORD:0) cycle 220 (not finished: VEL)' };
    expect(markTooltip([miss])).toBe('+2.210000 s velocityLoop: deadline miss (ORD:0) cycle 220 (not finished: VEL)');
    const many = Array.from({ length: 9 }, (_, i) => ({ ...miss, t: miss.t + i }));
    const text = markTooltip(many).split('\n');
    expect(text).toHaveLength(7);
    expect(text[6]).toBe('… and 3 more mark(s) here');
  });
});

describe("a data flow's dropped values", () => {
  const at = (ns: number, kind: string, peer: string, detail: string) =>
    parseRecordLine('CAM.csv', 2, `${ns},w,CAM,${kind},${peer},0,24,${detail}`);

  it('are counted per flow with their reason, shown after its deliveries; a flow that delivers all shows none', () => {
    const m = new MonitorModel();
    m.push(at(1_000_000, 'data_posted', 'SRT', 'to_port=0'));
    m.push(at(2_000_000, 'data_posted', 'LOG', 'to_port=1'));
    for (let i = 0; i < 5; i++) m.push(at(3_000_000 + i, 'data_dropped', 'SRT', 'to_port=0 queue full'));
    m.push(at(4_000_000, 'data_dropped', 'NAV', 'to_port=2 Connection refused')); // a flow that never delivered
    const flows = m.live.dataFlows;
    expect(flows.get('CAM:0->SRT:0')).toEqual({ count: 1, last: 0, dropped: 5, dropReason: 'queue full' });
    expect(flowDropText('CAM:0->SRT:0', flows.get('CAM:0->SRT:0')!)).toBe(' · 5 dropped (queue full: SRT does not read it fast enough)');
    expect(flowDropText('CAM:0->NAV:2', flows.get('CAM:0->NAV:2')!)).toBe(' · 1 dropped (Connection refused)');
    expect(flows.get('CAM:0->NAV:2')).toMatchObject({ count: 0, last: 3_000_000 });
    expect(flowDropText('CAM:0->LOG:1', flows.get('CAM:0->LOG:1')!)).toBe('');
  });
});

describe('the scheduling line', () => {
  it('names how ORD was scheduled, and under nice levels says that misses are likely and what runs it real-time', () => {
    expect(schedulingText('SCHED_FIFO 90')).toBe('Scheduling: ORD priority SCHED_FIFO 90 (real-time)');
    const nice = schedulingText('nice 1 (priority 90)');
    expect(nice).toMatch(/^Scheduling: ORD priority nice 1 \(priority 90\): not real-time, a nice level \(deadline misses are likely on a busy machine; /);
    expect(nice).toContain("the run settings' Real-time");
  });
});

describe('a periodic schema never released', () => {
  it('is "not released yet" while the run goes on, "never released" after it, and a run with no records did not start', () => {
    expect(notReleasedText(true, true)).toBe('not released yet');
    expect(notReleasedText(false, false)).toBe('never released in this run');
    expect(notReleasedText(false, true)).toMatch(/^no release: the run has no records \(it did not start/);
  });
});
