/**
 * Build service benchmark -> bench/parts/build.json (flat metric -> number):
 *   build.cold_s.<sandbox>        tutorial: submit -> built, fresh workspace (generation + full make)
 *   build.noop_s.<sandbox>        the same build again (nothing changed): target < 1 s
 *   build.sandbox_overhead_ratio  make step of the same clean tutorial build, bwrap / none (best of 5 each,
 *                                 alternated: the least disturbed run on a shared machine)
 *   artifacts.collect_ms.<sandbox>  tutorial run of 1 s: copying its 9 CSV logs out of the sandbox
 *                                 (host no-follow reads; docker: archive API of the volume)
 *   stream.latency_ms_p50         a module's printf (its CLOCK_REALTIME stamp) -> SSE client, median
 * The runtime is built once beforehand (it is a per-machine cache, not a per-build cost) from a
 * snapshot of runtime/, so concurrent edits of the runtime do not disturb the figures.
 * Sandboxes that are unavailable here are left out (and said so on stderr).
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { createBuildServer, type BuildServer } from '../server.js';
import type { SandboxName } from '../sandbox/types.js';
import { getJob, postJob, readEvents } from '../test-support/client.js';
import { benchLog, median, round, writePart, runBench } from './bench-support.js';
import { dockerUp } from '../test-support/docker-env.js';
import { MAA_MODULE, snapshotRuntime, TUTORIAL_DIR, tutorialFiles, withRegion } from '../test-support/tutorial.js';

const say = benchLog('build');

async function timedJob(url: string, body: Record<string, unknown>): Promise<{ seconds: number; job: Record<string, any> }> {
  const t0 = performance.now();
  const r = await postJob(url, body);
  if (r.status !== 201) throw new Error(`POST /api/jobs: ${r.status} ${JSON.stringify(r.json)}`);
  await readEvents(url, r.json.id as string);
  const seconds = (performance.now() - t0) / 1000;
  const job = await getJob(url, r.json.id as string);
  if (job.status !== 'succeeded') throw new Error(`job ${job.id} ${job.status}: ${job.result?.message}`);
  return { seconds, job };
}

async function withServer<T>(cacheDir: string, runtimeSource: string, fn: (url: string, s: BuildServer) => Promise<T>): Promise<T> {
  const server = createBuildServer({ token: false, allowNoneSandbox: true, port: 0, concurrency: 1, cacheDir, runtimeSource, projectRoots: [join(TUTORIAL_DIR, '..')] });
  const { url } = await server.listen();
  try {
    return await fn(url, server);
  } finally {
    await server.close();
  }
}

async function main(): Promise<void> {
  const out: Record<string, number> = {};
  const cacheDir = mkdtempSync(join(tmpdir(), 'contract-bench-'));
  const runtimeSource = snapshotRuntime();
  const docker = dockerUp();
  try {
    const sandboxes: SandboxName[] = ['none', 'bwrap', ...(docker.available ? (['docker'] as const) : [])];
    if (!docker.available) say(`docker left out: ${docker.reason}`);
    const files = await tutorialFiles();
    // warm-up: builds the runtime cache and loads the language packages once
    await withServer(cacheDir, runtimeSource, (url) => timedJob(url, { action: 'build', sandbox: 'none', project: { files } }));

    for (const sandbox of sandboxes) {
      await withServer(cacheDir, runtimeSource, async (url) => {
        const cold = await timedJob(url, { action: 'build', sandbox, project: { dir: TUTORIAL_DIR } });
        const noop = await timedJob(url, { action: 'build', sandbox, project: { dir: TUTORIAL_DIR } });
        out[`build.cold_s.${sandbox}`] = round(cold.seconds);
        out[`build.noop_s.${sandbox}`] = round(noop.seconds);
        say(`${sandbox}: cold ${cold.seconds.toFixed(2)} s (make ${cold.job.result.durations_ms.build} ms), no-op ${noop.seconds.toFixed(2)} s`);
        const run = await timedJob(url, { action: 'run', sandbox, duration: 1, project: { dir: TUTORIAL_DIR } });
        const files = run.job.artifacts?.files?.length ?? 0;
        if (files < 9) throw new Error(`${sandbox}: the run's logs were not collected (${files} file(s))`);
        out[`artifacts.collect_ms.${sandbox}`] = run.job.artifacts.collect_ms as number;
        say(`${sandbox}: ${files} CSV logs collected in ${run.job.artifacts.collect_ms} ms`);
      });
    }

    const makeMs: Record<string, number[]> = { none: [], bwrap: [] };
    await withServer(cacheDir, runtimeSource, async (url) => {
      for (let i = 0; i < 5; i++) {
        for (const sandbox of ['none', 'bwrap'] as const) {
          const { job } = await timedJob(url, { action: 'build', sandbox, project: { files } });
          makeMs[sandbox]!.push(job.result.durations_ms.build as number);
        }
      }
    });
    out['build.sandbox_overhead_ratio'] = round(Math.min(...makeMs.bwrap!) / Math.min(...makeMs.none!));
    say(`make step: none ${makeMs.none!.join('/')} ms, bwrap ${makeMs.bwrap!.join('/')} ms`);

    // latency: MAA prints 200 lines stamped with CLOCK_REALTIME (us) at start-up, 5 ms apart
    const stamped = withRegion(
      withRegion(files, MAA_MODULE, 'protect_additional_import_MAA', '#include <time.h>\n#include <unistd.h>\n#include <stdio.h>', true),
      MAA_MODULE,
      'protect_init_MAA',
      '    for (int i = 0; i < 200; i++) { struct timespec ts; clock_gettime(CLOCK_REALTIME, &ts); printf("LATENCY %lld\\n", (long long)ts.tv_sec * 1000000LL + ts.tv_nsec / 1000); fflush(stdout); usleep(5000); }\n    return 1;',
    );
    await withServer(cacheDir, runtimeSource, async (url) => {
      const r = await postJob(url, { action: 'run', sandbox: 'bwrap', duration: 4, project: { files: stamped } });
      const lat: number[] = [];
      await readEvents(url, r.json.id as string, (e) => {
        if (e.type === 'line' && e.source === 'MAA') {
          const m = /^LATENCY (\d+)$/.exec(e.line);
          // sub-millisecond wall clock (Date.now() truncates to whole ms)
          if (m) lat.push(performance.timeOrigin + performance.now() - Number(m[1]) / 1000);
        }
      });
      if (lat.length < 100) throw new Error(`latency: only ${lat.length} stamped lines arrived`);
      out['stream.latency_ms_p50'] = round(median(lat), 2);
      say(`latency over ${lat.length} lines: p50 ${median(lat).toFixed(2)} ms, max ${Math.max(...lat).toFixed(1)} ms`);
    });
  } finally {
    rmSync(cacheDir, { recursive: true, force: true });
    rmSync(runtimeSource, { recursive: true, force: true });
    docker.stop();
  }
  writePart('build', out);
  console.log(JSON.stringify(out, null, 2));
}

runBench(say, main);
