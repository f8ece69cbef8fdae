#!/usr/bin/env node
// The end of `contract run --trace` on a long run: settleTraceFile's pass over the saved CSV logs
// (streamed, merged in time order, each record a JSON line, hashed) on generated logs of a 60 s
// run of 50 modules (synthetic-logs.mjs: about 810,000 records, 73 MiB, 177 MB of JSON). Each
// pass runs in a process of its own; CPU time (user + system), not wall time: the machine is
// shared. Writes bench/parts/trace-settle.json:
//   cli.trace_settle_cpu_s            median CPU seconds of a pass (TRACE_SETTLE_RUNS passes, 3 by default)
//   cli.trace_settle_records_per_s    records / that median
//   cli.trace_settle_records          records of the generated logs
//   cli.trace_settle_log_mib          their size
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { writeSyntheticLogs } from './synthetic-logs.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const repo = join(here, '..', '..', '..');

if (process.argv[2] === '--pass') {
  // one pass, in this process: what settleTraceFile does when the digests agree
  const { createHash } = await import('node:crypto');
  const { jsonLinesOf, openLogFolder, closeLogs } = await import('../dist/trace-stream.js');
  const t0 = process.cpuUsage();
  const logs = await openLogFolder(process.argv[3]);
  if (typeof logs === 'string') throw new Error(logs);
  const hash = createHash('sha256');
  const { counts } = await jsonLinesOf(logs, (piece) => void hash.update(piece));
  await closeLogs(logs);
  const cpu = process.cpuUsage(t0);
  console.log(JSON.stringify({ cpu_s: (cpu.user + cpu.system) / 1e6, records: counts.records + counts.unreadable, digest: hash.digest('hex') }));
} else {
  const runs = Number(process.env.TRACE_SETTLE_RUNS ?? 3);
  const dir = mkdtempSync(join(tmpdir(), 'contract-trace-settle-bench-'));
  try {
    const made = writeSyntheticLogs(dir);
    const passes = [];
    for (let i = 0; i < runs; i++) {
      const r = spawnSync(process.execPath, [fileURLToPath(import.meta.url), '--pass', dir], { encoding: 'utf8' });
      if (r.status !== 0) throw new Error(`pass ${i + 1}: exit ${r.status}\n${r.stderr.slice(-2000)}`);
      passes.push(JSON.parse(r.stdout));
      process.stderr.write(`[trace-settle] pass ${i + 1}: ${passes[i].cpu_s.toFixed(2)} s CPU\n`);
    }
    if (new Set(passes.map((p) => p.digest)).size !== 1 || passes[0].records !== made.records) throw new Error(`passes disagree: ${JSON.stringify(passes)} (${made.records} records written)`);
    const cpu = [...passes.map((p) => p.cpu_s)].sort((a, b) => a - b)[Math.floor(passes.length / 2)];
    const out = {
      'cli.trace_settle_cpu_s': Math.round(cpu * 100) / 100,
      'cli.trace_settle_records_per_s': Math.round(made.records / cpu),
      'cli.trace_settle_records': made.records,
      'cli.trace_settle_log_mib': Math.round((made.bytes / 1048576) * 10) / 10,
    };
    mkdirSync(join(repo, 'bench', 'parts'), { recursive: true });
    writeFileSync(join(repo, 'bench', 'parts', 'trace-settle.json'), JSON.stringify(out, null, 2) + '\n');
    console.log(JSON.stringify(out, null, 2));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}
