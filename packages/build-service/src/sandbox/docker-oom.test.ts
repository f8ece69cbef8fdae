import { describe, expect, test } from 'vitest';
import { engineSaysOomKilled, KILLED_LINE, looksKilled } from './docker-oom.js';

/** An engine whose OOM flag is set from the `setOn`-th inspection on (the race of its two events). */
function engine(setOn: number): { inspect: () => Promise<{ State: { OOMKilled: boolean } }>; asked: () => number } {
  let n = 0;
  return {
    inspect: async () => ({ State: { OOMKilled: ++n >= setOn } }),
    asked: () => n,
  };
}

describe('reading a memory kill from the Docker engine', () => {
  test('an exit that looks like a kill waits for a flag that comes late', async () => {
    const late = engine(4);
    expect(await engineSaysOomKilled(late.inspect, true, 2000, 5)).toBe(true);
    expect(late.asked()).toBe(4);
  });

  test('any other exit asks once: a flag that comes late is not waited for', async () => {
    const late = engine(4);
    expect(await engineSaysOomKilled(late.inspect, false, 2000, 5)).toBe(false);
    expect(late.asked()).toBe(1);
  });

  test('a kill that was not for memory waits no longer than the bound', async () => {
    let asked = 0;
    const t0 = Date.now();
    expect(await engineSaysOomKilled(async () => (asked++, { State: { OOMKilled: false } }), true, 200, 20)).toBe(false);
    expect(Date.now() - t0).toBeGreaterThanOrEqual(200);
    expect(Date.now() - t0).toBeLessThan(1000);
    expect(asked).toBeGreaterThan(3);
  });

  test('a container already gone ends the wait at once', async () => {
    const t0 = Date.now();
    expect(await engineSaysOomKilled(() => Promise.reject(new Error('no such container')), true, 2000, 5)).toBe(false);
    expect(Date.now() - t0).toBeLessThan(100);
  });

  test('what looks like a kill: 137, or a failure after make or a shell said Killed', () => {
    expect(looksKilled(137, false)).toBe(true);
    expect(looksKilled(2, true)).toBe(true);
    expect(looksKilled(2, false)).toBe(false);
    expect(looksKilled(0, true)).toBe(false);
    expect(looksKilled(null, true)).toBe(false);
    expect(KILLED_LINE.test('make: *** [Makefile:6: run] Killed')).toBe(true);
    expect(KILLED_LINE.test('sh: line 1:    42 Killed                  ./app')).toBe(true);
    expect(KILLED_LINE.test('make: *** [Makefile:6: run] Error 3')).toBe(false);
  });
});
