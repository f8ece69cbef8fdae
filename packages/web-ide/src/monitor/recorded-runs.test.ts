import { describe, expect, it } from 'vitest';
import { isRecorded, recordedRunsToLetGo, type KeptRun } from './recorded-runs.js';

const run = (id: string, used: number, recordCount = 1000, live = false): KeptRun => ({ id, used, recordCount, live });

describe('the recorded runs the Monitor keeps', () => {
  it('keeps the 6 used last; lets go of the others, oldest use first', () => {
    const runs = Array.from({ length: 8 }, (_, i) => run(`job:j${i}`, i + 1));
    expect(recordedRunsToLetGo(runs, new Set(['job:j7']))).toEqual(['job:j1', 'job:j0']);
  });

  it('keeps what the records allow: a large run lets the older ones go', () => {
    const runs = [run('job:old', 1, 1_000_000), run('dir:logs', 2, 1_500_000), run('job:new', 3, 1_000_000)];
    expect(recordedRunsToLetGo(runs, new Set(['job:new']))).toEqual(['job:old']);
    expect(recordedRunsToLetGo(runs, new Set(['job:new']), { runs: 6, records: 2_400_000 })).toEqual(['dir:logs', 'job:old']);
  });

  it('never lets go of the run just made nor the one shown, even past the bounds', () => {
    const runs = [run('job:shown', 1, 5_000_000), run('file:t.jsonl', 2), run('job:new', 3, 5_000_000)];
    expect(recordedRunsToLetGo(runs, new Set(['job:new', 'job:shown']))).toEqual(['file:t.jsonl']);
  });

  it('counts recorded runs only: a live run (its worker is bounded apart) and a simulation are not', () => {
    expect(isRecorded({ id: 'live:j1', live: false })).toBe(false);
    expect(isRecorded({ id: 'sim', live: false })).toBe(false);
    expect(isRecorded({ id: 'job:j1', live: false })).toBe(true);
    const runs = [...Array.from({ length: 6 }, (_, i) => run(`dir:d${i}`, i + 10)), run('live:j9', 99, 10_000_000), run('sim', 98, 10_000_000)];
    expect(recordedRunsToLetGo(runs, new Set())).toEqual([]);
  });
});
