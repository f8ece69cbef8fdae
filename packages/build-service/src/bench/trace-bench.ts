/**
 * Live trace benchmark -> bench/parts/monitor.json (docs/build-service-api.md "Trace channel").
 * A 1 kHz periodic schema (the "New project" template with PERIOD=1ms) run in bwrap through the
 * HTTP service. In ONE run, phases of PHASE_SECONDS (default 3) alternate: no client attached, an
 * SSE client attached to the job's stream (from the current seq: it follows the live trace), in
 * ABBA order over PAIRS (default 6) pairs, so that load drifts weigh on both sides alike. The
 * releases (ORD's ord_release records of the collected log, tick_ns on the host's CLOCK_MONOTONIC,
 * the clock of the phase boundaries) are split by phase; the first 200 ms of each phase are left
 * out (the attach / detach itself).
 *   monitor.jitter_ratio                  median over the pairs of p99 release lateness
 *                                         (release_ns - tick_ns) with the client / without (goal <= 1.1)
 *   monitor.jitter_ratio_pooled           the same over all phases pooled; _pairs: every pair's ratio
 *   monitor.release_lateness_us_p99_without / _with   the pooled p99s
 *   monitor.service_trace_latency_ms_p99  from a record's write (its wall_time column) to its
 *                                         arrival at the SSE client (Date.now()), p99; _p50 too
 *   monitor.trace_records                 records the SSE client received; _events_per_s: trace events a second
 *   monitor.service_cpu_ms_per_s_without / _with  CPU time of the service's process (and the
 *                                         in-process client) per second of phase
 * The runtime is built from a snapshot of runtime/. A build + warm-up run first; about 70 s in all.
 */
import { chmodSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PROJECT_TEMPLATES } from '@contract-studio/language';
import { artifactBytes } from '../pipeline/artifacts.js';
import type { TraceEvent } from '../pipeline/job-events.js';
import { createBuildServer } from '../server.js';
import { postJob, streamEvents } from '../test-support/client.js';
import { REPO, snapshotRuntime } from '../test-support/tutorial.js';
import { parseRecordLine } from '../trace/parse.js';

const PHASE_SECONDS = Number(process.env.PHASE_SECONDS ?? 3);
const PAIRS = Number(process.env.PAIRS ?? 6);
/** Left out at the start of each phase (the attach or detach itself). */
const SETTLE_NS = 200_000_000n;
const say = (s: string): void => void process.stderr.write(`[bench monitor] ${s}\n`);
const round = (x: number, d = 3): number => Math.round(x * 10 ** d) / 10 ** d;
const pct = (xs: number[], p: number): number => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))]! : NaN;
};
const median = (xs: number[]): number => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2]! : (s[s.length / 2 - 1]! + s[s.length / 2]!) / 2;
};
const sleep = (ms: number): Promise<void> => new Promise((r) => setTimeout(r, ms));

/** An SSE client of the job's stream from `after` on, until aborted; `onTrace` sees each trace event. */
async function attach(base: string, id: string, after: number, signal: AbortSignal, onTrace: (e: TraceEvent) => void): Promise<void> {
  try {
    await streamEvents(base, id, (e) => {
      if (e.type === 'trace') onTrace(e as TraceEvent);
    }, after, signal);
  } catch (e) {
    if (!signal.aborted) throw e;
  }
}

interface Phase {
  withClient: boolean;
  pair: number;
  from: bigint;
  to: bigint;
  cpuMs: number;
}

/** The template at 1 kHz: PERIOD=1ms, module budgets well inside it. */
function project(dir: string): void {
  mkdirSync(dir, { recursive: true });
  for (const [name, text] of Object.entries(PROJECT_TEMPLATES)) {
    writeFileSync(join(dir, name), text.replace('PERIOD=10ms; CRITICAL_DELAY=10ms;', 'PERIOD=1ms; CRITICAL_DELAY=1ms;').replace('C=500us;', 'C=100us;').replace('C=1ms;', 'C=200us;'));
  }
}

async function main(): Promise<void> {
  const root = mkdtempSync(join(tmpdir(), 'contract-monitor-bench-'));
  chmodSync(root, 0o755); // the jobs' uids walk through it to their work dirs
  const cacheDir = join(root, 'cache');
  const dir = join(root, 'projects', 'khz');
  project(dir);
  mkdirSync(cacheDir, { recursive: true });
  const runtimeSource = snapshotRuntime();
  const server = createBuildServer({ token: false, port: 0, concurrency: 1, cacheDir, runtimeSource, projectRoots: [join(root, 'projects')] });
  const { url } = await server.listen();
  /** Logs of earlier runs stay in the reused workspace's logs/ (and among the artifacts). */
  const seen = new Set<string>();
  /** One run of `seconds`; `during` runs once the run streams its trace; returns ORD's releases (tick_ns, lateness in us). */
  const run = async (seconds: number, during: (jobId: string) => Promise<void>): Promise<{ tick: bigint; lateUs: number }[]> => {
    const r = await postJob(url, { action: 'run', sandbox: 'bwrap', duration: seconds, project: { dir } });
    if (r.status !== 201) throw new Error(`submit: ${JSON.stringify(r.json)}`);
    const job = server.service.get(r.json.id as string)!;
    // the run streams (looked at in-process: no client attached)
    while (!job.events.all.some((e) => e.type === 'trace') && !job.result) await sleep(20);
    await during(job.id);
    await job.finished;
    if (!job.result?.ok) {
      const tail = job.events.all.flatMap((e) => (e.type === 'line' ? [`${e.source}: ${e.line}`] : [])).slice(-25);
      throw new Error(`run failed: ${job.result?.message}\n${tail.join('\n')}`);
    }
    const ord = job.artifacts?.files.find((f) => f.name.startsWith('ORD_') && !seen.has(f.name));
    for (const f of job.artifacts?.files ?? []) seen.add(f.name);
    if (!ord) throw new Error('no new ORD log');
    const releases: { tick: bigint; lateUs: number }[] = [];
    artifactBytes(ord).toString('utf8').split('\n').forEach((line, i) => {
      if (!line.includes(',ord_release,')) return;
      const rec = parseRecordLine(ord.name, i + 1, line);
      if (rec.kind !== 'ord_release') return;
      const m = /tick_ns=(\d+) release_ns=(\d+)/.exec(rec.detail);
      if (m) releases.push({ tick: BigInt(m[1]!), lateUs: Number(BigInt(m[2]!) - BigInt(m[1]!)) / 1000 });
    });
    return releases;
  };
  try {
    say('build + warm-up run (3 s)');
    await run(3, async () => {});
    const phases: Phase[] = [];
    const latency: number[] = [];
    let records = 0;
    let events = 0;
    const phaseMs = PHASE_SECONDS * 1000;
    const seconds = Math.ceil(2 * PAIRS * PHASE_SECONDS + 3);
    say(`one run of ${seconds} s: ${PAIRS} pairs of ${PHASE_SECONDS} s phases without / with an SSE client on the live trace (ABBA)`);
    const releases = await run(seconds, async (jobId) => {
      const job = server.service.get(jobId)!;
      for (let pair = 0; pair < PAIRS; pair++) {
        const order = pair % 2 === 0 ? [false, true] : [true, false];
        for (const withClient of order) {
          const cpu0 = process.cpuUsage();
          const from = process.hrtime.bigint();
          if (withClient) {
            const abort = new AbortController();
            const after = job.events.all.at(-1)?.seq ?? 0;
            const reading = attach(url, jobId, after, abort.signal, (e) => {
              const now = Date.now();
              events++;
              for (const l of e.records) {
                records++;
                const wall = Date.parse(l.text.split(',', 2)[1] ?? '');
                if (Number.isFinite(wall)) latency.push(now - wall);
              }
            });
            await sleep(phaseMs);
            abort.abort();
            await reading;
          } else await sleep(phaseMs);
          const cpu = process.cpuUsage(cpu0);
          phases.push({ withClient, pair, from, to: process.hrtime.bigint(), cpuMs: (cpu.user + cpu.system) / 1000 });
        }
      }
    });
    const inPhase = (p: Phase): number[] => releases.filter((r) => r.tick >= p.from + SETTLE_NS && r.tick < p.to).map((r) => r.lateUs);
    const ratios: number[] = [];
    for (let pair = 0; pair < PAIRS; pair++) {
      const w = phases.find((p) => p.pair === pair && p.withClient)!;
      const wo = phases.find((p) => p.pair === pair && !p.withClient)!;
      ratios.push(pct(inPhase(w), 99) / pct(inPhase(wo), 99));
    }
    const pooled = (withClient: boolean): number[] => phases.filter((p) => p.withClient === withClient).flatMap(inPhase);
    const cpuPerS = (withClient: boolean): number => {
      const ps = phases.filter((p) => p.withClient === withClient);
      return ps.reduce((a, p) => a + p.cpuMs, 0) / ps.reduce((a, p) => a + Number(p.to - p.from) / 1e9, 0);
    };
    const p99Without = pct(pooled(false), 99);
    const p99With = pct(pooled(true), 99);
    const out = {
      'monitor.jitter_ratio': round(median(ratios)),
      'monitor.jitter_ratio_pooled': round(p99With / p99Without),
      'monitor.jitter_ratio_pairs': ratios.map((x) => round(x)),
      'monitor.release_lateness_us_p99_without': round(p99Without, 1),
      'monitor.release_lateness_us_p99_with': round(p99With, 1),
      'monitor.service_trace_latency_ms_p99': round(pct(latency, 99), 1),
      'monitor.service_trace_latency_ms_p50': round(pct(latency, 50), 1),
      'monitor.trace_records': records,
      'monitor.trace_events_per_s': round(events / phases.filter((p) => p.withClient).reduce((a, p) => a + Number(p.to - p.from) / 1e9, 0), 0),
      'monitor.service_cpu_ms_per_s_without': round(cpuPerS(false), 1),
      'monitor.service_cpu_ms_per_s_with': round(cpuPerS(true), 1),
      'monitor.releases': pooled(true).length + pooled(false).length,
    };
    say(JSON.stringify(out));
    mkdirSync(join(REPO, 'bench', 'parts'), { recursive: true });
    writeFileSync(join(REPO, 'bench', 'parts', 'monitor.json'), JSON.stringify(out, null, 2) + '\n');
  } finally {
    await server.close();
    rmSync(root, { recursive: true, force: true });
    rmSync(runtimeSource, { recursive: true, force: true });
  }
}

main().catch((e) => {
  say(`FAILED: ${(e as Error).stack ?? e}`);
  process.exit(1);
});
