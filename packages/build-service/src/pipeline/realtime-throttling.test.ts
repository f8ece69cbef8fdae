import { describe, expect, it } from 'vitest';
import { budgetThrottling, throttlingWarning } from './realtime-throttling.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const MS = 1_000_000;

/** ORD's log: a release record every millisecond from `from` for `ms` ms, but in the silences [start, end). */
function ordLog(from: number, ms: number, silent: (t: number) => boolean): string {
  const lines = [HEADER];
  for (let i = 0; i < ms; i++) {
    const t = from + i * MS + 40_000; // ORD writes 40 µs after each tick
    if (!silent(t)) lines.push(`${t},w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=${i} tick_ns=${from + i * MS} release_ns=${t} release=${i + 1}`);
  }
  return `${lines.join('\n')}\n`;
}

describe('a real-time run throttled by its budget', () => {
  it('counts the silences of ORD that end at one point of the budget\'s period (the field test: 15-26 ms of each 100 ms)', () => {
    // 2 s pinned at --realtime --cpus 1: the budget used up at 75-85 ms of each 100 ms period, nothing runs until it ends
    const from = 59_529_770_322_845;
    const log = ordLog(from, 2000, (t) => {
      const phase = t % (100 * MS);
      const usedUp = (75 + (Math.floor(t / (100 * MS)) % 3) * 5) * MS; // 75, 80 or 85 ms into the period
      return phase >= usedUp;
    });
    const t = budgetThrottling(log, 100 * MS)!;
    expect(t.times).toBeGreaterThanOrEqual(19);
    expect(t.times).toBeLessThanOrEqual(21);
    expect(t.totalNs / t.times).toBeGreaterThan(14 * MS);
    expect(t.totalNs / t.times).toBeLessThan(27 * MS);
    expect(throttlingWarning(t, 40_000, 100_000)).toMatch(
      /^warning: the architecture was throttled by its real-time CPU budget about \d+ times \(0\.\d\d s in all\): the sandbox gives the whole architecture 40 ms of each 100 ms on each CPU, .*contract run --cpus 0,1.*REALTIME_BOUNDS\.cpuRuntimeUs/);
  });

  it('does not take a loaded machine\'s stalls, which end anywhere in the period, for it', () => {
    // 3-9 ms stalls every 37-ish ms: at nice levels on a busy machine
    let seed = 7;
    const rand = () => ((seed = (seed * 1103515245 + 12345) % 2 ** 31) / 2 ** 31);
    const stalls: Array<[number, number]> = [];
    for (let t = 0; t < 5000 * MS; t += (20 + rand() * 40) * MS) stalls.push([t, t + (3 + rand() * 6) * MS]);
    const from = 1_000_000_000;
    const log = ordLog(from, 5000, (t) => stalls.some(([a, b]) => t - from >= a && t - from < b));
    expect(budgetThrottling(log, 100 * MS)).toBeUndefined();
  });

  it('a run that was never silent 3 ms or more, or a log with no record, was not throttled', () => {
    expect(budgetThrottling(ordLog(1_000_000_000, 1000, () => false), 100 * MS)).toBeUndefined();
    expect(budgetThrottling(`${HEADER}\n`, 100 * MS)).toBeUndefined();
    expect(budgetThrottling('', 100 * MS)).toBeUndefined();
  });
});
