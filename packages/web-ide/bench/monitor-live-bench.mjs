#!/usr/bin/env node
// Monitor live benchmark -> bench/parts/monitor-live.json (flat metric -> number).
// A real Build & Run in the IDE (production build, real server with the build service, bwrap) of
// the "New project" template at 1 kHz (PERIOD = CRITICAL_DELAY = 1 ms), the Monitor following it:
// the run's CSV records reach the live run's Web Worker as trace events on its own socket
// (docs/build-service-api.md "Trace channel"), are folded there and drawn by the panel.
//   monitor.trace_latency_ms_p99 / _p50  a record written by a module (its wall_time column) ->
//                                        drawn in the Monitor (the end of the first frame whose model holds it), same host clock
//   monitor.live_max_frame_ms / live_frame_ms_p99   animation-frame gaps while the run streams
//   monitor.live_trace_records           records drawn live
//   monitor.arrival_latency_ms_p99 / _p50  the same record -> its trace event received by the worker (the rest is the page's)
// RUN_SECONDS (default 5) sets the run's duration; the part takes about 40 s (the build is most of it).
import { mkdirSync, writeFileSync, mkdtempSync, rmSync, realpathSync, chmodSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { buildProductionIde, launchChromium, writePart } from './bench-support.mjs';

const runSeconds = Number(process.env.RUN_SECONDS ?? 5);
const { startIdeServer } = await buildProductionIde();
const { PROJECT_TEMPLATES } = await import('@contract-studio/language');
const base = realpathSync(mkdtempSync(join(tmpdir(), 'monitor-live-bench-')));
chmodSync(base, 0o755); // the sandboxed job's uid walks through it
const workspace = join(base, 'khz');
mkdirSync(workspace);
for (const [name, text] of Object.entries(PROJECT_TEMPLATES)) {
  writeFileSync(join(workspace, name), text.replace('PERIOD=10ms; CRITICAL_DELAY=10ms;', 'PERIOD=1ms; CRITICAL_DELAY=1ms;').replace('C=500us;', 'C=100us;').replace('C=1ms;', 'C=200us;'));
}
const server = await startIdeServer({ workspace, port: 0, buildService: true });
let context;
try {
  context = await launchChromium(join(base, 'profile'));
  const page = context.pages()[0] ?? (await context.newPage());
  await page.goto(server.openUrl);
  await page.waitForSelector('body[data-ready=true]', { timeout: 60_000 });
  await page.evaluate((duration) => {
    localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration }));
    const ide = window.__ide;
    // each record's wall_time and its arrival at the worker come with the snapshot that first
    // holds it (monitor.measure); latencies are counted in 0.1 ms bins, so that the measuring does
    // not load the page it measures
    ide.monitor.measure = true;
    const m = { snapshots: [], lat: new Uint32Array(100_000), arr: new Uint32Array(100_000), n: 0, received: 0, gaps: [], streaming: false };
    window.__liveBench = m;
    const bin = (bins, ms) => bins[Math.min(bins.length - 1, Math.max(0, Math.round(ms * 10)))]++;
    ide.build.onStarted.on(() => {
      m.streaming = true;
      const model = ide.monitor.lastLive;
      model.onSnapshot = (snap, version) => {
        if (!snap.walls?.length) return;
        m.received += snap.walls.length;
        for (let i = 0; i < snap.walls.length; i++) bin(m.arr, snap.arrived[i] - snap.walls[i]);
        m.snapshots.push({ version, walls: snap.walls });
      };
    });
    ide.build.onFinished.on(() => (m.streaming = false));
    let last = performance.now();
    // what this frame drew, looked at once the frame is done (a task queued from a frame callback
    // runs after the frame's other callbacks, the panel's among them, and after its paint)
    const drawn = () => {
      const panel = ide.monitor.panel;
      const live = ide.monitor.lastLive;
      if (panel && live && panel.drawn.model === live) {
        const now = Date.now();
        while (m.snapshots.length && m.snapshots[0].version <= panel.drawn.version) {
          for (const w of m.snapshots.shift().walls) {
            bin(m.lat, now - w);
            m.n++;
          }
        }
      }
    };
    const tick = (t) => {
      if (m.streaming) m.gaps.push(t - last);
      last = t;
      setTimeout(drawn, 0);
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }, runSeconds);
  await page.locator('#btn-run').click();
  await page.waitForFunction(() => document.getElementById('status-job')?.dataset.status === 'succeeded' || document.getElementById('status-job')?.dataset.status === 'failed', undefined, { timeout: 150_000 });
  await page.waitForTimeout(500);
  const r = await page.evaluate(() => {
    const m = window.__liveBench;
    const pct = (xs, p) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor((xs.length * p) / 100))];
    const binPct = (bins, p) => {
      const total = bins.reduce((a, b) => a + b, 0);
      let k = 0;
      for (let i = 0; i < bins.length; i++) if ((k += bins[i]) >= (total * p) / 100) return i / 10;
      return NaN;
    };
    const g = m.gaps.slice(2);
    return { status: document.getElementById('status-job').dataset.status, p99: binPct(m.lat, 99), p50: binPct(m.lat, 50), n: m.n,
      received: m.received, maxFrame: Math.max(...g), p99Frame: pct(g, 99), frames: g.length,
      a99: binPct(m.arr, 99), a50: binPct(m.arr, 50), problems: window.__ide.monitor.lastLive?.problems ?? [] };
  });
  if (r.status !== 'succeeded' || !r.n) throw new Error(`the run did not stream: ${JSON.stringify(r)}`);
  const round = (x, d = 1) => Math.round(x * 10 ** d) / 10 ** d;
  const result = {
    'monitor.trace_latency_ms_p99': round(r.p99),
    'monitor.trace_latency_ms_p50': round(r.p50),
    'monitor.live_max_frame_ms': round(r.maxFrame),
    'monitor.live_frame_ms_p99': round(r.p99Frame),
    'monitor.live_trace_records': r.n,
    'monitor.arrival_latency_ms_p99': round(r.a99),
    'monitor.arrival_latency_ms_p50': round(r.a50),
  };
  writePart('monitor-live', result);
  console.log(JSON.stringify({ ...result, received: r.received, frames: r.frames, runSeconds, problems: r.problems }));
} finally {
  await context?.close().catch(() => undefined);
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
