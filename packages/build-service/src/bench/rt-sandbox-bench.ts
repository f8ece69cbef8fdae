/**
 * Real-time mode benchmark -> bench/parts/sched-sandbox.json (docs/engines.md "Real-time mode in
 * the sandbox"): the engines benchmark's 1 kHz schema (ORD + BSU + BMA/BMB/BMC, built by
 * runtime/engines.mk) run by contract-launch on the host and in the bwrap sandbox with real-time
 * mode (BwrapSandbox.start, as a `contract run --realtime` job's run step), alternated in the same
 * benchmark run, same placement (`--cpus` = the last CPU, as the engines benchmark), RT_BENCH_RUNS
 * (6) runs of RT_BENCH_SECONDS each way; the median run counts, not one disturbed by a host stall.
 *   sched.host_rt.period_jitter_us_p99   median over the host runs of ORD's release lateness p99
 *   sched.host_rt.missed_periods         their overruns + missed ticks, summed
 *   sched.bwrap_rt.period_jitter_us_p99  the same in bwrap with real-time mode
 *   sched.bwrap_rt.missed_periods
 *   sched.bwrap_rt_jitter_ratio          bwrap p99 / host p99 (goal <= 1.2)
 */
import { spawn, spawnSync } from 'node:child_process';
import { chownSync, copyFileSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { cpus, tmpdir } from 'node:os';
import { join } from 'node:path';
import { DEFAULT_LIMITS, REALTIME_BOUNDS } from '../limits.js';
import { BwrapSandbox } from '../sandbox/bwrap.js';
import { REPO } from '../test-support/tutorial.js';
import { benchLog, median, round, writePart, runBench } from './bench-support.js';

const say = benchLog('rt-sandbox');
const RUNS = Number(process.env.RT_BENCH_RUNS ?? 6);
const SECONDS = process.env.RT_BENCH_SECONDS ?? '10.2';
const MODULES = ['ORD', 'BSU', 'BMA', 'BMB', 'BMC'];
const RUNTIME = join(REPO, 'runtime');
const BENCH_BIN = join(RUNTIME, 'build', 'engines', 'bench');
/** A host uid of its own for the sandboxed run (as a workspace gets one when the service is root). */
const BENCH_UID = 100_999;

interface OrdStats {
  p99: number;
  missed: number;
}

function readStats(file: string): OrdStats {
  const js = JSON.parse(readFileSync(file, 'utf8')) as Record<string, number>;
  return { p99: js.release_late_us_p99!, missed: (js.overruns ?? 0) + (js.missed_ticks ?? 0) };
}

function launchArgs(bin: string, work: string, cpu: number): string[] {
  return ['--run-dir', join(work, 'run'), '--log-dir', join(work, 'logs'), '--start', 'BSU.run()', '--duration', SECONDS, '--cpus', String(cpu), ...MODULES.map((m) => join(bin, m))];
}

async function hostRun(cpu: number): Promise<OrdStats> {
  const work = mkdtempSync(join(tmpdir(), 'contract-rt-bench-host-'));
  try {
    const stats = join(work, 'ord.json');
    const child = spawn(join(RUNTIME, 'build', 'contract-launch'), launchArgs(BENCH_BIN, work, cpu), {
      env: { ...process.env, CONTRACT_ORD_STATS: stats, CONTRACT_LOG_DIR: join(work, 'logs') },
      stdio: ['ignore', 'ignore', 'pipe'],
    });
    let err = '';
    child.stderr!.on('data', (d: Buffer) => (err += String(d)));
    const code = await new Promise<number | null>((r) => child.on('exit', r));
    if (code !== 0) throw new Error(`host run: contract-launch exit ${code}\n${err.slice(-2000)}`);
    return readStats(stats);
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
}

async function bwrapRun(sandbox: BwrapSandbox, cpu: number): Promise<OrdStats> {
  const work = mkdtempSync(join(tmpdir(), 'contract-rt-bench-bwrap-'));
  const asRoot = process.getuid?.() === 0;
  try {
    mkdirSync(join(work, 'bin'));
    for (const m of MODULES) copyFileSync(join(BENCH_BIN, m), join(work, 'bin', m));
    copyFileSync(join(RUNTIME, 'build', 'contract-launch'), join(work, 'bin', 'contract-launch'));
    if (asRoot) for (const p of [work, join(work, 'bin'), ...readdirSync(join(work, 'bin')).map((f) => join(work, 'bin', f))]) chownSync(p, BENCH_UID, BENCH_UID);
    const proc = await sandbox.start({
      name: `rt-bench-${process.pid}-${Date.now()}`,
      workDir: work,
      cwd: '',
      argv: ['/work/bin/contract-launch', ...launchArgs('/work/bin', '/work', cpu)],
      env: { CONTRACT_ORD_STATS: '/work/ord.json', CONTRACT_LOG_DIR: '/work/logs' },
      limits: { ...DEFAULT_LIMITS },
      ...(asRoot ? { owner: { uid: BENCH_UID, gid: BENCH_UID } } : {}),
      realtime: true,
    });
    let err = '';
    proc.stderr.on('data', (d: Buffer) => (err += String(d)));
    proc.stdout.resume();
    const exit = await proc.done;
    if (exit.exitCode !== 0) throw new Error(`bwrap run: exit ${exit.exitCode} ${exit.signal ?? ''}\n${err.slice(-2000)}`);
    if (/SCHED_FIFO not permitted/.test(err)) throw new Error(`bwrap run: a module did not get SCHED_FIFO:\n${err.slice(-2000)}`);
    return readStats(join(work, 'ord.json'));
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
}

async function main(): Promise<void> {
  const make = spawnSync('make', ['-s', '-C', RUNTIME, 'build/contract-launch', ...MODULES.map((m) => `build/engines/bench/${m}`)], { stdio: 'inherit' });
  if (make.status !== 0) throw new Error('building the engines bench modules failed');
  const sandbox = new BwrapSandbox();
  const support = await sandbox.realtimeSupport();
  if (!support.ok) throw new Error(`real-time mode refused on this host: ${support.reason}`);
  say(`real-time mode: ${support.detail} (bounds: ${JSON.stringify(REALTIME_BOUNDS)})`);
  const cpu = cpus().length - 1;
  const host: OrdStats[] = [];
  const bwrap: OrdStats[] = [];
  for (let i = 0; i < RUNS; i++) {
    host.push(await hostRun(cpu));
    say(`host run ${i + 1}: p99 ${host.at(-1)!.p99} us, ${host.at(-1)!.missed} missed`);
    bwrap.push(await bwrapRun(sandbox, cpu));
    say(`bwrap --realtime run ${i + 1}: p99 ${bwrap.at(-1)!.p99} us, ${bwrap.at(-1)!.missed} missed`);
  }
  const medianP99 = (xs: OrdStats[]) => median(xs.map((s) => s.p99));
  const sum = (xs: OrdStats[]) => xs.reduce((a, s) => a + s.missed, 0);
  const out = {
    'sched.host_rt.period_jitter_us_p99': round(medianP99(host)),
    'sched.host_rt.missed_periods': sum(host),
    'sched.bwrap_rt.period_jitter_us_p99': round(medianP99(bwrap)),
    'sched.bwrap_rt.missed_periods': sum(bwrap),
    'sched.bwrap_rt_jitter_ratio': round(medianP99(bwrap) / medianP99(host)),
  };
  writePart('sched-sandbox', out);
  say(JSON.stringify(out));
}

runBench(say, main);
