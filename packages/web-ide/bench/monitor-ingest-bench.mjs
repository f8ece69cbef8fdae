#!/usr/bin/env node
// Monitor ingest micro-benchmark -> bench/parts/monitor-ingest.json (flat metric -> number).
// The live run's fold in Node, no browser: the Monitor's model (monitor/monitor-model.ts, bundled
// by esbuild as the page's worker is) fed the trace of a 1 kHz periodic schema (khz-cycle.mjs, every
// record a cycle writes: 20 a cycle) the way the live run's worker feeds it (live-follower.ts): the
// lines of 20 ms as one text, each line read in place (pushLineIn). Repeated ROUNDS times on a fresh
// model each; the median round is kept.
//   monitor.ingest_node_us_per_record   the model's time to read and fold one record (the panel
//                                       benchmark's monitor.ingest_us_per_record, measured in the page's worker)
//   monitor.flow_findings_ns_per_record the share of the flow findings (FlowFindings.seeScanned: what
//                                       contract trace's DataFlowUse follows): every line scanned and followed,
//                                       less every line scanned only
// Times are the process's CPU time (process.cpuUsage): the machine is shared with other work.
// INGEST_BENCH_SECONDS (default 30) sets how long a run of the schema is fed each round (600,000 records).
import { mkdtempSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { build } from 'esbuild';
import { pkg, writePart } from './bench-support.mjs';
import { khzCycle } from './khz-cycle.mjs';

const seconds = Number(process.env.INGEST_BENCH_SECONDS ?? 30);
const ROUNDS = Number(process.env.INGEST_BENCH_ROUNDS ?? 7);

const dir = mkdtempSync(join(tmpdir(), 'monitor-ingest-bench-'));
let model;
try {
  const entry = join(dir, 'entry.ts');
  const out = join(dir, 'bundle.mjs');
  await build({
    stdin: {
      contents: `export { MonitorModel } from ${JSON.stringify(join(pkg, 'src/monitor/monitor-model.ts'))};
export { FlowFindings } from ${JSON.stringify(join(pkg, 'src/monitor/flow-findings.ts'))};
export { scanLine } from ${JSON.stringify(join(pkg, 'src/monitor/line-scan.ts'))};`,
      resolveDir: pkg, loader: 'ts', sourcefile: entry,
    },
    bundle: true, platform: 'node', format: 'esm', outfile: out, logLevel: 'warning',
  });
  model = await import(out);
} finally {
  rmSync(dir, { recursive: true, force: true });
}
const { MonitorModel, FlowFindings, scanLine } = model;

/** The trace events of `seconds` of the schema: one text of 20 ms of lines each, with each line's log and where it is. */
function traceEvents() {
  const events = [];
  let lines = [];
  const state = { release: 0 };
  const L = (ns, module, event, peer, port, size, detail) => lines.push({ ns, text: `${ns},2026-12-07T12:00:00.000000Z,${module},${event},${peer},${port},${size},${detail}`, file: `${module}_7-Dec-2026-12h00m00s.csv` });
  for (let c = 0; c < seconds * 1000; c++) {
    khzCycle(L, c, state, true);
    if (c % 20 === 19) {
      lines.sort((a, b) => a.ns - b.ns);
      let text = '', from = 0;
      const at = [];
      for (const l of lines) {
        at.push({ file: l.file, from, to: from + l.text.length });
        text += l.text + '\n';
        from += l.text.length + 1;
      }
      events.push({ text, at });
      lines = [];
    }
  }
  return events;
}

const events = traceEvents();
const records = events.reduce((n, e) => n + e.at.length, 0);

/** CPU time of this process in ns (the machine is shared: wall time would count the others' work). */
const cpuNs = () => {
  const u = process.cpuUsage();
  return (u.user + u.system) * 1000;
};

function ingestRound() {
  const m = new MonitorModel({});
  const t0 = cpuNs();
  let id = 0, line = 0;
  for (const e of events) {
    id++;
    for (const a of e.at) m.pushLineIn(a.file, ++line, e.text, a.from, a.to, id);
  }
  const ns = cpuNs() - t0;
  m.recordsEnded();
  return ns / records;
}

/** Every line scanned (scanLine), and, with `findings`, handed to the flow findings then: the difference is theirs. */
function scanRound(findings) {
  const f = new FlowFindings();
  const t0 = cpuNs();
  for (const e of events) {
    for (const a of e.at) {
      scanLine(e.text, a.from, a.to, a.file);
      if (findings) f.seeScanned(e.text, a.from, a.to);
    }
  }
  f.endLines();
  return (cpuNs() - t0) / records;
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
ingestRound(); // warm-up (the JIT)
scanRound(true);
scanRound(false);
const ingest = [], scanOnly = [], withFindings = [];
for (let r = 0; r < ROUNDS; r++) {
  ingest.push(ingestRound());
  scanOnly.push(scanRound(false));
  withFindings.push(scanRound(true));
}
const result = {
  'monitor.ingest_node_us_per_record': +(median(ingest) / 1000).toFixed(3),
  'monitor.flow_findings_ns_per_record': +Math.max(0, median(withFindings) - median(scanOnly)).toFixed(1),
  'monitor.ingest_node_records': records,
};
writePart('monitor-ingest', result);
console.log(`monitor-ingest: ${records} records a round, ${ROUNDS} rounds: ingest ${result['monitor.ingest_node_us_per_record']} µs a record ` +
  `(rounds ${ingest.map((x) => (x / 1000).toFixed(3)).join(', ')}); flow findings ${result['monitor.flow_findings_ns_per_record']} ns a record ` +
  `(a line scanned ${median(scanOnly).toFixed(0)} ns, scanned and followed ${median(withFindings).toFixed(0)} ns)`);
