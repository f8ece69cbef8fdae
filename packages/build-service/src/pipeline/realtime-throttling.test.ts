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

/**
 * ORD's log as ORD writes it (runtime/src/engines/ord_core.c) for a 1 kHz schema: a release record
 * 40 µs after each tick, but in the silences (`silent`); when it runs again after one, a `missed
 * tick` line for each tick it skipped (overtaken by a later one), then the release of the tick due.
 */
function ordLog(from: number, ms: number, silent: (t: number) => boolean): string {
  const lines = [HEADER];
  const missed: number[] = [];
  for (let i = 0; i < ms; i++) {
    const t = from + i * MS + 40_000; // ORD writes 40 µs after each tick
    if (silent(t)) {
      missed.push(i);
      continue;
    }
    for (const k of missed) lines.push(`${t},w,ORD,scheduler,,,0,missed tick of fastLoop (cycle ${k})`);
    missed.length = 0;
    lines.push(`${t},w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=${i} tick_ns=${from + i * MS} release_ns=${t} release=${i + 1}`);
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

  it('does not take ORD\'s idle time between the ticks of a 100 ms schema for it, though those silences end at one point of the period (the auditor\'s `lim`, 4 s)', () => {
    // ORD's records of one 100 ms schema whose module LIM uses about 0.5 ms a release, as a real
    // --realtime run writes them: the release 20-80 µs after the tick, LIM's ack read about 0.6 ms
    // after it; then nothing to do until the next tick: 99 ms of silence ending at the same phase
    const from = 59_529_770_322_845;
    const lines = [HEADER, `${from - 2_000_000},w,ORD,scheduler,,,0,activate lim (activation #1 from SUP)`];
    for (let k = 0; k < 40; k++) {
      const tick = from + k * 100 * MS, rel = tick + 20_000 + ((k * 7919) % 60_000), done = rel + 600_000;
      lines.push(`${rel},w,ORD,ord_release,LIM,,0,schema=lim cycle=${k} tick_ns=${tick} release_ns=${rel} release=${k + 1}`);
      lines.push(`${done},w,ORD,ack_received,LIM,,0,ACK_FINISHED id=${k + 1}`);
      lines.push(`${done + 2_000},w,ORD,ord_finished,LIM,,0,schema=lim cycle=${k} release=${k + 1} response_ns=${done - tick}`);
      lines.push(`${done + 3_000},w,ORD,ord_complete,,,0,schema=lim cycle=${k} tick_ns=${tick} response_ns=${done - tick}`);
    }
    const log = `${lines.join('\n')}\n`;
    expect(budgetThrottling(log, 100 * MS, 40 * MS)).toBeUndefined();
  });

  it('does not take the tutorial\'s idle seconds (two 1 s schemas) for it (the auditor\'s 5 s run: 3 cycles completed)', () => {
    const from = 12_000_000_000;
    const lines = [HEADER];
    for (let k = 0; k < 5; k++) {
      const tick = from + k * 1000 * MS;
      let t = tick + 45_000;
      for (const [m, id] of [['MSA', 3 * k + 1], ['MSC', 3 * k + 2], ['MSD', 3 * k + 3]] as const) {
        lines.push(`${t},w,ORD,ord_release,${m},,0,schema=schemaCommande1 cycle=${k} tick_ns=${tick} release_ns=${t} release=${id}`);
        t += 150_000;
        lines.push(`${t},w,ORD,ack_received,${m},,0,ACK_FINISHED id=${id}`);
        lines.push(`${t + 1_000},w,ORD,ord_finished,${m},,0,schema=schemaCommande1 cycle=${k} release=${id} response_ns=${t - tick}`);
        t += 10_000;
      }
      lines.push(`${t},w,ORD,ord_complete,,,0,schema=schemaCommande1 cycle=${k} tick_ns=${tick} response_ns=${t - tick}`);
    }
    expect(budgetThrottling(`${lines.join('\n')}\n`, 100 * MS, 40 * MS)).toBeUndefined();
  });

  it('counts a silence for at most what the budget can take of a period (60 of each 100 ms), whatever ORD\'s silence was', () => {
    // ORD silent 85 ms of each 100 ms with ticks due: no 40/100 budget does that alone; at most 60 ms a period is the budget's
    const from = 59_529_770_322_845;
    const t = budgetThrottling(ordLog(from, 2000, (x) => x % (100 * MS) >= 15 * MS), 100 * MS, 40 * MS)!;
    expect(t.times).toBeGreaterThanOrEqual(19);
    expect(t.totalNs).toBeLessThanOrEqual(t.times * 60 * MS);
    expect(t.totalNs / t.times).toBeGreaterThan(59 * MS);
  });

  it('counts a throttled 100 ms schema: its tick fell in the silence, ORD released it when the period ended', () => {
    // a 100 ms schema ticking 70 ms into each budget period, the budget used up by then: ORD releases it 30 ms late, at the period's end
    const from = 5_000_000_000;
    const lines = [HEADER];
    for (let k = 0; k < 20; k++) {
      const tick = from + k * 100 * MS + 70 * MS, rel = from + (k + 1) * 100 * MS + 30_000;
      lines.push(`${tick - 5 * MS},w,ORD,ack_received,LIM,,0,ACK_FINISHED id=${k}`);
      lines.push(`${rel},w,ORD,ord_release,LIM,,0,schema=lim cycle=${k} tick_ns=${tick} release_ns=${rel} release=${k + 1}`);
    }
    const t = budgetThrottling(`${lines.join('\n')}\n`, 100 * MS, 40 * MS)!;
    expect(t).toBeDefined();
    expect(t.times).toBeGreaterThanOrEqual(19);
    expect(t.totalNs / t.times).toBeGreaterThan(29 * MS);
    expect(t.totalNs / t.times).toBeLessThan(31 * MS);
  });

  it('a run that was never silent 3 ms or more, or a log with no record, was not throttled', () => {
    expect(budgetThrottling(ordLog(1_000_000_000, 1000, () => false), 100 * MS)).toBeUndefined();
    expect(budgetThrottling(`${HEADER}\n`, 100 * MS)).toBeUndefined();
    expect(budgetThrottling('', 100 * MS)).toBeUndefined();
  });
});

/**
 * The reading of ORD's log as a model: every record of the text (its time; when its work was due:
 * a release's tick, a missed tick on its schema's grid, a deadline), sorted, each silence kept with
 * the earliest work due in it that the records after it (to the next silence) show.
 */
function modelThrottling(log: string, periodNs: number, runtimeNs = 0): Throttling | undefined {
  const records: Array<{ t: number; due: number }> = [];
  const grids = new Map<string, { cycle: number; tick: number; periodNs: number }>();
  for (const line of log.split('\n')) {
    const f = line.slice(0, 512).split(',');
    if (!/^\d{1,19}$/.test(f[0]!) || f.length < 2) continue;
    let due = Infinity;
    const detail = f.length >= 8 ? f.slice(7).join(',') : '';
    if (f.length >= 8 && f[3] === 'ord_release') {
      const m = /tick_ns=(\d{1,19})/.exec(detail);
      if (m) due = Number(m[1]);
      const r = /^"?schema=(\S+) cycle=(\d+) tick_ns=(\d+)/.exec(detail);
      if (r) {
        const g = grids.get(r[1]!), cycle = Number(r[2]), tick = Number(r[3]);
        if (!g) grids.set(r[1]!, { cycle, tick, periodNs: 0 });
        else {
          if (cycle > g.cycle && tick > g.tick) g.periodNs = (tick - g.tick) / (cycle - g.cycle);
          Object.assign(g, { cycle, tick });
        }
      }
    } else if (f.length >= 8 && f[3] === 'scheduler') {
      const m = /^"?missed tick of (\S+) \(cycle (\d+)\)/.exec(detail);
      const g = m && grids.get(m[1]!);
      if (g && g.periodNs > 0) due = g.tick + (Number(m[2]) - g.cycle) * g.periodNs;
    } else if (f.length >= 8 && f[3] === 'ord_deadline_miss') {
      const tick = /tick_ns=(\d{1,19})/.exec(detail), cd = /critical_delay_ns=(\d{1,19})/.exec(detail);
      if (tick && cd) due = Number(tick[1]) + Number(cd[1]);
    }
    records.push({ t: Number(f[0]), due });
  }
  records.sort((a, b) => a.t - b.t);
  const bins = Math.max(1, Math.round(periodNs / 500_000));
  const silences: Array<{ from: number; to: number; dueFrom: number }> = [];
  for (let i = 1; i < records.length; i++) {
    const r = records[i]!;
    if (r.t - records[i - 1]!.t >= 3 * MS) silences.push({ from: records[i - 1]!.t, to: r.t, dueFrom: Infinity });
    const s = silences[silences.length - 1];
    if (s && r.due > s.from && r.due < s.to) s.dueFrom = Math.min(s.dueFrom, r.due);
  }
  const late = silences.filter((s) => s.to - s.dueFrom >= 1 * MS)
    .map((s) => ({ ns: Math.min(s.to - s.dueFrom, periodNs - runtimeNs), bin: Math.floor((s.to % periodNs) / 500_000) % bins }));
  const around = (c: number) => [-2, -1, 0, 1, 2].map((d) => (c + d + bins) % bins);
  let best = 0, bestBin = 0;
  for (let c = 0; c < bins; c++) {
    const n = around(c).reduce((sum, bin) => sum + late.filter((x) => x.bin === bin).length, 0);
    if (n > best) [best, bestBin] = [n, c];
  }
  if (best < 3 || best < 0.5 * late.length) return undefined;
  const throttled = late.filter((x) => new Set(around(bestBin)).has(x.bin));
  return { times: throttled.length, totalNs: throttled.reduce((sum, x) => sum + x.ns, 0), silences: late.length };
}

describe('ORD\'s log read as a stream', () => {
  it('finds what the whole text sorted gives, its bytes given in chunks cut anywhere (lines a few records out of order, the header, lines that are no record)', () => {
    const log = fc.tuple(fc.integer({ min: 0, max: 2 ** 40 }), fc.array(fc.tuple(fc.integer({ min: 0, max: 12 * MS }), fc.nat(30)), { minLength: 0, maxLength: 400 }), fc.integer({ min: 0, max: 50 }))
      .map(([from, steps, seed]) => {
        let t = from;
        const lines = steps.map(([step, what]) => {
          t += step;
          // a release on a 1 ms grid (its tick up to 12 ms before it), a missed tick on it, a deadline told late, other records
          const tick = t - (what % 13) * MS;
          return what === 0 ? 'garbage,line' : what === 1 ? 'no comma'
            : what < 12 ? `${t},w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=${Math.floor(tick / MS)} tick_ns=${Math.floor(tick / MS) * MS} release_ns=${t} release=1`
            : what < 18 ? `${t},w,ORD,scheduler,,,0,missed tick of fastLoop (cycle ${Math.floor(tick / MS)})`
            : what < 20 ? `${t},w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=1 tick_ns=${tick - 800_000} critical_delay_ns=800000`
            : `${t},w,ORD,ack_received,ENC,,0,ACK_FINISHED id=1`;
        });
        // a few lines each a few records out of place (two threads writing at once)
        for (let i = seed % 7; i + 3 < lines.length; i += 11 + (seed % 5)) [lines[i], lines[i + 3]] = [lines[i + 3]!, lines[i]!];
        return `${HEADER}\n${lines.join('\n')}${seed % 2 ? '\n' : ''}`;
      });
    fc.assert(fc.property(log, fc.integer({ min: 1, max: 64 }), fc.constantFrom(10 * MS, 100 * MS, 1 * MS), (text, chunk, periodNs) => {
      const bytes = Buffer.from(text);
      const reader = new ThrottlingReader(periodNs, periodNs * 0.4);
      for (let at = 0; at < bytes.length; at += chunk) reader.add(bytes.subarray(at, at + chunk));
      expect(reader.result()).toEqual(modelThrottling(text, periodNs, periodNs * 0.4));
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
    let missedFrom = 0;
    for (let i = 0; i < 1_000_000; i++) {
      const t = from + i * MS + 40_000;
      // the budget used up 58 ms into each 100 ms period: ORD silent for the rest of it
      if (t % (100 * MS) < 58 * MS) {
        for (; missedFrom < i; missedFrom++) lines.push(`${t},2026-12-07T03:00:00.000000Z,ORD,scheduler,,,0,missed tick of fastLoop (cycle ${missedFrom})`);
        missedFrom = i + 1;
        lines.push(`${t},2026-12-07T03:00:00.000000Z,ORD,ord_release,ENC,,0,schema=fastLoop cycle=${i} tick_ns=${from + i * MS} release_ns=${t} release=${i + 1} ${'x'.repeat(30)}`);
      }
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
