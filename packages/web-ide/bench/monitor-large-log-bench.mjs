#!/usr/bin/env node
// One long recorded log (LARGE_LOG_MIB, default 600 MiB: ORD's log of a 1 kHz schema, some 550 s of
// run) in a workspace folder, opened in the Monitor as a user does (GET /api/log-folder, then each
// log through GET /api/log, the recorded run's model built) -> bench/parts/monitor-large-log.json.
// The real IDE (production build, real server on a copy of examples/tutorial) in headless Chromium.
//   monitor.large_log_ms              asked -> the run shown
//   monitor.large_log_heap_peak_mb    the page's JS heap at its highest meanwhile (CDP Performance.getMetrics, every 250 ms)
//   monitor.large_log_rss_peak_mb     Chromium's processes' resident memory at its highest meanwhile (ps, every 250 ms)
//   monitor.large_log_records         records the model holds
import { closeSync, cpSync, mkdirSync, mkdtempSync, openSync, realpathSync, rmSync, statSync, writeSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { buildProductionIde, launchChromium, openIdePage, root, writePart } from './bench-support.mjs';
import { khzCycle } from './khz-cycle.mjs';

const targetBytes = Number(process.env.LARGE_LOG_MIB ?? 600) * 1024 * 1024;
const { startIdeServer } = await buildProductionIde();
const base = realpathSync(mkdtempSync(join(tmpdir(), 'monitor-large-log-bench-')));
const workspace = join(base, 'tutorial');
cpSync(join(root, 'examples/tutorial'), workspace, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
mkdirSync(join(workspace, 'logs'));
const W = '2026-11-26T12:00:00.000000Z';
const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail\n';
const ordPath = join(workspace, 'logs', 'ORD_26-Nov-2026-12h00m00s.csv');
const fd = openSync(ordPath, 'w');
let bytes = writeSync(fd, `${HEADER}500000000000,${W},ORD,scheduler,,,0,activate schemaCommande1\n`);
let batch = [];
const L = (ns, m, ev, peer, port, size, detail) => {
  if (m === 'ORD') batch.push(`${ns},${W},${m},${ev},${peer},${port},${size},${detail}\n`);
};
const state = { release: 0 };
let cycles = 0;
while (bytes < targetBytes) {
  for (let i = 0; i < 1000; i++) khzCycle(L, cycles++, state, true);
  bytes += writeSync(fd, batch.join(''));
  batch = [];
}
closeSync(fd);
const profile = join(base, 'profile');
const server = await startIdeServer({ workspace, port: 0, buildService: false });

/** Resident memory of the Chromium started on `profile` and of its children (kB -> MB). */
function chromiumRssMb() {
  const rows = execFileSync('ps', ['-e', '-o', 'pid=,ppid=,rss=,args='], { encoding: 'utf8', maxBuffer: 64 << 20 }).trim().split('\n')
    .map((l) => l.trim().match(/^(\d+)\s+(\d+)\s+(\d+)\s+(.*)$/)).filter(Boolean).map((m) => ({ pid: +m[1], ppid: +m[2], rss: +m[3], args: m[4] }));
  const mine = new Set(rows.filter((r) => r.args.includes(profile) && !r.args.includes('--type=')).map((r) => r.pid));
  for (let grew = true; grew;) {
    grew = false;
    for (const r of rows) if (!mine.has(r.pid) && mine.has(r.ppid)) (mine.add(r.pid), (grew = true));
  }
  return rows.filter((r) => mine.has(r.pid)).reduce((n, r) => n + r.rss, 0) / 1024;
}

let context;
try {
  context = await launchChromium(profile);
  const page = await openIdePage(context, server);
  const cdp = await context.newCDPSession(page);
  await cdp.send('Performance.enable');
  const heapMb = async () => ((await cdp.send('Performance.getMetrics')).metrics.find((m) => m.name === 'JSHeapUsedSize')?.value ?? 0) / 1e6;
  const before = { heap: await heapMb(), rss: chromiumRssMb() };
  let peakHeap = before.heap;
  let peakRss = before.rss;
  let sampling = true;
  const sampler = (async () => {
    while (sampling) {
      peakHeap = Math.max(peakHeap, await heapMb().catch(() => 0));
      peakRss = Math.max(peakRss, chromiumRssMb());
      await new Promise((r) => setTimeout(r, 250));
    }
  })();
  const t0 = Date.now();
  const r = await page.evaluate(async () => {
    const ide = window.__ide;
    await ide.monitor.openFolder('logs');
    const run = ide.monitor.runs.get('dir:logs');
    return { records: run?.model.recordCount, label: run?.label };
  });
  const ms = Date.now() - t0;
  sampling = false;
  await sampler;
  const after = { heap: await heapMb(), rss: chromiumRssMb() };
  const round = (x) => Math.round(x * 10) / 10;
  writePart('monitor-large-log', {
    'monitor.large_log_ms': ms,
    'monitor.large_log_heap_peak_mb': round(peakHeap),
    'monitor.large_log_rss_peak_mb': round(peakRss),
    'monitor.large_log_records': r.records ?? 0,
  });
  console.log(`[monitor-large-log] ${round(statSync(ordPath).size / 1048576)} MiB ORD log (${cycles} cycles): shown after ${ms} ms, ${r.records} records; ` +
    `JS heap ${round(before.heap)} -> peak ${round(peakHeap)} -> ${round(after.heap)} MB; Chromium RSS ${round(before.rss)} -> peak ${round(peakRss)} -> ${round(after.rss)} MB\n  label: ${r.label}`);
} finally {
  await context?.close();
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
