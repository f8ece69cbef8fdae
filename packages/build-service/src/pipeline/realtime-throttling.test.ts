import { describe, expect, it } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import type { Sandbox } from '../sandbox/types.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import type { LineEvent } from './job-events.js';
import { Job } from './job.js';
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
      /^the architecture was throttled by its real-time CPU budget about \d+ times \(0\.\d\d s in all\): the sandbox gives the whole architecture 40 ms of each 100 ms on each CPU, .*contract run --cpus 0,1.*REALTIME_BOUNDS\.cpuRuntimeUs/);
  });

  it('reads ORD\'s log as bytes: one larger than a string can be (up to RUN_LOG_MAX_BYTES) is read too', () => {
    const from = 59_529_770_322_845;
    const records = Buffer.from(ordLog(from, 2000, (t) => t % (100 * MS) >= 80 * MS));
    // 600 MB of zeros (untouched pages) first, as one line: past V8's longest string (2^29 - 24 characters)
    const big = Buffer.alloc(600_000_001 + records.length);
    big[600_000_000] = 10;
    records.copy(big, 600_000_001);
    const t = budgetThrottling(big, 100 * MS)!;
    expect(t.times).toBeGreaterThanOrEqual(19);
    expect(t.times).toBeLessThanOrEqual(21);
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

describe('the throttling warning of a job', () => {
  it('is one of the job\'s warnings (the CLI says those at the end in every mode), and its run\'s `warning:` line, once each', async () => {
    const from = 59_529_770_322_845;
    // the field test (khzb): the budget used up about 58 ms into each 100 ms period
    const log = ordLog(from, 2000, (t) => t % (100 * MS) >= 58 * MS);
    const job = new Job('j-throttled', { action: 'run', realtime: true, project: { files: { Makefile: 'all:\n\ttrue\nrun:\n\ttrue\n' } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS } } as never, 'none');
    const sandbox: Sandbox = {
      ...scriptedSandbox({ run: { start: (p) => p.exit(0) } }),
      realtimeSupport: async () => ({ ok: true, detail: 'scripted (test)', budget: { runtimeUs: 40_000, periodUs: 100_000 } }),
      readWorkDirs: async (_w: string, rels: string[]) => new Map(rels.map((rel) => [rel, rel === 'logs'
        ? { entries: [{ name: 'ORD_7-Dec-2026-03h00m00s.csv', kind: 'file' as const, size: log.length, read: async (max: number) => Buffer.from(log).subarray(0, max) }] }
        : null])),
      removeRunOutputs: async () => true,
    };
    await job.execute(scriptedContext(sandbox, scratchWorkspace()));
    const said = job.warnings.filter((w) => w.startsWith('the architecture was throttled by its real-time CPU budget about '));
    expect(said, job.events.all.map((e) => (e.type === 'line' ? e.line : '')).join('\n')).toHaveLength(1);
    const lines = job.events.all.filter((e): e is LineEvent => e.type === 'line' && e.step === 'run' && e.source === 'service').map((e) => e.line);
    expect(lines.filter((l) => l.includes('throttled'))).toEqual([`warning: ${said[0]}`]);
  });
});
