import { describe, expect, it } from 'vitest';
import { recentEntry, recentRunsOf, startTime } from './recent-runs.js';

const ID = `j-${'a'.repeat(32)}`;
const at = (h: number, m: number, s: number, day = 7) => new Date(2026, 11, day, h, m, s).getTime();
const run = (over: Record<string, unknown> = {}) => ({ id: ID, project: '', status: 'succeeded', createdAt: at(18, 31, 5), finishedAt: at(18, 31, 20), ok: true, message: 'run finished', ...over });

describe("the Monitor's entries of the workspace's recent Build & Run jobs", () => {
  it('labels an ended job as the job entries are, with its start time and how it ended', () => {
    const now = at(19, 0, 0);
    expect(recentEntry(run(), now)).toEqual({ id: `job:${ID}`, jobId: ID, label: `Build & Run job ${ID} · started 18:31:05 · ended: succeeded`, outcome: 'succeeded', project: '' });
    expect(recentEntry(run({ status: 'failed', ok: false, message: 'run: MAA exited with status 3' }), now).label).toBe(`Build & Run job ${ID} · started 18:31:05 · ended: failed: run: MAA exited with status 3`);
    expect(recentEntry(run({ status: 'cancelled', ok: false, message: 'cancelled' }), now).outcome).toBe('cancelled');
    expect(recentEntry(run({ project: 'robot' }), now).label).toBe(`Build & Run job ${ID} · robot · started 18:31:05 · ended: succeeded`);
  });

  it('says a job going on is followed live when picked, and dates a job of another day', () => {
    const going = recentEntry(run({ status: 'running', finishedAt: null, ok: null, message: null }), at(19, 0, 0));
    expect(going.outcome).toBeUndefined();
    expect(going.label).toBe(`Build & Run job ${ID} · started 18:31:05 · running: pick it to follow it live`);
    expect(startTime(at(8, 5, 9, 6), at(19, 0, 0))).toBe('2026-12-06 08:05:09');
  });

  it("keeps only well-formed jobs of the server's answer", () => {
    expect(recentRunsOf({ jobs: [run(), run({ id: '../x' }), { id: ID }, null, run({ createdAt: 'now' })] })).toEqual([run()]);
    expect(recentRunsOf(null)).toEqual([]);
    expect(recentRunsOf({ jobs: 'no' })).toEqual([]);
  });
});
