#!/usr/bin/env node
// Simulate panel benchmark -> bench/parts/simulate-panel.json (flat metric -> number).
//
// What one click of the Simulate panel costs on the server (docs/simulation.md "In the IDE"): the
// real IDE server (dist-server) on a copy of examples/tutorial, POST /api/simulate of a session
// grown one event at a time, as the panel sends it (each request re-runs the whole session).
// - simulate_panel.first_ms: the first request with an empty harness cache (load, check,
//   generate the tables, compile and link the harness, run);
// - simulate_panel.step_median_ms / step_p95_ms: the next 30 requests (harness cached), each
//   session one MAA:2 event longer; goal: well under a second;
// - simulate_panel.run_median_ms: the harness run alone inside them.
import { cpSync, mkdirSync, mkdtempSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';

const pkg = fileURLToPath(new URL('..', import.meta.url));
const base = realpathSync(mkdtempSync(join(tmpdir(), 'simulate-panel-bench-')));
process.env.CONTRACT_CACHE_DIR = join(base, 'cache'); // a cold harness for the first request
const { startIdeServer } = await import(join(pkg, 'dist-server/index.js'));
const ws = join(base, 'tutorial');
cpSync(join(pkg, '../../examples/tutorial'), ws, { recursive: true, filter: (src) => !/[\/]logs$/.test(src) });
const ide = await startIdeServer({ workspace: ws, port: 0, buildService: false, distDir: join(base, 'no-dist') });

async function post(scenario) {
  const t0 = performance.now();
  const res = await fetch(`${ide.url}/api/simulate`, {
    method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': ide.token }, body: JSON.stringify({ scenario }),
  });
  const json = await res.json();
  if (res.status !== 200 || !json.passed) throw new Error(`POST /api/simulate: ${res.status} ${JSON.stringify(json).slice(0, 300)}`);
  return { ms: performance.now() - t0, runMs: json.runMs };
}

const head = 'scenario bench\nuntil 1s\nstart SUP.action(consigne = {1.0, 2.0, 3.0})\n';
const values = ['"disconnected"', '"connected"'];
try {
  const first = await post(head);
  const steps = [];
  let text = head;
  for (let i = 1; i <= 30; i++) {
    text += `t=${i}ms MAA:2 connection_status = ${values[i % 2]}\n`;
    steps.push(await post(text));
  }
  const q = (xs, p) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(p * xs.length))];
  const out = {
    'simulate_panel.first_ms': Math.round(first.ms),
    'simulate_panel.step_median_ms': Math.round(q(steps.map((s) => s.ms), 0.5)),
    'simulate_panel.step_p95_ms': Math.round(q(steps.map((s) => s.ms), 0.95)),
    'simulate_panel.run_median_ms': Math.round(q(steps.map((s) => s.runMs), 0.5)),
  };
  const parts = join(pkg, '../../bench/parts');
  mkdirSync(parts, { recursive: true });
  writeFileSync(join(parts, 'simulate-panel.json'), JSON.stringify(out, null, 2) + '\n');
  console.log(out);
} finally {
  await ide.close();
  rmSync(base, { recursive: true, force: true });
}
