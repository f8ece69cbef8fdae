#!/usr/bin/env node
// Runs every benchmark of the project and merges their figures into bench/results.json.
//
// Convention: each benchmark is a command that writes one flat JSON object
// (metric name -> number) to bench/parts/<part>.json. This script runs them in order,
// merges the parts, writes bench/results.json and prints a readable table.
// `node bench/run-all.mjs PART...` runs only those parts and merges their figures into the
// existing bench/results.json (the other figures are kept as they were). bench/result-parts.json
// says which metrics each part wrote last time, so that a part run again replaces all of its
// figures (a metric it no longer writes, as a `..._skipped` reason once the thing runs, is dropped).
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync, existsSync, rmSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const partsDir = join(root, 'bench', 'parts');

/** One entry per benchmark: the part file it writes and the command that writes it. */
const benches = [
  { part: 'runtime', cmd: ['make', '-s', '-C', 'runtime', 'bench'] },
  { part: 'engines', cmd: ['make', '-s', '-C', 'runtime', 'bench-engines'] },
  // the engines' 1 kHz schema on the host and in bwrap with real-time mode, alternated, 3 runs each (about 2 min)
  { part: 'sched-sandbox', cmd: ['npm', 'run', '-s', 'bench:rt-sandbox', '-w', 'packages/build-service'] },
  { part: 'language', cmd: ['npm', 'run', '-s', 'bench', '-w', 'packages/language'] },
  { part: 'codegen', cmd: ['npm', 'run', '-s', 'bench', '-w', 'packages/codegen'] },
  { part: 'build', cmd: ['npm', 'run', '-s', 'bench', '-w', 'packages/build-service'] },
  { part: 'ide', cmd: ['npm', 'run', '-s', 'bench', '-w', 'packages/web-ide'] },
  // a 1 kHz schema with and without an SSE client on the live trace channel: pinned and the control (no client) twice in turns, CPUs shared, shared real-time (about 400 s)
  { part: 'monitor', cmd: ['npm', 'run', '-s', 'bench:monitor', '-w', 'packages/build-service'] },
  // record written -> SSE client, bwrap vs Docker (skipped without an engine), a 5 s run each (about 40 s)
  { part: 'trace-latency', cmd: ['npm', 'run', '-s', 'bench:trace-latency', '-w', 'packages/build-service'] },
  // the supervisor simulator: events/s in virtual time, a changed .contract -> first simulated step
  { part: 'simulate', cmd: ['npm', 'run', '-s', 'bench', '-w', 'packages/simulator'] },
  // the edit-build-run loop from the command line: no-op build vs check, one-module edit, cold folder, run overhead
  { part: 'cli', cmd: ['node', 'bench/cli-build-bench.mjs'] },
  // `contract check` of a supervisor whose 300 and 1,000 rules form one endof chain, each subscribing to one port (about 30 s)
  { part: 'check-rules', cmd: ['node', 'bench/cli-check-rules-bench.mjs'] },
  // the end of `contract run --trace` on generated logs of a 60 s run of 50 modules (810,000 records, 73 MiB): CPU of the settling pass, 3 passes (about 40 s)
  { part: 'trace-settle', cmd: ['npm', 'run', '-s', 'bench:trace-settle', '-w', 'packages/cli'] },
  // the Monitor panel fed a 1 kHz schema's trace at the real rate for 60 s (MONITOR_BENCH_SECONDS), then a 60 s recorded run replayed (about 100 s)
  { part: 'monitor-panel', cmd: ['npm', 'run', '-s', 'bench:monitor-panel', '-w', 'packages/web-ide'] },
  // the Monitor's live fold in Node, no browser: a 1 kHz schema's records read in place and folded, and the flow findings' share of it (about 30 s)
  { part: 'monitor-ingest', cmd: ['npm', 'run', '-s', 'bench:monitor-ingest', '-w', 'packages/web-ide'] },
  // a log folder of 90 s of a 1 kHz schema (190 MB) opened in the Monitor: downloaded, decoded and built, frames meanwhile (about 20 s)
  { part: 'monitor-folder', cmd: ['npm', 'run', '-s', 'bench:monitor-folder', '-w', 'packages/web-ide'] },
  // a real Build & Run of a 1 kHz schema, 55 s, watched live in the Monitor: record written -> drawn (about 75 s)
  { part: 'monitor-live', cmd: ['npm', 'run', '-s', 'bench:monitor-live', '-w', 'packages/web-ide'] },
  // a real Build & Run whose module prints 10,000 lines a second for 20 s, the log panel and the Monitor open: frames, long tasks, keys, how far behind the page reads (about 60 s)
  { part: 'log-flood', cmd: ['npm', 'run', '-s', 'bench:log-flood', '-w', 'packages/web-ide'] },
  // the Simulate panel's server side: POST /api/simulate of a growing session, cold then per step (about 15 s)
  { part: 'simulate-panel', cmd: ['npm', 'run', '-s', 'bench:simulate-panel', '-w', 'packages/web-ide'] },
  // 10 minutes of the mobile-robot example, every CSV record counted (SOAK_SECONDS to change it)
  { part: 'soak', cmd: ['npm', 'run', '-s', 'bench:soak', '-w', 'packages/build-service'] },
  // a cancel under 8 concurrent runs of mobile-robot 30 s in (cancel -> processes ended -> logs collected -> job ended), and of a launcher that ignores SIGTERM (about 3 min)
  { part: 'cancel', cmd: ['npm', 'run', '-s', 'bench:cancel', '-w', 'packages/build-service'] },
];

const only = process.argv.slice(2);
mkdirSync(partsDir, { recursive: true });
const resultsFile = join(root, 'bench', 'results.json');
const partsFile = join(root, 'bench', 'result-parts.json');
const results = only.length && existsSync(resultsFile) ? JSON.parse(readFileSync(resultsFile, 'utf8')) : {};
/** part -> the metrics it wrote when it last ran. */
const partKeys = only.length && existsSync(partsFile) ? JSON.parse(readFileSync(partsFile, 'utf8')) : {};
const failures = [];
for (const b of benches) {
  if (only.length && !only.includes(b.part)) continue;
  const file = join(partsDir, `${b.part}.json`);
  if (existsSync(file)) rmSync(file);
  const t0 = Date.now();
  process.stderr.write(`[bench] ${b.part}: ${b.cmd.join(' ')}\n`);
  const r = spawnSync(b.cmd[0], b.cmd.slice(1), { cwd: root, stdio: ['ignore', 'inherit', 'inherit'] });
  const secs = ((Date.now() - t0) / 1000).toFixed(1);
  if (r.status !== 0 || !existsSync(file)) {
    failures.push(`${b.part} (exit ${r.status}, ${secs} s${existsSync(file) ? '' : ', no ' + file})`);
    continue;
  }
  const figures = JSON.parse(readFileSync(file, 'utf8'));
  for (const k of partKeys[b.part] ?? []) if (!(k in figures)) delete results[k];
  partKeys[b.part] = Object.keys(figures);
  Object.assign(results, figures);
  process.stderr.write(`[bench] ${b.part}: done in ${secs} s\n`);
}
writeFileSync(resultsFile, JSON.stringify(results, null, 2) + '\n');
writeFileSync(partsFile, JSON.stringify(partKeys, null, 2) + '\n');
const width = Math.max(10, ...Object.keys(results).map((k) => k.length));
console.log(`${'metric'.padEnd(width)}  value`);
for (const [k, v] of Object.entries(results)) console.log(`${k.padEnd(width)}  ${v}`);
if (failures.length) {
  console.error(`\n[bench] FAILED: ${failures.join('; ')}`);
  process.exit(1);
}
