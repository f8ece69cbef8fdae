#!/usr/bin/env node
// Monitor live benchmark -> bench/parts/monitor-live.json (flat metric -> number).
// A real Build & Run in the IDE (production build, real server with the build service, bwrap) of
// the "New project" template at 1 kHz (PERIOD = CRITICAL_DELAY = 1 ms), the Monitor following it:
// the run's CSV records reach the page as trace events (docs/build-service-api.md "Trace
// channel") and are drawn by the panel.
//   monitor.trace_latency_ms_p99 / _p50  a record written by a module (its wall_time column) ->
//                                        drawn in the Monitor (the end of the first frame whose model holds it), same host clock
//   monitor.live_max_frame_ms / live_frame_ms_p99   animation-frame gaps while the run streams
//   monitor.live_trace_records           records drawn live
//   monitor.arrival_latency_ms_p99 / _p50  the same record -> its trace event handed to the page (the rest is the page's)
//   monitor.live_max_queued_events       most trace events waiting to be folded at a frame (the page keeping up)
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
    // wall_time of each record (µs precision) by the cumulative count the live model will reach
    // (the second, parsed once per second of wall time, plus the fraction: the measuring must not
    // load the page it measures with a date parse per record)
    let second = '';
    let secondMs = NaN;
    const wall = (text) => {
      const c = text.indexOf(',');
      const w = text.slice(c + 1, c + 27); // 2026-11-28T13:58:13.785123
      const s = w.slice(0, 19);
      if (s !== second) {
        second = s;
        secondMs = Date.parse(`${s}Z`);
      }
      return secondMs + Number(w.slice(20, 26)) / 1000;
    };
    const m = { pending: [], latencies: [], arrivals: [], gaps: [], received: 0, streaming: false, maxQueued: 0 };
    window.__liveBench = m;
    ide.build.onStarted.on(() => {
      m.received = 0;
      m.streaming = true;
    });
    ide.build.onTrace.on(({ records }) => {
      const now = Date.now();
      for (const r of records) {
        const w = wall(r.text);
        m.pending.push({ version: ++m.received, wall: w });
        if (Number.isFinite(w)) m.arrivals.push(now - w);
      }
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
        let i = 0;
        for (; i < m.pending.length && m.pending[i].version <= panel.drawn.version; i++) if (Number.isFinite(m.pending[i].wall)) m.latencies.push(now - m.pending[i].wall);
        if (i) m.pending.splice(0, i);
      }
    };
    const tick = (t) => {
      if (m.streaming) m.gaps.push(t - last);
      m.maxQueued = Math.max(m.maxQueued, ide.monitor.pendingEvents);
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
    const g = m.gaps.slice(2);
    return { status: document.getElementById('status-job').dataset.status, p99: pct(m.latencies, 99), p50: pct(m.latencies, 50), n: m.latencies.length,
      received: m.received, maxFrame: Math.max(...g), p99Frame: pct(g, 99), frames: g.length,
      a99: pct(m.arrivals, 99), a50: pct(m.arrivals, 50), maxQueued: m.maxQueued };
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
    'monitor.live_max_queued_events': r.maxQueued,
  };
  writePart('monitor-live', result);
  console.log(JSON.stringify({ ...result, received: r.received, frames: r.frames, runSeconds }));
} finally {
  await context?.close().catch(() => undefined);
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
