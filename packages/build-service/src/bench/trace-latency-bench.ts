/**
 * Live trace latency by sandbox -> bench/parts/trace-latency.json (docs/build-service-api.md
 * "Trace channel"). The "New project" template (as it is: a 10 ms periodic schema) runs RUN_SECONDS
 * (default 5) in bwrap, then in Docker (skipped, and said so, when no engine and image answer), through
 * the HTTP service, with an SSE client following the job from its start. For every record that
 * reaches the client while the job is `running`:
 * latency = the client's CLOCK_MONOTONIC at the event's arrival (process.hrtime) - the record's
 * mono_ns (the module's CLOCK_MONOTONIC when it logged it: the same clock on this host, for bwrap
 * and for Docker containers alike, which have no time namespace).
 *   trace_latency.<sandbox>_ms_p50 / _p99 / _max   that latency
 *   trace_latency.<sandbox>_records                records measured
 * A build + 1 s warm-up run first in each sandbox; about 30 s in all.
 */
import { join } from 'node:path';
import type { JobStatus } from '../pipeline/job-events.js';
import { DockerSandbox } from '../sandbox/docker.js';
import { postJob, streamEvents } from '../test-support/client.js';
import { monoOf } from '../pipeline/trace-order.js';
import { benchLog, pct, round, runBench, startBenchServer, writePart, writeTemplateProject } from './bench-support.js';

const RUN_SECONDS = Number(process.env.RUN_SECONDS ?? 5);
const say = benchLog('trace-latency');

async function main(): Promise<void> {
  const bench = await startBenchServer('contract-trace-latency-', { log: () => {} });
  const { url } = bench;
  const dir = join(bench.projects, 'template');
  writeTemplateProject(dir);
  const out: Record<string, number | string> = {};
  /** One run followed from its start; the latencies (ms) of the records that came while it was running. */
  const run = async (sandbox: string, seconds: number): Promise<number[]> => {
    const r = await postJob(url, { action: 'run', sandbox, duration: seconds, project: { dir } });
    if (r.status !== 201) throw new Error(`submit: ${JSON.stringify(r.json)}`);
    const id = r.json.id as string;
    let status: JobStatus = 'queued';
    const latency: number[] = [];
    const notes: string[] = [];
    let result: { ok?: boolean; message?: string } | null = null;
    await streamEvents(url, id, (e) => {
      const at = process.hrtime.bigint();
      if (e.type === 'status') status = e.status;
      else if (e.type === 'line' && e.line.startsWith('trace:')) notes.push(e.line);
      else if (e.type === 'end') result = e.result as typeof result;
      else if (e.type === 'trace' && status === 'running') {
        for (const l of e.records) {
          const mono = monoOf(l.text);
          if (mono >= 0n) latency.push(Number(at - mono) / 1e6);
        }
      }
    });
    const res = result as { ok?: boolean; message?: string } | null;
    if (!res?.ok) throw new Error(`${sandbox} run failed: ${res?.message}`);
    for (const n of notes) say(`${sandbox}: ${n}`);
    return latency;
  };
  try {
    const sandboxes = ['bwrap'];
    const probe = await new DockerSandbox({ log: () => {} }).probe();
    if (probe.available) sandboxes.push('docker');
    else {
      say(`docker SKIPPED: ${probe.detail}`);
      out['trace_latency.docker_skipped'] = probe.detail;
    }
    for (const sandbox of sandboxes) {
      say(`${sandbox}: build + warm-up run (1 s)`);
      await run(sandbox, 1);
      say(`${sandbox}: a ${RUN_SECONDS} s run, followed over SSE`);
      const latency = await run(sandbox, RUN_SECONDS);
      out[`trace_latency.${sandbox}_ms_p50`] = round(pct(latency, 50), 1);
      out[`trace_latency.${sandbox}_ms_p99`] = round(pct(latency, 99), 1);
      out[`trace_latency.${sandbox}_ms_max`] = round(Math.max(...latency), 1);
      out[`trace_latency.${sandbox}_records`] = latency.length;
    }
    say(JSON.stringify(out));
    writePart('trace-latency', out);
  } finally {
    await bench.close();
  }
}

runBench(say, main);
