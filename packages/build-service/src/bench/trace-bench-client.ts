/**
 * The trace benchmark's SSE client (trace-bench.ts): follows a job's events and measures each
 * record's latency (its wall_time -> its arrival). In the bench's process (MONITOR_CLIENT=in-process,
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
  /** wall_time -> arrival, per record (ms). */
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
      const now = Date.now();
      report.events++;
      for (const l of (e as TraceEvent).records) {
        report.records++;
        const wall = Date.parse(l.text.split(',', 2)[1] ?? '');
        if (Number.isFinite(wall)) report.latencyMs.push(now - wall);
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
