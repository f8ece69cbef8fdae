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
    for (let k = 0; k < 300_000; k++) lines.push(`${k * 1000},w,CTL,run_started,ORD,,0,activation=${k + 1}`, `${k * 1000 + 300},w,CTL,run_finished,ORD,,0,activation=${k + 1} ACK_FINISHED`);
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
