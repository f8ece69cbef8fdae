/**
 * The trace benchmark's SSE client (trace-bench.ts): follows a job's events and measures each
 * record's latency (its mono_ns -> its arrival, on CLOCK_MONOTONIC). In the bench's process (MONITOR_CLIENT=in-process,
 * the default) or as a child process of its own (MONITOR_CLIENT=child), so that the service's CPU
 * time (process.cpuUsage in the bench's process) is the service's only, as it is for the IDE's page
 * or `contract run --monitor`, which run in processes of their own:
 *   node trace-bench-client.js <base url> <job id> <after seq>
 * follows the job's events until SIGTERM, then prints its ClientReport as one JSON line on stdout.
 */
import { pathToFileURL } from 'node:url';
import type { TraceEvent } from '../pipeline/job-events.js';
import { streamEvents } from '../test-support/client.js';

export interface ClientReport {
  records: number;
  events: number;
  /** mono_ns -> arrival, per record (ms). */
  latencyMs: number[];
  /** The client's CPU time (ms): its process's when a child, NaN in-process. */
  cpuMs: number;
}

/** Follows the job's events from `after` until `signal` aborts. */
export async function followTrace(base: string, id: string, after: number, signal: AbortSignal): Promise<ClientReport> {
  const report: ClientReport = { records: 0, events: 0, latencyMs: [], cpuMs: NaN };
  try {
    await streamEvents(base, id, (e) => {
      if (e.type !== 'trace') return;
      // the record's mono_ns (its first column: CLOCK_MONOTONIC, as process.hrtime in bwrap and
      // none) -> its arrival: read without parsing its wall_time, so that the measuring costs the
      // client little beside the decoding every client does
      const now = Number(process.hrtime.bigint()) / 1e6;
      report.events++;
      for (const l of (e as TraceEvent).records) {
        report.records++;
        const mono = Number(l.text.slice(0, l.text.indexOf(','))) / 1e6;
        if (mono > 0) report.latencyMs.push(now - mono);
      }
    }, after, signal);
  } catch (e) {
    if (!signal.aborted) throw e;
  }
  return report;
}

async function main(): Promise<void> {
  const [base, id, after] = process.argv.slice(2);
  if (!base || !id) throw new Error('usage: trace-bench-client <base> <job id> [after]');
  const abort = new AbortController();
  const cpu0 = process.cpuUsage();
  process.on('SIGTERM', () => abort.abort());
  const report = await followTrace(base, id, Number(after ?? 0), abort.signal);
  const cpu = process.cpuUsage(cpu0);
  report.cpuMs = (cpu.user + cpu.system) / 1000;
  process.stdout.write(JSON.stringify(report) + '\n');
}

if (process.argv[1] && import.meta.url === pathToFileURL(process.argv[1]).href) {
  main().catch((e) => {
    process.stderr.write(`[bench monitor client] FAILED: ${(e as Error).stack ?? e}\n`);
    process.exit(1);
  });
}
