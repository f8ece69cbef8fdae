/**
 * Live trace benchmark -> bench/parts/monitor.json (docs/build-service-api.md "Trace channel").
 * A 1 kHz periodic schema (the "New project" template with PERIOD=1ms) run in bwrap through the
 * HTTP service, on the same workspace (later builds are no-ops): with no client, and with an SSE
 * client reading the live trace.
 *   monitor.jitter_ratio                  p99 of the release lateness (ord_release release_ns -
 *                                         tick_ns, from the collected ORD log) with the client /
 *                                         without (goal <= 1.1)
 *   monitor.release_lateness_us_p99_without / _with   those two p99s
 *   monitor.service_trace_latency_ms_p99  from a record's write (its wall_time column) to its
 *                                         arrival at the SSE client (Date.now()), p99; _p50 too
 *   monitor.trace_records                 records the SSE client received
 *   monitor.service_cpu_ms_without / _with  CPU time of the service's process (and the in-process
 *                                         client) per job, from submit to collected logs
 * The runtime is built from a snapshot of runtime/. Runs RUN_SECONDS (default 3) each, two pairs
 * (without, with) alternated, figures pooled per condition; about 45 s in all.
 */
import { chmodSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PROJECT_TEMPLATES } from '@contract-studio/language';
import { artifactBytes } from '../pipeline/artifacts.js';
import type { TraceEvent } from '../pipeline/job-events.js';
import { createBuildServer } from '../server.js';
import { postJob, readEvents } from '../test-support/client.js';
import { REPO, snapshotRuntime } from '../test-support/tutorial.js';
import { parseRecordLine } from '../trace/parse.js';

const RUN_SECONDS = Number(process.env.RUN_SECONDS ?? 3);
const PAIRS = 2;
const say = (s: string): void => void process.stderr.write(`[bench monitor] ${s}\n`);
const round = (x: number, d = 3): number => Math.round(x * 10 ** d) / 10 ** d;
const pct = (xs: number[], p: number): number => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))]! : NaN;
};

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
  const run = async (withClient: boolean): Promise<{ lateness: number[]; latency: number[]; records: number; cpuMs: number }> => {
    const cpu0 = process.cpuUsage();
    const r = await postJob(url, { action: 'run', sandbox: 'bwrap', duration: RUN_SECONDS, project: { dir } });
    if (r.status !== 201) throw new Error(`submit: ${JSON.stringify(r.json)}`);
    const job = server.service.get(r.json.id as string)!;
    const latency: number[] = [];
    let records = 0;
    if (withClient) {
      await readEvents(url, job.id, (e) => {
        if (e.type !== 'trace') return;
        const now = Date.now();
        for (const l of (e as TraceEvent).records) {
          records++;
          const wall = Date.parse(l.text.split(',', 2)[1] ?? '');
          if (Number.isFinite(wall)) latency.push(now - wall);
          if (process.env.TRACE_BENCH_DEBUG && now - wall > 400) say(`slow ${now - wall} ms (event seq ${e.seq}, ${(e as TraceEvent).records.length} lines): ${l.text.slice(0, 100)}`);
        }
      });
    }
    await job.finished;
    if (!job.result?.ok) {
      const tail = job.events.all.flatMap((e) => (e.type === 'line' ? [`${e.source}: ${e.line}`] : [])).slice(-25);
      throw new Error(`run failed: ${job.result?.message}\n${tail.join('\n')}`);
    }
    const ord = job.artifacts?.files.find((f) => f.name.startsWith('ORD_') && !seen.has(f.name));
    for (const f of job.artifacts?.files ?? []) seen.add(f.name);
    if (!ord) throw new Error('no new ORD log');
    const lateness: number[] = [];
    artifactBytes(ord).toString('utf8').split('\n').forEach((line, i) => {
      if (!line.includes(',ord_release,')) return;
      const rec = parseRecordLine(ord.name, i + 1, line);
      if (rec.kind !== 'ord_release') return;
      const m = /tick_ns=(\d+) release_ns=(\d+)/.exec(rec.detail);
      if (m) lateness.push(Number(BigInt(m[2]!) - BigInt(m[1]!)) / 1000);
    });
    const cpu = process.cpuUsage(cpu0);
    return { lateness, latency, records, cpuMs: (cpu.user + cpu.system) / 1000 };
  };
  try {
    say(`build + warm-up run (${RUN_SECONDS} s)`);
    await run(false);
    // alternated, pooled: the machine's load drifts between runs
    const without = { lateness: [] as number[], cpuMs: 0 };
    const withC = { lateness: [] as number[], latency: [] as number[], records: 0, cpuMs: 0 };
    for (let pair = 0; pair < PAIRS; pair++) {
      say(`run ${pair + 1}/${PAIRS} without a client`);
      const w = await run(false);
      without.lateness.push(...w.lateness);
      without.cpuMs += w.cpuMs;
      say(`run ${pair + 1}/${PAIRS} with an SSE client on the live trace`);
      const r = await run(true);
      withC.lateness.push(...r.lateness);
      withC.latency.push(...r.latency);
      withC.records += r.records;
      withC.cpuMs += r.cpuMs;
    }
    const p99Without = pct(without.lateness, 99);
    const p99With = pct(withC.lateness, 99);
    const out = {
      'monitor.jitter_ratio': round(p99With / p99Without),
      'monitor.release_lateness_us_p99_without': round(p99Without, 1),
      'monitor.release_lateness_us_p99_with': round(p99With, 1),
      'monitor.service_trace_latency_ms_p99': round(pct(withC.latency, 99), 1),
      'monitor.service_trace_latency_ms_p50': round(pct(withC.latency, 50), 1),
      'monitor.trace_records': withC.records,
      'monitor.service_cpu_ms_without': round(without.cpuMs / PAIRS, 0),
      'monitor.service_cpu_ms_with': round(withC.cpuMs / PAIRS, 0),
      'monitor.releases': withC.lateness.length,
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
