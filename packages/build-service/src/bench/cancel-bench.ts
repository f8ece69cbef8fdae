/**
 * Cancel benchmark -> bench/parts/cancel.json: CANCEL_JOBS (default 8) runs of an example
 * (CANCEL_EXAMPLE: mobile-robot, the default, or tutorial) at once
 * in bwrap through the job service (concurrency CANCEL_JOBS), each in its own copy of the project;
 * once every one runs its architecture, each is cancelled in turn, one at a time, while the others
 * keep running (CANCEL_AFTER_SECONDS after they started, default 30), and the time from the cancel to the job's end is measured (docs/build-service-api.md
 * "DELETE /api/jobs/:id": within CANCEL_DEADLINE_MS). The cancelled job's lines after the cancel
 * are printed with their times, so that where the time goes can be read.
 *   cancel.jobs            the jobs running when the first cancel comes
 *   cancel.ms_max          the longest cancel -> end
 *   cancel.ms_p50          the median
 *   cancel.stopped_ms_max  the longest cancel -> every process of the sandbox ended (`run: cancelled`)
 *   cancel.collect_ms_max  the longest collection of the cancelled run's logs, which comes after
 *   cancel.hung_launcher_ms cancel -> end of a run whose launcher ignores SIGTERM (killed after the grace)
 *   cancel.over_deadline   cancels that took CANCEL_DEADLINE_MS or more to the job's end
 */
import { chmodSync, cpSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { JobService } from '../job-service.js';
import { CANCEL_DEADLINE_MS } from '../limits.js';
import type { Job } from '../pipeline/job.js';
import type { JobEvent } from '../pipeline/job-events.js';
import { infiniteLoop, makeProject } from '../test-support/c-projects.js';
import { REPO, snapshotRuntime } from '../test-support/tutorial.js';
import { benchLog, median, writePart, runBench } from './bench-support.js';

const say = benchLog('cancel');

/** Resolves when `job` has begun its run step. */
function running(job: Job): Promise<void> {
  return new Promise((resolve, reject) => {
    job.events.subscribe(0, (e: JobEvent) => {
      if (e.type === 'status' && e.status === 'running') resolve();
      if (e.type === 'end') reject(new Error(`job ${job.id} ended before its run: ${job.result?.message}`));
    });
  });
}

async function main(): Promise<void> {
  const jobs = Number(process.env.CANCEL_JOBS ?? 8);
  // the example run (tutorial, or mobile-robot: about 12 MB of CSV a minute), and how long the runs go before the cancels
  const example = join(REPO, 'examples', process.env.CANCEL_EXAMPLE ?? 'mobile-robot');
  const runFor = Number(process.env.CANCEL_AFTER_SECONDS ?? 30);
  const scratch = mkdtempSync(join(tmpdir(), 'contract-cancel-bench-'));
  chmodSync(scratch, 0o711); // the sandbox's own uids reach the cache inside
  const runtimeSource = snapshotRuntime();
  const projects = Array.from({ length: jobs }, (_, i) => {
    const dir = join(scratch, `robot-${i}`);
    cpSync(example, dir, { recursive: true });
    return dir;
  });
  const service = new JobService({ sandbox: 'bwrap', concurrency: jobs, queueSize: 0, projectRoots: [scratch], cacheDir: join(scratch, 'cache'), runtimeSource, limits: { runSeconds: 300 } });
  try {
    // built one at a time first (the runtime once), so that the runs start together
    for (const dir of projects) {
      const b = await service.submit({ action: 'build', sandbox: 'bwrap', project: { dir } });
      await b.finished;
      if (b.status !== 'succeeded') {
        b.events.subscribe(0, (e: JobEvent) => void (e.type === 'line' && say(`  ${e.source}: ${e.line}`)));
        throw new Error(`build of ${dir}: ${b.result?.message}`);
      }
    }
    say(`${jobs} builds done; starting ${jobs} runs`);
    const started = await Promise.all(projects.map((dir) => service.submit({ action: 'run', sandbox: 'bwrap', project: { dir }, duration: 240 })));
    await Promise.all(started.map(running));
    say(`${jobs} runs under way`);
    await new Promise((r) => setTimeout(r, runFor * 1000)); // every architecture started, logging
    const times: number[] = [];
    /** cancel -> the sandbox's processes all ended (the service's `run: cancelled` line), before the logs' collection */
    const stopped: number[] = [];
    const collect: number[] = [];
    for (const job of started) {
      const t0 = Date.now();
      const after: string[] = [];
      job.events.subscribe(0, (e: JobEvent) => {
        if (e.t >= t0 && e.type === 'line' && e.source === 'service' && /^run: cancelled/.test(e.line)) stopped.push(e.t - t0);
        const collected = e.type === 'line' && e.t >= t0 ? /^collected \d+ artifact\(s\) in (\d+) ms/.exec(e.line) : null;
        if (collected) collect.push(Number(collected[1]));
        if (e.t >= t0 && e.type === 'line') after.push(`+${e.t - t0} ms ${e.source}: ${e.line}`);
        if (e.t >= t0 && e.type === 'status') after.push(`+${e.t - t0} ms status ${e.status}`);
      });
      await service.cancel(job.id);
      await job.finished;
      const ms = Date.now() - t0;
      times.push(ms);
      say(`cancel of ${job.id} (${started.length - times.length + 1} running): ${ms} ms, ${job.status}`);
      for (const l of after) say(`  ${l}`);
    }
    // the worst case: an architecture whose launcher ignores SIGTERM (asked, then killed after the
    // grace), cancelled while jobs - 1 runs of the tutorial go on
    say(`${jobs - 1} runs and one whose launcher ignores SIGTERM`);
    const others = await Promise.all(projects.slice(1).map((dir) => service.submit({ action: 'run', sandbox: 'bwrap', project: { dir }, duration: 240 })));
    const files = makeProject(infiniteLoop);
    files.Makefile = `all:\n\ttrue\nrun:\n\tcp /bin/sh ./contract-launch && exec ./contract-launch -c 'trap "" TERM; echo looping; while :; do sleep 1; done'\n`;
    const hung = await service.submit({ action: 'run', kind: 'make', sandbox: 'bwrap', project: { files } });
    await Promise.all([...others, hung].map(running));
    await new Promise((r) => setTimeout(r, 5000));
    const hungMs: number[] = [];
    {
      const t0 = Date.now();
      const after: string[] = [];
      hung.events.subscribe(0, (e: JobEvent) => {
        if (e.t >= t0 && e.type === 'line') after.push(`+${e.t - t0} ms ${e.source}: ${e.line}`);
        if (e.t >= t0 && e.type === 'status') after.push(`+${e.t - t0} ms status ${e.status}`);
      });
      await service.cancel(hung.id);
      await hung.finished;
      hungMs.push(Date.now() - t0);
      say(`cancel of the launcher that ignores SIGTERM (${jobs} running): ${hungMs[0]} ms, ${hung.status}`);
      for (const l of after) say(`  ${l}`);
    }
    await Promise.all(others.map((j) => service.cancel(j.id)));
    await Promise.all(others.map((j) => j.finished));
    const out = {
      'cancel.hung_launcher_ms': hungMs[0],
      'cancel.jobs': jobs,
      'cancel.ms_max': Math.max(...times),
      'cancel.ms_p50': median(times),
      'cancel.stopped_ms_max': Math.max(...stopped),
      'cancel.collect_ms_max': Math.max(...collect),
      'cancel.over_deadline': [...times, ...hungMs].filter((t) => t >= CANCEL_DEADLINE_MS).length,
    };
    say(JSON.stringify(out));
    writePart('cancel', out);
  } finally {
    await service.close();
    rmSync(scratch, { recursive: true, force: true });
    rmSync(runtimeSource, { recursive: true, force: true });
  }
}

runBench(say, main);
