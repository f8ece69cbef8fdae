/**
 * Live trace benchmark -> bench/parts/monitor.json (docs/build-service-api.md "Trace channel").
 * A 1 kHz periodic schema (the "New project" template with PERIOD=1ms) run in bwrap through the
 * HTTP service, once per layout (planLayouts; the pinned layout and its control PINNED_RUNS times,
 * in turns). In ONE run, phases of PHASE_SECONDS (default 3)
 * alternate: no client attached, an SSE client attached to the job's stream (from the current seq:
 * it follows the live trace), in ABBA order over PAIRS (default 9: 57 s, inside the run's 60 s
 * bound) pairs, so that load drifts weigh on both sides alike. The releases (ORD's ord_release
 * records of the collected log, tick_ns on the host's CLOCK_MONOTONIC, the clock of the phase
 * boundaries) are split by phase; the first 200 ms of each phase are left out (the attach / detach
 * itself). Layouts (docs/monitor-performance.md "Where the run, the service and the browser run"):
 *   monitor.*                 the modules pinned to the last CPU (the job's `cpus`): the set-up in
 *                             which sched.period_jitter_us_p99 is measured (docs/engines.md); the
 *                             service keeps off that CPU by itself (service-affinity.ts; the bench
 *                             checks it), the child client is started on the service's CPUs
 *   monitor.shared.*          no placement: the modules, the service and its client share every CPU
 *   monitor.shared_realtime.* the same with the job's real-time mode (the modules at SCHED_FIFO)
 *   monitor.null.*            the control: the pinned layout, its "with" phases attaching NO client
 *                             (A/A): its ratios are the host's noise alone, the spread any
 *                             jitter_ratio above must be read against
 *   (MONITOR_LAYOUTS=pinned,shared,shared_realtime,null picks; one that the machine cannot have, as
 *   pinned on one CPU, is <prefix>.skipped with why.) Each layout's figures:
 *   jitter_ratio                  median over the pairs (of every run of the layout: PINNED_RUNS,
 *                                 default 2, for the pinned layout and its control, taken in turns;
 *                                 one for the others; _runs: each run's own median) of p99 release lateness
 *                                 (release_ns - tick_ns) with the client / without (goal <= 1.1)
 *   jitter_ratio_pooled           the same over all phases pooled; _pairs: every pair's ratio
 *   release_lateness_us_p99_without / _with   the pooled p99s; releases: how many were counted
 *   service_trace_latency_ms_p99  from a record's write (its mono_ns column) to its arrival at the
 *                                 SSE client (process.hrtime, the same clock), p99; _p50 too
 *   trace_records                 records the SSE client received; trace_events_per_s: trace events a second
 *   service_cpu_ms_per_s_without / _with  CPU time of the service's process per second of phase;
 *                                 _sys_: of it in the kernel; _by_thread_: main thread and the
 *                                 others (GC, JIT, libuv's pool). The SSE client
 *                                 (trace-bench-client.ts) runs in the service's process by default
 *                                 (so the "with" figures include its work, as when the jitter goal
 *                                 was set); MONITOR_CLIENT=child runs it in a child process of its
 *                                 own, as the IDE's page and the CLI are: the figures are then the
 *                                 service's only (monitor.client says which)
 *   service_cpu_us_per_record_without / _with  that CPU time over the records the run wrote in
 *                                 those phases (counted in the collected logs by mono_ns)
 *   client_cpu_ms_per_s           (child client only) its own CPU time per second of phase
 *   steal_ms_per_s_without / _with  time the hypervisor took from the modules' CPUs (/proc/stat
 *                                 steal, summed over those CPUs) per second of phase; steal_ms_pairs:
 *                                 each pair's with - without (0 on a machine that is not a guest)
 *   steal_r                       correlation of the pairs' log(ratio) with their steal difference
 *   jitter_ratio_at_equal_steal   the ratio a least-squares line of log(ratio) on the steal
 *                                 difference gives at no difference (left out when nothing was stolen)
 * The runtime is built from a snapshot of runtime/. A build + warm-up run first; about 400 s in all.
 */
import { spawn } from 'node:child_process';
import { readdirSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { artifactBytes, type Artifact } from '../pipeline/artifacts.js';
import { postJob } from '../test-support/client.js';
import { followTrace, type ClientReport } from './trace-bench-client.js';
import { benchLog, median, pct, ratioAtZero, round, runBench, startBenchServer, writePart, writeTemplateProject } from './bench-support.js';
import { parseRecordLine } from '../trace/parse.js';
import { ownCpus } from '../pipeline/service-affinity.js';

const PHASE_SECONDS = Number(process.env.PHASE_SECONDS ?? 3);
const PAIRS = Number(process.env.PAIRS ?? 9);
/**
 * Runs of the pinned layout and of its control, taken in turns (pinned, control, pinned, ...):
 * their figures are over the pairs of all of them (a median of 9 pairs moves by about 10 % with
 * nothing changed: docs/monitor-performance.md "What the host takes").
 */
const PINNED_RUNS = Math.max(1, Number(process.env.PINNED_RUNS ?? 2));
/**
 * The SSE client in a child process of its own (MONITOR_CLIENT=child): the CPU figures are then
 * the service's only; in this process (the default, as the jitter goal was set) they include the
 * client's work, and the two share one thread.
 */
const CHILD_CLIENT = process.env.MONITOR_CLIENT === 'child';
/** Left out at the start of each phase (the attach or detach itself). */
const SETTLE_NS = 200_000_000n;
const say = benchLog('monitor');
const sleep = (ms: number): Promise<void> => new Promise((r) => setTimeout(r, ms));

const TICK_MS = 1000 / 100; // USER_HZ: /proc's clock ticks (100 on Linux)

/** Stolen time (ms, /proc/stat's steal column) of each CPU so far. */
function stealMs(): Map<number, number> {
  const out = new Map<number, number>();
  for (const line of readFileSync('/proc/stat', 'utf8').split('\n')) {
    const m = /^cpu(\d+) (.*)$/.exec(line);
    if (m) out.set(Number(m[1]), (Number(m[2]!.split(' ')[7]) || 0) * TICK_MS);
  }
  return out;
}

/** CPU ms of this process's threads: the main thread, the others summed by thread name. */
function threadCpuMs(): Map<string, number> {
  const out = new Map<string, number>();
  for (const t of readdirSync('/proc/self/task')) {
    try {
      const stat = readFileSync(`/proc/self/task/${t}/stat`, 'utf8');
      const comm = stat.slice(stat.indexOf('(') + 1, stat.lastIndexOf(')')).replace(/\d+$/, 'N');
      const name = t === String(process.pid) ? 'main' : `other ${comm}`;
      const f = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      out.set(name, (out.get(name) ?? 0) + (Number(f[11]) + Number(f[12])) * TICK_MS);
    } catch {
      /* the thread ended */
    }
  }
  return out;
}

/** CPU ids of a list such as `0-2,5`. */
function cpuIds(list: string): number[] {
  return list.split(',').flatMap((part) => {
    const [lo, hi] = part.split('-').map(Number);
    return hi === undefined ? [lo!] : Array.from({ length: hi - lo! + 1 }, (_, i) => lo! + i);
  });
}

/**
 * An SSE client of the job's stream from `after` on until `stop` resolves: in this process, or
 * (MONITOR_CLIENT=child) in a child process (trace-bench-client.ts); its report.
 */
async function attach(base: string, id: string, after: number, stop: Promise<void>, clientCpus?: string): Promise<ClientReport> {
  if (!CHILD_CLIENT) {
    const abort = new AbortController();
    const following = followTrace(base, id, after, abort.signal);
    await stop;
    abort.abort();
    return following;
  }
  const script = join(dirname(fileURLToPath(import.meta.url)), 'trace-bench-client.js');
  const argv = [process.execPath, script, base, id, String(after)];
  // the partitioned run: the client on the service's CPUs (inherited when in this process)
  const [cmd, ...args] = clientCpus ? ['taskset', '-c', clientCpus, ...argv] : argv;
  const child = spawn(cmd!, args, { stdio: ['ignore', 'pipe', 'inherit'] });
  let out = '';
  child.stdout.setEncoding('utf8').on('data', (d: string) => (out += d));
  const exited = new Promise<number | null>((resolve) => child.on('exit', (code) => resolve(code)));
  await stop;
  child.kill('SIGTERM');
  const code = await exited;
  if (code !== 0) throw new Error(`the SSE client exited with ${code}`);
  return JSON.parse(out) as ClientReport;
}

/** One run's layout: where the modules run, in which mode, and the figures' prefix. */
interface Layout {
  prefix: string;
  label: string;
  /** The job's `cpus` (the modules pinned there); the service keeps off them by itself. */
  cpus?: string;
  /** The CPUs the service should be left on while the run runs (checked; the child client goes there). */
  serviceCpus?: string;
  realtime?: boolean;
  /** The control (A/A): the "with" phases attach no client. */
  control?: boolean;
}

/**
 * The runs of the benchmark: the modules pinned to the last CPU (the set-up of
 * sched.period_jitter_us_p99, docs/engines.md: `monitor.`), every CPU shared (`monitor.shared.`),
 * and every CPU shared with real-time mode (`monitor.shared_realtime.`). A layout the machine
 * cannot have is skipped with why (one CPU, no taskset); MONITOR_LAYOUTS=pinned,shared picks some.
 */
function planLayouts(): (Layout | { prefix: string; skip: string })[] {
  const wanted = (process.env.MONITOR_LAYOUTS ?? 'pinned,shared,shared_realtime,null').split(',');
  const out: (Layout | { prefix: string; skip: string })[] = [];
  const own = ownCpus();
  const pinned = (prefix: string, control: boolean): Layout | { prefix: string; skip: string } => {
    if (!own || own.length < 2) return { prefix, skip: `CPUs ${own?.join(',') ?? 'unknown'}: no CPU to give the modules alone` };
    const modules = String(own.at(-1));
    const service = own.slice(0, -1).join(',');
    const label = `modules pinned to CPU ${modules} (cpus), the service${control ? '' : ' and its client'} on CPU ${service}`;
    return control
      ? { prefix, label: `${label}; the control: no client in either phase`, cpus: modules, serviceCpus: service, control }
      : { prefix, label, cpus: modules, serviceCpus: service };
  };
  // the control in turns with the pinned runs, so that the host is as alike as it can be
  for (let i = 0; i < PINNED_RUNS; i++) {
    if (wanted.includes('pinned')) out.push(pinned('monitor', false));
    if (wanted.includes('null')) out.push(pinned('monitor.null', true));
  }
  if (wanted.includes('shared')) out.push({ prefix: 'monitor.shared', label: 'every CPU shared by the modules, the service and its client' });
  if (wanted.includes('shared_realtime'))
    out.push({ prefix: 'monitor.shared_realtime', label: 'every CPU shared, the modules in real-time mode (SCHED_FIFO)', realtime: true });
  return out;
}

/** One of ORD's releases (ord_release): its tick on CLOCK_MONOTONIC, lateness in us. */
interface Release {
  tick: bigint;
  lateUs: number;
}

interface Phase {
  withClient: boolean;
  pair: number;
  from: bigint;
  to: bigint;
  cpuMs: number;
  /** Of cpuMs, in the kernel (system calls). */
  sysMs: number;
  /** CPU ms of the service's threads in the phase, by thread name (/proc/self/task: main, libuv workers, GC helpers). */
  threads: Map<string, number>;
  /** Records the run wrote in the phase (by mono_ns, from the collected logs). */
  records: number;
  /** Time the hypervisor took from the modules' CPUs in the phase (ms). */
  stealMs: number;
}

/** The template at 1 kHz: PERIOD=1ms, module budgets well inside it. */
const atOneKhz = (text: string): string =>
  text.replace('PERIOD=10ms; CRITICAL_DELAY=10ms;', 'PERIOD=1ms; CRITICAL_DELAY=1ms;').replace('C=500us;', 'C=100us;').replace('C=1ms;', 'C=200us;');

async function main(): Promise<void> {
  const bench = await startBenchServer('contract-monitor-bench-');
  const { url, server } = bench;
  const dir = join(bench.projects, 'khz');
  writeTemplateProject(dir, atOneKhz);
  /** Logs of earlier runs stay in the reused workspace's logs/ (and among the artifacts). */
  const seen = new Set<string>();
  /** One run of `seconds`; `during` runs once the run streams its trace; returns ORD's releases (tick_ns, lateness in us) and the run's logs. */
  const run = async (seconds: number, during: (jobId: string) => Promise<void>, placement: { cpus?: string; realtime?: boolean } = {}): Promise<{ releases: Release[]; logs: Artifact[] }> => {
    const r = await postJob(url, { action: 'run', sandbox: 'bwrap', duration: seconds, project: { dir }, ...(placement.realtime ? { realtime: true } : {}), ...(placement.cpus ? { cpus: placement.cpus } : {}) });
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
    const logs = (job.artifacts?.files ?? []).filter((f) => !seen.has(f.name));
    const ord = logs.find((f) => f.name.startsWith('ORD_'));
    for (const f of logs) seen.add(f.name);
    if (!ord) throw new Error('no new ORD log');
    const releases: Release[] = [];
    artifactBytes(ord).toString('utf8').split('\n').forEach((line, i) => {
      if (!line.includes(',ord_release,')) return;
      const rec = parseRecordLine(ord.name, i + 1, line);
      if (rec.kind !== 'ord_release') return;
      const m = /tick_ns=(\d+) release_ns=(\d+)/.exec(rec.detail);
      if (m) releases.push({ tick: BigInt(m[1]!), lateUs: Number(BigInt(m[2]!) - BigInt(m[1]!)) / 1000 });
    });
    return { releases, logs };
  };
  try {
    say('build + warm-up run (3 s)');
    await run(3, async () => {});
    const phaseMs = PHASE_SECONDS * 1000;
    const seconds = Math.ceil(2 * PAIRS * PHASE_SECONDS + 3);
    /** The pairs of the phases (numbered across a layout's runs). */
    const pairIds = (phases: Phase[]): number[] => [...new Set(phases.map((p) => p.pair))].sort((a, b) => a - b);
    /** The p99 release lateness of each pair's phases with / without the client, and pooled. */
    const jitterOf = (phases: Phase[], releases: Release[]) => {
      const inPhase = (p: Phase): number[] => releases.filter((r) => r.tick >= p.from + SETTLE_NS && r.tick < p.to).map((r) => r.lateUs);
      const ratios: number[] = [];
      for (const pair of pairIds(phases)) {
        const w = phases.find((p) => p.pair === pair && p.withClient)!;
        const wo = phases.find((p) => p.pair === pair && !p.withClient)!;
        ratios.push(pct(inPhase(w), 99) / pct(inPhase(wo), 99));
      }
      const pooled = (withClient: boolean): number[] => phases.filter((p) => p.withClient === withClient).flatMap(inPhase);
      return { ratios, pooled, p99Without: pct(pooled(false), 99), p99With: pct(pooled(true), 99) };
    };
    /** PAIRS pairs of phases without / with a client (ABBA) in the running job. */
    const alternate = async (jobId: string, layout: Layout, clientCpus?: string) => {
      const moduleCpus = layout.cpus ? cpuIds(layout.cpus) : (ownCpus() ?? []);
      const job = server.service.get(jobId)!;
      const got = { phases: [] as Phase[], latency: [] as number[], records: 0, events: 0, clientCpuMs: 0 };
      for (let pair = 0; pair < PAIRS; pair++) {
        const order = pair % 2 === 0 ? [false, true] : [true, false];
        for (const withClient of order) {
          const cpu0 = process.cpuUsage();
          const threads0 = threadCpuMs();
          const steal0 = stealMs();
          const from = process.hrtime.bigint();
          if (withClient && !layout.control) {
            const after = job.events.all.at(-1)?.seq ?? 0;
            const report = await attach(url, jobId, after, sleep(phaseMs), clientCpus);
            got.events += report.events;
            got.records += report.records;
            got.clientCpuMs += report.cpuMs;
            for (const x of report.latencyMs) got.latency.push(x);
          } else await sleep(phaseMs);
          const cpu = process.cpuUsage(cpu0);
          const threads = threadCpuMs();
          for (const [k, v] of threads0) threads.set(k, (threads.get(k) ?? 0) - v);
          const steal = stealMs();
          const stolen = moduleCpus.reduce((a, c) => a + (steal.get(c) ?? 0) - (steal0.get(c) ?? 0), 0);
          got.phases.push({ withClient, pair, from, to: process.hrtime.bigint(), cpuMs: (cpu.user + cpu.system) / 1000, sysMs: cpu.system / 1000, threads, records: 0, stealMs: stolen });
        }
      }
      return got;
    };
    /** Every figure of one layout's run, named `<prefix>.<figure>`. */
    const figuresOf = (prefix: string, control: boolean, got: Awaited<ReturnType<typeof alternate>>, releases: Release[], logs: Artifact[]): Record<string, unknown> => {
      const { phases, latency, records, events, clientCpuMs } = got;
      say(`phases on CLOCK_MONOTONIC (a --cpu-prof profile's clock, in us): ${phases[0]!.from / 1000n}..${phases.at(-1)!.to / 1000n}`);
      // the records written in each phase, by their mono_ns (the clock of the phase boundaries)
      for (const log of logs) {
        for (const line of artifactBytes(log).toString('utf8').split('\n')) {
          const m = /^(\d+),/.exec(line);
          if (!m) continue;
          const mono = BigInt(m[1]!);
          const p = phases.find((q) => mono >= q.from && mono < q.to);
          if (p) p.records++;
        }
      }
      const { ratios, pooled, p99Without, p99With } = jitterOf(phases, releases);
      const stealPairs = pairIds(phases).map((pair) => {
        const of = (w: boolean): number => phases.find((p) => p.pair === pair && p.withClient === w)!.stealMs;
        return of(true) - of(false);
      });
      const steal = ratioAtZero(ratios, stealPairs);
      const seconds = (withClient: boolean): number => phases.filter((p) => p.withClient === withClient).reduce((a, p) => a + Number(p.to - p.from) / 1e9, 0);
      const perS = (withClient: boolean, ms: (p: Phase) => number): number =>
        phases.filter((p) => p.withClient === withClient).reduce((a, p) => a + ms(p), 0) / seconds(withClient);
      const usPerRecord = (withClient: boolean): number => {
        const ps = phases.filter((p) => p.withClient === withClient);
        return (1000 * ps.reduce((a, p) => a + p.cpuMs, 0)) / Math.max(1, ps.reduce((a, p) => a + p.records, 0));
      };
      const threadNames = [...new Set(phases.flatMap((p) => [...p.threads.keys()]))];
      const byThread = (withClient: boolean): Record<string, number> =>
        Object.fromEntries(threadNames.map((n) => [n, round(perS(withClient, (p) => p.threads.get(n) ?? 0), 1)]).filter(([, v]) => (v as number) > 0));
      const figures: Record<string, unknown> = {
        jitter_ratio: round(median(ratios)),
        jitter_ratio_pooled: round(p99With / p99Without),
        jitter_ratio_pairs: ratios.map((x) => round(x)),
        release_lateness_us_p99_without: round(p99Without, 1),
        release_lateness_us_p99_with: round(p99With, 1),
        releases: pooled(true).length + pooled(false).length,
        service_trace_latency_ms_p99: round(pct(latency, 99), 1),
        service_trace_latency_ms_p50: round(pct(latency, 50), 1),
        trace_records: records,
        trace_events_per_s: round(events / seconds(true), 0),
        records_written_per_s: round(phases.reduce((a, p) => a + p.records, 0) / (seconds(true) + seconds(false)), 0),
        service_cpu_ms_per_s_without: round(perS(false, (p) => p.cpuMs), 1),
        service_cpu_ms_per_s_with: round(perS(true, (p) => p.cpuMs), 1),
        service_cpu_us_per_record_without: round(usPerRecord(false), 2),
        service_cpu_us_per_record_with: round(usPerRecord(true), 2),
        service_cpu_sys_ms_per_s_without: round(perS(false, (p) => p.sysMs), 1),
        service_cpu_sys_ms_per_s_with: round(perS(true, (p) => p.sysMs), 1),
        service_cpu_ms_per_s_by_thread_without: byThread(false),
        service_cpu_ms_per_s_by_thread_with: byThread(true),
        ...(CHILD_CLIENT ? { client_cpu_ms_per_s: round(clientCpuMs / seconds(true), 1) } : {}),
        steal_ms_per_s_without: round(perS(false, (p) => p.stealMs), 1),
        steal_ms_per_s_with: round(perS(true, (p) => p.stealMs), 1),
        steal_ms_pairs: stealPairs.map((x) => round(x, 0)),
        ...(steal ? { steal_r: round(steal.r), jitter_ratio_at_equal_steal: round(steal.ratio) } : {}),
      };
      // the control attached no client: it has no client figures
      const clientFigures = ['service_trace_latency_ms_p99', 'service_trace_latency_ms_p50', 'trace_records', 'trace_events_per_s'];
      return Object.fromEntries(Object.entries(figures).filter(([k]) => !control || !clientFigures.includes(k)).map(([k, v]) => [`${prefix}.${k}`, v]));
    };
    const out: Record<string, unknown> = { 'monitor.client': CHILD_CLIENT ? 'child process' : 'in the service process' };
    type Got = Awaited<ReturnType<typeof alternate>>;
    /** Each layout's runs, merged: their phases' pairs numbered on from one run to the next. */
    const byLayout = new Map<string, { layout: Layout; got: Got; releases: Release[]; logs: Artifact[]; runMedians: number[] }>();
    for (const layout of planLayouts()) {
      if ('skip' in layout) {
        if (!(`${layout.prefix}.skipped` in out)) say(`${layout.prefix} skipped: ${layout.skip}`);
        out[`${layout.prefix}.skipped`] = layout.skip;
        continue;
      }
      const merged = byLayout.get(layout.prefix);
      say(`${layout.prefix}: run ${merged ? merged.runMedians.length + 1 : 1} of ${seconds} s, ${layout.label}: ${PAIRS} pairs of ${PHASE_SECONDS} s phases without / with ${layout.control ? 'no client either (the control)' : 'an SSE client on the live trace'} (ABBA)`);
      let got: Got | null = null;
      const { releases, logs } = await run(seconds, async (jobId) => {
        if (layout.serviceCpus) {
          // the service keeps off the run's CPUs by itself (service-affinity.ts): checked, not done here
          const own = ownCpus();
          if (!own || own.join(',') !== cpuIds(layout.serviceCpus).join(',')) throw new Error(`the service runs on CPUs ${own?.join(',')}, not ${layout.serviceCpus}: it did not keep off the run's CPUs`);
        }
        got = await alternate(jobId, layout, CHILD_CLIENT ? layout.serviceCpus : undefined);
      }, { cpus: layout.cpus, realtime: layout.realtime });
      const g = got! as Got;
      const runMedian = median(jitterOf(g.phases, releases).ratios);
      say(`${layout.prefix}: this run's jitter_ratio ${round(runMedian)}`);
      if (!merged) {
        byLayout.set(layout.prefix, { layout, got: g, releases, logs, runMedians: [runMedian] });
        continue;
      }
      const offset = Math.max(...merged.got.phases.map((p) => p.pair)) + 1;
      merged.got.phases.push(...g.phases.map((p) => ({ ...p, pair: p.pair + offset })));
      for (const x of g.latency) merged.got.latency.push(x); // (a spread of 10^5 arguments overflows the stack)
      merged.got.records += g.records;
      merged.got.events += g.events;
      merged.got.clientCpuMs += g.clientCpuMs;
      for (const r of releases) merged.releases.push(r);
      merged.logs.push(...logs);
      merged.runMedians.push(runMedian);
    }
    for (const [prefix, m] of byLayout) {
      Object.assign(out, figuresOf(prefix, !!m.layout.control, m.got, m.releases, m.logs), {
        [`${prefix}.layout`]: m.layout.label,
        [`${prefix}.runs`]: m.runMedians.length,
        ...(m.runMedians.length > 1 ? { [`${prefix}.jitter_ratio_runs`]: m.runMedians.map((x) => round(x)) } : {}),
      });
    }
    say(JSON.stringify(out));
    writePart('monitor', out);
  } finally {
    await bench.close();
  }
}

runBench(say, main);
