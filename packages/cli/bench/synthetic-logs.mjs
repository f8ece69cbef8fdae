// A run's CSV logs made up, in the runtime's exact format (docs/runtime-api.md "CSV log" and
// "Trace records"; runtime/src/csvlog.c's quoting): ORD releasing a periodic schema of N modules,
// each module's request/run/ack records, a data flow, and a supervisor's rule changes and quoted
// lines, with the clocks as the runtime writes them (mono_ns, and a wall_time taken at the same
// moment). Deterministic: the same options give the same bytes. Used by trace-settle-bench.mjs
// (the end of `contract run --trace` on a long run).
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
/** mono_ns of the run's first record (CLOCK_MONOTONIC: the machine's uptime), and its wall time in ms. */
const MONO0 = 60652986077749n;
const WALL0_MS = Date.UTC(2026, 11, 7, 5, 34, 39, 684);

/** A CSV field as csvlog.c writes it: quoted when it holds a quote or a comma (quotes doubled). */
function field(text) {
  return /[",]/.test(text) ? `"${text.replace(/"/g, '""')}"` : text;
}

/** The runtime's wall_time of a mono_ns: `2026-12-07T05:34:39.684061Z` (microseconds). */
function wallOf(mono) {
  const us = Number((mono - MONO0) / 1000n);
  const ms = WALL0_MS + Math.floor(us / 1000);
  return `${new Date(ms).toISOString().slice(0, 19)}.${String(((ms % 1000) * 1000) + (us % 1000)).padStart(6, '0')}Z`;
}

/** The module names: ORD, SUP and `modules - 2` others (M00, M01, ...). */
function moduleNames(modules) {
  const names = ['ORD', 'SUP'];
  for (let i = 0; names.length < modules; i++) names.push(`M${String(i).padStart(2, '0')}`);
  return names;
}

/**
 * Writes `modules` CSV logs (ORD, SUP and the others, `<NAME>_7-Dec-2026-05h34m39s.csv`) of a
 * run of `seconds` into `dir` (created), ORD releasing every other module once per cycle of
 * `periodMs`; returns the log names, their bytes and the records written (headers left out).
 * 50 modules, 60 s, 32 ms: about 810,000 records, 74 MiB (the size of a 60 s run of 50 modules).
 */
export function writeSyntheticLogs(dir, { modules = 50, seconds = 60, periodMs = 32 } = {}) {
  mkdirSync(dir, { recursive: true });
  const names = moduleNames(Math.max(3, modules));
  const workers = names.slice(2);
  /** Each log's lines, in the order written (its times go forward). */
  const logs = new Map(names.map((n) => [n, [HEADER]]));
  let records = 0;
  const log = (mono, module, event, peer, port, size, detail) => {
    logs.get(module).push(`${mono},${wallOf(mono)},${module},${event},${field(peer)},${port},${size},${field(detail)}`);
    records++;
  };
  let t = MONO0;
  const at = (ns) => (t += BigInt(ns));
  // start: every module's module_started and priority lines
  names.forEach((m, i) => {
    log(at(20_000 + i * 700), m, 'module_started', '', '', 0, `pid=${24 + i} priority=${90 - i}`);
    log(at(3_000), m, 'priority', '', '', 0, `nice ${1 + (i % 19)} (priority ${90 - i})`);
  });
  log(at(1_700_000), 'SUP', 'supervisor', '', '', 0, 'function mission(goal = {x=1.5,y=-2.0,mode=AUTO}) started');
  log(at(40_000), 'SUP', 'sup_rule', '', '', 0, 'mission.FIRST active cause=elapsed=1000000ns');
  log(at(5_000), 'SUP', 'supervisor', '', '', 0, 'activate schema control(param = {i=27.12,j=0.0,k=0.04}) (activation #1, to ORD)');
  log(at(20_000), 'ORD', 'request_received', 'SUP', '', 29, 'START control');
  log(at(20_000), 'ORD', 'scheduler', '', '', 0, 'activate control (activation #1 from SUP)');
  const cycles = Math.floor((seconds * 1000) / periodMs);
  const release = new Map(workers.map((m) => [m, 0]));
  for (let cycle = 0; cycle < cycles; cycle++) {
    const tick = MONO0 + 2_000_000_000n + BigInt(cycle) * BigInt(periodMs) * 1_000_000n;
    if (t < tick) t = tick;
    for (const [i, m] of workers.entries()) {
      const id = release.get(m) + 1;
      release.set(m, id);
      const sent = at(1_500 + (i % 7) * 130);
      log(sent, 'ORD', 'ord_release', m, '', 0, `schema=control cycle=${cycle} tick_ns=${tick} release_ns=${sent} release=${id}`);
      log(at(9_000), m, 'request_received', 'ORD', '', 0, 'START');
      log(at(600), m, 'run_started', 'ORD', '', 0, `activation=${id}`);
      if (i > 0) log(at(2_000), m, 'data_received', workers[i - 1], 0, 24, `latency_ns=${8_000 + ((cycle * 31 + i * 17) % 5_000)}`);
      log(at(30_000 + ((cycle * 13 + i * 7) % 20_000)), m, 'data_posted', workers[(i + 1) % workers.length], 0, 24, 'to_port=0');
      log(at(1_000), m, 'run_finished', '', '', 0, `activation=${id} cpu_ns=41000 ACK_FINISHED`);
      log(at(700), m, 'ack_sent', 'ORD', '', 0, `ACK_FINISHED id=${id}`);
      log(at(8_000), 'ORD', 'ack_received', m, '', 0, `ACK_FINISHED id=${id}`);
      log(at(900), 'ORD', 'ord_finished', m, '', 0, `schema=control cycle=${cycle} release=${id} response_ns=${t - tick}`);
    }
    log(at(1_000), 'ORD', 'ord_complete', '', '', 0, `schema=control cycle=${cycle} tick_ns=${tick} response_ns=${t - tick}`);
    // once a second: the supervisor's event and rule change, a quoted line, a priority claim
    if (cycle % Math.max(1, Math.round(1000 / periodMs)) === 0) {
      const m = workers[cycle % workers.length];
      log(at(4_000), m, 'event_posted', 'SUP', 2, 256, 'to_port=2');
      log(at(9_000), 'SUP', 'event_received', m, 2, 256, 'from_port=2 latency_ns=9000');
      log(at(3_000), 'SUP', 'sup_rule', '', '', 0, `mission.AVOID ${cycle % 2 ? 'inactive' : 'active'} cause=${m}:2 value="obstacle, ${cycle % 97} cm"`);
      log(at(2_000), 'SUP', 'supervisor', m, '', 0, `parameterize ${m}:0 gain (24 bytes) = {i=${cycle % 13}.5,j=0.0,k=0.04}`);
      log(at(2_000), m, 'priority_changed', 'SUP', '', 0, `nice ${cycle % 19} (priority ${10 + (cycle % 60)}, was 30)`);
    }
  }
  // the end: every module's exit record, counting its own records
  for (const m of [...workers, 'SUP', 'ORD']) {
    const lines = logs.get(m);
    log(at(50_000), m, 'module_exit', '', '', 0, `status=0 records=${lines.length}`);
  }
  const files = [];
  let bytes = 0;
  for (const [m, lines] of logs) {
    const name = `${m}_7-Dec-2026-05h34m39s.csv`;
    const text = lines.join('\n') + '\n';
    writeFileSync(join(dir, name), text);
    files.push(name);
    bytes += Buffer.byteLength(text);
  }
  return { files: files.sort(), bytes, records };
}
