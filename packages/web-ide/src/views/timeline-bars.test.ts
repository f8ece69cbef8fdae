import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import type { Activation } from './activation-log.js';
import { firstStartingAt, laneBars, lanesOf, lastTime } from './timeline-bars.js';
import { activationsFromLogs } from './run-logs.js';

/** `n` activations of CTL, one every `periodNs` from 0, each running `runNs`. */
function periodic(n: number, periodNs: number, runNs: number): Activation[] {
  return Array.from({ length: n }, (_, k) => ({ module: 'CTL', start: k * periodNs, end: k * periodNs + runNs, detail: `activation=${k + 1}` }));
}

describe('timeline bars', () => {
  it('draws each activation as its own bar when they are pixels apart, only those in the range', () => {
    const acts = periodic(100, 1_000_000, 200_000);
    const x = (t: number) => t / 100_000; // 10 px a period
    const invX = (px: number) => px * 100_000;
    const bars = laneBars(acts, x, invX, 100_000_000, 95, 305);
    // activations 9 (90–92 px, reaching nothing) .. 30 (300 px): the one at 90 ends at 92 < 95
    expect(bars.map((b) => b.first.start / 1_000_000)).toEqual(Array.from({ length: 21 }, (_, k) => k + 10));
    expect(bars.every((b) => b.count === 1)).toBe(true);
    expect(bars[0]).toMatchObject({ x1: 100, x2: 102 });
  });

  it('joins activations within a pixel into one bar that counts them, whatever the run length', () => {
    const acts = periodic(240_000, 1_000_000, 300_000); // 240 s of a 1 kHz module
    const span = 240_000_000_000;
    const x = (t: number) => (t / span) * 1000; // the whole run on 1000 px
    const invX = (px: number) => (px / 1000) * span;
    const bars = laneBars(acts, x, invX, span, -1000, 2000);
    expect(bars.length).toBe(1); // 1,000 activations a pixel, each drawn 2 px wide: one bar
    expect(bars[0]!.count).toBe(240_000);
    expect(bars[0]!.last).toBe(acts.at(-1));
    expect(lastTime(acts)).toBe(239_999_300_000);
  });

  it('starts with the activation before the range when it reaches into it, and marks one still running', () => {
    const acts: Activation[] = [
      { module: 'SLOW', start: 0, end: 50, detail: '' },
      { module: 'SLOW', start: 60, detail: '' },
    ];
    const bars = laneBars(acts, (t) => t, (px) => px, 100, 40, 70);
    expect(bars.map((b) => [b.x1, b.x2, b.count, b.open])).toEqual([[0, 50, 1, false], [60, 100, 1, true]]);
    expect(laneBars(acts, (t) => t, (px) => px, 100, 51, 55)).toEqual([]);
  });

  it('finds the first activation starting at a time', () => {
    const acts = periodic(10, 10, 1);
    expect(firstStartingAt(acts, -5)).toBe(0);
    expect(firstStartingAt(acts, 10)).toBe(1);
    expect(firstStartingAt(acts, 11)).toBe(2);
    expect(firstStartingAt(acts, 1000)).toBe(10);
  });

  it('reads the activations of logs longer than a call can spread (300,000 in one file)', () => {
    const lines = ['mono_ns,wall_time,module,event,peer,port,size,detail'];
    for (let k = 0; k < 300_000; k++) lines.push(`${k * 1000},w,CTL,run_started,ORD,,0,activation=${k + 1}`, `${k * 1000 + 300},w,CTL,run_finished,ORD,,0,activation=${k + 1} cpu_ns=41000 ACK_FINISHED`);
    const { acts, errors } = activationsFromLogs([{ name: 'CTL.csv', text: lines.join('\n') }]);
    expect(errors).toEqual([]);
    expect(acts).toHaveLength(300_000);
    expect(lastTime(acts)).toBe(299_999_300);
  });
});

describe('timeline lanes', () => {
  it('one per module, sorted, each with its activations in order; past the bound counted, not drawn (a log naming a new module a line)', () => {
    const acts: Activation[] = [
      { module: 'MSC', start: 1, detail: '' }, { module: 'MSA', start: 2, detail: '' }, { module: 'MSC', start: 3, detail: '' },
      ...Array.from({ length: 100_000 }, (_, i): Activation => ({ module: `Z${i}`, start: 10 + i, detail: '' })),
    ];
    const { modules, lanes, leftOutModules, leftOutActs } = lanesOf(acts, 256);
    expect(modules).toHaveLength(256);
    expect(modules.slice(0, 2)).toEqual(['MSA', 'MSC']);
    expect(lanes[1]!.map((a) => a.start)).toEqual([1, 3]);
    expect(leftOutModules).toBe(100_002 - 256);
    expect(leftOutActs).toBe(100_000 - 254);
    expect(lanesOf(acts.slice(0, 3), 256)).toMatchObject({ modules: ['MSA', 'MSC'], leftOutModules: 0, leftOutActs: 0 });
  });
});

describe("an asynchronous module's lane: the events it handles (real records of tutorial runs)", () => {
  const logs = (run: string) => {
    const dir = fileURLToPath(new URL(`../monitor/fixtures/${run}`, import.meta.url));
    return readdirSync(dir).filter((f) => f.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(dir, name), 'utf8') }));
  };
  /** The lane of `module`, the run drawn on 1000 px (as the view does at zoom 0), its bars in ns. */
  const laneOf = (files: ReturnType<typeof logs>, module: string) => {
    const { acts, errors } = activationsFromLogs(files);
    expect(errors).toEqual([]);
    const t0 = acts[0]!.start;
    const span = lastTime(acts) - t0;
    const x = (t: number) => ((t - t0) / span) * 1000;
    const invX = (px: number) => t0 + (px / 1000) * span;
    const { modules, lanes } = lanesOf(acts, 256);
    const lane = lanes[modules.indexOf(module)]!;
    return { acts, lane, bars: laneBars(lane, x, invX, t0 + span, -1000, 2000), x };
  };
  const csvTimes = (text: string, event: string) => text.split('\n').filter((l) => l.split(',')[3] === event).map((l) => Number(l.split(',')[0]));

  it("draws each event MAB handled as a bar from its event_received to its event_handled (a 2.4 ms handler: a plan)", () => {
    const files = logs('async-handler-run');
    const mab = files.find((f) => f.name.startsWith('MAB'))!.text;
    const received = csvTimes(mab, 'event_received');
    const handled = csvTimes(mab, 'event_handled');
    expect(received.length).toBeGreaterThanOrEqual(3);
    expect(handled).toHaveLength(received.length);
    const { lane, bars, x } = laneOf(files, 'MAB');
    const events = lane.filter((a) => a.event);
    // a bar per event handled, from its reception to its end, as the log says them
    expect(events.map((a) => [a.start, a.end])).toEqual(received.map((t, i) => [t, handled[i]]));
    for (const a of events) {
      expect(a.event).toMatchObject({ from: 'MAA:0', ended: true });
      expect(a.end! - a.start).toBeGreaterThanOrEqual(2_400_000); // the handler's 2.4 ms, not a sliver
    }
    // drawn at the event times, apart (they are 250 ms apart): not one sliver at the start
    const eventBars = bars.filter((b) => b.first.event);
    expect(eventBars.map((b) => b.x1)).toEqual(received.map((t) => x(t)));
    expect(eventBars.every((b) => b.count === 1)).toBe(true);
    // MAB's START run is the sliver at its start, and the only activation the period guess could count
    expect(lane.filter((a) => !a.event)).toHaveLength(1);
  });

  it("in logs of a runtime that wrote no event_handled, ends a bar at the handler's last record, the reception when it wrote none", () => {
    const files = logs('tutorial-run');
    const mab = files.find((f) => f.name.startsWith('MAB'))!.text;
    const received = csvTimes(mab, 'event_received');
    expect(received).toHaveLength(4);
    const { lane, bars, x } = laneOf(files, 'MAB');
    expect(lane.filter((a) => a.event).map((a) => [a.start, a.end, a.event!.ended])).toEqual(received.map((t) => [t, t, false]));
    expect(bars.filter((b) => b.first.event).map((b) => b.x1)).toEqual(received.map((t) => x(t)));
    // a handler that posts: its bar lasts to its last post, and the next request read ends it
    const header = 'mono_ns,wall_time,module,event,peer,port,size,detail';
    const pln = [header, '1000,w,PLN,run_started,SUP,,0,activation=1', '1100,w,PLN,run_finished,,,0,activation=1 cpu_ns=41000',
      '5000,w,PLN,request_received,SUP,2,8,EVENT from_port=2', '5010,w,PLN,event_received,SUP,2,8,from_port=2 latency_ns=900',
      '7410,w,PLN,event_posted,CTL,0,64,to_port=0', '9000,w,PLN,priority_changed,SUP,,0,"nice 13 (priority 30, was 30)"',
      '9100,w,PLN,request_received,SUP,2,8,EVENT from_port=2'].join('\n');
    const acts = activationsFromLogs([{ name: 'PLN.csv', text: pln }]).acts.filter((a) => a.event);
    expect(acts.map((a) => [a.start, a.end, a.event!.records, a.event!.last])).toEqual([[5010, 7410, 1, 'event_posted']]);
  });
});
