import { setFlagsFromString } from 'node:v8';
import { runInNewContext } from 'node:vm';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import type { Sandbox } from '../sandbox/types.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import type { LineEvent } from './job-events.js';
import { Job } from './job.js';
import { budgetThrottling, throttlingWarning, ThrottlingReader, type Throttling } from './realtime-throttling.js';

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

/** The reading of ORD's log before it was streamed, as a model: every time of the text, sorted, each silence kept. */
function modelThrottling(log: string, periodNs: number): Throttling | undefined {
  const times: number[] = [];
  for (const line of log.split('\n')) {
    const comma = line.indexOf(',');
    if (comma > 0 && /^\d+$/.test(line.slice(0, comma))) times.push(Number(line.slice(0, comma)));
  }
  times.sort((a, b) => a - b);
  const bins = Math.max(1, Math.round(periodNs / 500_000));
  const silences = times.slice(1).map((t, i) => ({ ns: t - times[i]!, bin: Math.floor((t % periodNs) / 500_000) % bins })).filter((s) => s.ns >= 3 * MS);
  const around = (c: number) => [-2, -1, 0, 1, 2].map((d) => (c + d + bins) % bins);
  let best = 0, bestBin = 0;
  for (let c = 0; c < bins; c++) {
    const n = around(c).reduce((sum, bin) => sum + silences.filter((x) => x.bin === bin).length, 0);
    if (n > best) [best, bestBin] = [n, c];
  }
  if (best < 3 || best < 0.5 * silences.length) return undefined;
  const throttled = silences.filter((x) => around(bestBin).includes(x.bin));
  return { times: throttled.length, totalNs: throttled.reduce((sum, x) => sum + x.ns, 0), silences: silences.length };
}

describe('ORD\'s log read as a stream', () => {
  it('finds what the whole text sorted gives, its bytes given in chunks cut anywhere (lines a few records out of order, the header, lines that are no record)', () => {
    const log = fc.tuple(fc.integer({ min: 0, max: 2 ** 40 }), fc.array(fc.tuple(fc.integer({ min: 0, max: 12 * MS }), fc.nat(30)), { minLength: 0, maxLength: 400 }), fc.integer({ min: 0, max: 50 }))
      .map(([from, steps, seed]) => {
        let t = from;
        const lines = steps.map(([step, what]) => {
          t += step;
          return what === 0 ? 'garbage,line' : what === 1 ? 'no comma' : `${t},w,ORD,ord_release,ENC,,0,x`;
        });
        // a few lines each a few records out of place (two threads writing at once)
        for (let i = seed % 7; i + 3 < lines.length; i += 11 + (seed % 5)) [lines[i], lines[i + 3]] = [lines[i + 3]!, lines[i]!];
        return `${HEADER}\n${lines.join('\n')}${seed % 2 ? '\n' : ''}`;
      });
    fc.assert(fc.property(log, fc.integer({ min: 1, max: 64 }), fc.constantFrom(10 * MS, 100 * MS, 1 * MS), (text, chunk, periodNs) => {
      const bytes = Buffer.from(text);
      const reader = new ThrottlingReader(periodNs);
      for (let at = 0; at < bytes.length; at += chunk) reader.add(bytes.subarray(at, at + chunk));
      expect(reader.result()).toEqual(modelThrottling(text, periodNs));
    }), { numRuns: 300 });
  });

  it('reads the log of a 1 kHz run of 17 minutes (580,000 records, 110 MB) given in chunks holding under 4 MB of V8\'s heap', () => {
    setFlagsFromString('--expose-gc');
    const gc = runInNewContext('gc') as () => void;
    const heap = () => (gc(), gc(), process.memoryUsage().heapUsed);
    const from = 59_529_770_322_845;
    const reader = new ThrottlingReader(100 * MS);
    const before = heap();
    let most = 0;
    let bytes = 0;
    let chunks = 0;
    let lines: string[] = [HEADER];
    const give = () => {
      const chunk = Buffer.from(lines.join('\n') + '\n');
      bytes += chunk.length;
      reader.add(chunk);
      lines = [];
      if (++chunks % 8 === 0) most = Math.max(most, heap() - before);
    };
    for (let i = 0; i < 1_000_000; i++) {
      const t = from + i * MS + 40_000;
      // the budget used up 58 ms into each 100 ms period: ORD silent for the rest of it
      if (t % (100 * MS) < 58 * MS) lines.push(`${t},2026-12-07T03:00:00.000000Z,ORD,ord_release,ENC,,0,schema=fastLoop cycle=${i} tick_ns=${from + i * MS} release_ns=${t} release=${i + 1} ${'x'.repeat(30)}`);
      if (lines.length >= 10_000) give();
    }
    give();
    const t = reader.result()!;
    most = Math.max(most, heap() - before);
    expect(bytes).toBeGreaterThan(100_000_000);
    expect(t.times).toBeGreaterThanOrEqual(9_990);
    expect(t.totalNs / t.times).toBeGreaterThan(40 * MS);
    // the text of the log alone, as the reader took it before (and a list of its times), is over 100 MB
    expect(most).toBeLessThan(4 * 1024 * 1024);
  });

  it('reads the times of a machine up for more than 104 days (mono_ns past 2^53)', () => {
    const from = 10_000_000_000_000_000; // 115 days
    const log = ordLog(from, 2000, (t) => t % (100 * MS) >= 58 * MS);
    const t = budgetThrottling(log, 100 * MS)!;
    expect(t.times).toBeGreaterThanOrEqual(19);
    expect(budgetThrottling(Buffer.from(log), 100 * MS)).toEqual(t);
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
