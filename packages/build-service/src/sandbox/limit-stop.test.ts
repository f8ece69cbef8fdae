/**
 * A limit hit during a run (limit-stop.ts): the job is told it is stopping the architecture before
 * the launcher is asked, so that the lines the launcher prints as it stops follow that line in the
 * job's log (they came before it: it was told once the asking had returned); a run with no
 * launcher to ask is told so, and killed at once.
 */
import { describe, expect, test } from 'vitest';
import type { LimitHit } from '../limits.js';
import { stopThenKill } from './limit-stop.js';

const HIT: LimitHit = { name: 'memory', value: 512 * 1024 * 1024, unit: 'bytes', mechanism: 'cgroup-v1' } as LimitHit;

function run(order: string[], launcher: boolean) {
  let exit!: () => void;
  const exited = new Promise<void>((r) => (exit = r));
  return {
    exited,
    terminateNamed: async () => {
      if (!launcher) return false;
      // the launcher gets the signal and prints before the asking returns
      order.push('launcher: stopping');
      await new Promise((r) => setTimeout(r, 20));
      setTimeout(exit, 10);
      return true;
    },
    kill: async () => void order.push('killed'),
  };
}

describe('the stop of a run by a limit', () => {
  test('says it is stopping before the launcher is asked (and prints), then kills what is left', async () => {
    const order: string[] = [];
    await stopThenKill({ processName: 'contract-launch', graceMs: 1000, stopping: () => order.push('stopping'), unanswered: () => order.push('unanswered') }, HIT, run(order, true));
    expect(order).toEqual(['stopping', 'launcher: stopping', 'killed']);
  });

  test('a run with no launcher to ask: stopping, then unanswered, then killed at once', async () => {
    const order: string[] = [];
    const t0 = Date.now();
    await stopThenKill({ processName: 'contract-launch', graceMs: 1000, stopping: () => order.push('stopping'), unanswered: () => order.push('unanswered') }, HIT, run(order, false));
    expect(order).toEqual(['stopping', 'unanswered', 'killed']);
    expect(Date.now() - t0).toBeLessThan(500);
  });

  test('a teller that throws stops nothing', async () => {
    const order: string[] = [];
    await stopThenKill({ processName: 'contract-launch', graceMs: 1000, stopping: () => { throw new Error('log failed'); } }, HIT, run(order, true));
    expect(order).toEqual(['launcher: stopping', 'killed']);
  });
});
