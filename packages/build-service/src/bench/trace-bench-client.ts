/**
 * The trace benchmark's SSE client (trace-bench.ts), run as a child process so that the service's
 * CPU time (process.cpuUsage in the bench's process) is the service's only, as it is for the IDE's
 * page or `contract run --monitor`, which run in processes of their own.
 *   node trace-bench-client.js <base url> <job id> <after seq>
 * Follows the job's events until SIGTERM, then prints one JSON line on stdout:
 *   { records, events, latencyMs: number[] (wall_time -> arrival, per record), cpuMs }
 */
import type { TraceEvent } from '../pipeline/job-events.js';
import { streamEvents } from '../test-support/client.js';

async function main(): Promise<void> {
  const [base, id, after] = process.argv.slice(2);
  if (!base || !id) throw new Error('usage: trace-bench-client <base> <job id> [after]');
  const abort = new AbortController();
  let records = 0;
  let events = 0;
  const latencyMs: number[] = [];
  const cpu0 = process.cpuUsage();
  process.on('SIGTERM', () => abort.abort());
  try {
    await streamEvents(base, id, (e) => {
      if (e.type !== 'trace') return;
      const now = Date.now();
      events++;
      for (const l of (e as TraceEvent).records) {
        records++;
        const wall = Date.parse(l.text.split(',', 2)[1] ?? '');
        if (Number.isFinite(wall)) latencyMs.push(now - wall);
      }
    }, Number(after ?? 0), abort.signal);
  } catch (e) {
    if (!abort.signal.aborted) throw e;
  }
  const cpu = process.cpuUsage(cpu0);
  process.stdout.write(JSON.stringify({ records, events, latencyMs, cpuMs: (cpu.user + cpu.system) / 1000 }) + '\n');
}

main().catch((e) => {
  process.stderr.write(`[bench monitor client] FAILED: ${(e as Error).stack ?? e}\n`);
  process.exit(1);
});
