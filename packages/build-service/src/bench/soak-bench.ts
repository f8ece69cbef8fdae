/**
 * Soak benchmark -> bench/parts/soak.json: the mobile-robot example (about 12 MB of CSV a minute)
 * run for SOAK_SECONDS (default 600) in bwrap through the job service, as `contract run` does, and
 * every CSV record counted (issue 18: long honest runs used to lose whole logs at collection).
 *   soak.seconds           the run's duration
 *   soak.run_ok            1 when the job succeeded with no run issue (run-issues.ts), else 0
 *   soak.issues            its run issues (stuck module, limit, cut output or logs)
 *   soak.records           CSV records collected (headers and log-capped markers not counted)
 *   soak.records_lost      records the modules logged and the collection did not give back: for each
 *                          module, its module_exit `records=K` minus the records collected up to it,
 *                          or the runtime's `log-capped` count; a log without its module_exit counts 1
 *   soak.logs              logs collected; soak.log_mib / soak.log_gzip_mib their size, plain / as kept;
 *                          soak.largest_log_mib the biggest one (the per-file bound is 256 MiB)
 *   soak.collect_ms        the collection (reads + gzip)
 *   soak.rss_growth_kib    module memory: the largest VmRSS growth of a module between the end of the
 *                          warm-up (10 % of the run, at least 10 s) and the last sample (every 5 s)
 *   soak.rss_max_kib       the largest VmRSS of a module
 * Modules are found as the descendants of this process (the sandbox's processes), by the names of
 * their output tags. The runtime is built from a snapshot of runtime/ (concurrent edits do not matter).
 */
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { JobService } from '../job-service.js';
import { artifactBytes } from '../pipeline/artifacts.js';
import { REPO, snapshotRuntime } from '../test-support/tutorial.js';
import { processParents } from '../sandbox/host-process.js';
import { benchLog, round, writePart, runBench } from './bench-support.js';

const say = benchLog('soak');


/** VmRSS (KiB) of the descendants of this process whose name is a module's, by module name. */
function moduleRss(modules: Set<string>): Map<string, number> {
  const ppid = processParents();
  const mine = new Set<number>([process.pid]);
  for (let grew = true; grew; ) {
    grew = false;
    for (const [pid, parent] of ppid) if (!mine.has(pid) && mine.has(parent)) (mine.add(pid), (grew = true));
  }
  const out = new Map<string, number>();
  for (const pid of mine) {
    try {
      const status = readFileSync(`/proc/${pid}/status`, 'utf8');
      const name = /^Name:\s+(\S+)/m.exec(status)?.[1];
      const rss = Number(/^VmRSS:\s+(\d+) kB/m.exec(status)?.[1]);
      if (name && modules.has(name) && rss > 0) out.set(name, rss);
    } catch {
      // gone meanwhile
    }
  }
  return out;
}

/** Records of one collected log and how many of those the module logged are missing. */
function countRecords(text: string): { records: number; lost: number } {
  const lines = text.split('\n').filter((l) => l !== '');
  let records = 0;
  let upToExit = -1;
  let declared = -1;
  let capped = -1;
  for (const line of lines.slice(1)) {
    const capLost = /,log-capped,[^,]*,[^,]*,\d+,(\d+) records not written/.exec(line);
    if (capLost) capped = Number(capLost[1]);
    if (/,log-capped,/.test(line)) continue;
    records++;
    const exit = /,module_exit,,,0,status=-?\d+ records=(\d+)/.exec(line);
    if (exit) (declared = Number(exit[1])), (upToExit = records);
  }
  if (capped >= 0) return { records, lost: capped };
  if (declared < 0) return { records, lost: 1 };
  return { records, lost: Math.max(0, declared - upToExit) };
}

async function main(): Promise<void> {
  const seconds = Number(process.env.SOAK_SECONDS ?? 600);
  if (!(seconds > 0)) throw new Error(`SOAK_SECONDS='${process.env.SOAK_SECONDS}' is not a positive number`);
  const cacheDir = mkdtempSync(join(tmpdir(), 'contract-soak-'));
  const runtimeSource = snapshotRuntime();
  const project = join(REPO, 'examples', 'mobile-robot');
  const service = new JobService({ sandbox: 'bwrap', concurrency: 1, queueSize: 0, projectRoots: [project], cacheDir, runtimeSource, limits: { runSeconds: seconds + 120, buildSeconds: 600 } });
  try {
    say(`mobile-robot for ${seconds} s (SOAK_SECONDS) in bwrap`);
    const job = await service.submit({ action: 'run', sandbox: 'bwrap', project: { dir: project }, duration: seconds });
    const modules = new Set<string>();
    let runningAt = 0;
    job.events.subscribe(0, (e) => {
      if (e.type === 'status' && e.status === 'running') runningAt = Date.now();
      if (e.type === 'line' && e.step === 'run' && !['service', 'launcher', 'run'].includes(e.source)) modules.add(e.source);
    });
    const warmupMs = Math.max(10, seconds * 0.1) * 1000;
    const baseline = new Map<string, number>();
    const last = new Map<string, number>();
    let rssMax = 0;
    const sampler = setInterval(() => {
      if (!runningAt || Date.now() - runningAt > (seconds - 2) * 1000) return;
      const rss = moduleRss(modules);
      for (const [m, kib] of rss) {
        rssMax = Math.max(rssMax, kib);
        if (Date.now() - runningAt >= warmupMs && !baseline.has(m)) baseline.set(m, kib);
        if (baseline.has(m)) last.set(m, kib);
      }
    }, 5000);
    await job.finished;
    clearInterval(sampler);
    const result = job.result!;
    say(`${job.status}: ${result.message}`);
    const files = job.artifacts?.files ?? [];
    let records = 0;
    let lost = 0;
    let bytes = 0;
    let gz = 0;
    let largest = 0;
    for (const f of files) {
      const c = countRecords(artifactBytes(f).toString('utf8'));
      records += c.records;
      lost += c.lost;
      bytes += f.size;
      largest = Math.max(largest, f.size);
      gz += f.gzip.length;
      if (c.lost) say(`${f.name}: ${c.lost} record(s) lost`);
    }
    lost += (job.artifacts?.skipped ?? []).filter((s) => s.bound).length; // whole logs left out: at least one each
    let growth = 0;
    for (const [m, kib] of last) growth = Math.max(growth, kib - baseline.get(m)!);
    const out = {
      'soak.seconds': seconds,
      'soak.run_ok': result.ok ? 1 : 0,
      'soak.issues': result.issues.length,
      'soak.records': records,
      'soak.records_lost': lost,
      'soak.logs': files.length,
      'soak.log_mib': round(bytes / 2 ** 20),
      'soak.log_gzip_mib': round(gz / 2 ** 20),
      'soak.largest_log_mib': round(largest / 2 ** 20),
      'soak.collect_ms': job.artifactsCollectMs ?? -1,
      'soak.rss_growth_kib': last.size ? growth : -1,
      'soak.rss_max_kib': rssMax,
    };
    for (const i of result.issues) say(`issue: ${i.message}`);
    say(`modules sampled: ${[...last.keys()].sort().join(' ') || 'none'}`);
    writePart('soak', out);
    process.stdout.write(JSON.stringify(out, null, 2) + '\n');
  } finally {
    await service.close();
    rmSync(cacheDir, { recursive: true, force: true });
    rmSync(runtimeSource, { recursive: true, force: true });
  }
}

runBench(say, main);
