#!/usr/bin/env node
// Monitor live benchmark -> bench/parts/monitor-live.json (flat metric -> number).
// A real Build & Run in the IDE (production build, real server with the build service, bwrap) of
// the "New project" template at 1 kHz (PERIOD = CRITICAL_DELAY = 1 ms), the Monitor following it:
// the run's CSV records reach the live run's Web Worker as trace events on its own socket
// (docs/build-service-api.md "Trace channel"), are folded there and drawn by the panel.
//   monitor.trace_latency_ms_p99 / _p50  a record written by a module (its wall_time column) ->
//                                        drawn in the Monitor (the end of the first frame whose model holds it), same host clock
//   monitor.live_max_frame_ms / live_frame_ms_p99   animation-frame gaps while the run streams: from the frame of
//                                        the first record in the page to the job's end
//   monitor.live_open_max_frame_ms / live_open_frames / live_open_late_frames   the frames before that: Build & Run
//                                        opening the Monitor (its first diagram, the editor narrowed) while the job
//                                        builds, no schema running yet; told apart, not hidden
//   monitor.live_trace_records           records drawn live
//   monitor.arrival_latency_ms_p99 / _p50  the same record -> its trace event received by the worker (the rest is the page's)
//   monitor.live_late_frames / _with_steal / live_on_time_frames_with_steal_share / live_steal_ms_per_s   as in
//                                        monitor-bench.mjs: late frames, those the hypervisor took time in, the chance (steal-sampler.mjs)
//   monitor.trace_latency_ms_p99_first_5s  the same p99 over the records of the run's first 5 s (the page, the worker and the
//                                        service's stream starting: a 5 s run measured that alone)
// RUN_SECONDS (default 55: a minute's run inside the service's 60 s bound) sets the run's duration; the part takes about 75 s.
// FRAME_TRACE=<file.json> records a trace of every Chromium process while the run streams, late frames marked
// (`node bench/frame-trace.mjs <file.json>` says which threads ran in each late frame's gap).
import { mkdirSync, writeFileSync, mkdtempSync, rmSync, realpathSync, chmodSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { buildProductionIde, launchChromium, openIdePage, writePart } from './bench-support.mjs';
import { LATE_FRAME_MS, lateFramesAndSteal, startStealSampler } from './steal-sampler.mjs';
import { installLatencyMeter } from './latency-meter.mjs';
import { startFrameTrace } from './frame-trace.mjs';

const runSeconds = Number(process.env.RUN_SECONDS ?? 55);
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
  const page = await openIdePage(context, server);
  await installLatencyMeter(page);
  await page.evaluate(({ duration, lateMs }) => {
    localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration }));
    const ide = window.__ide;
    ide.monitor.measure = true; // the worker's snapshots bring each record's wall time and arrival
    const m = { meter: window.__latencyMeter(), frames: [], streaming: false }; // frames: [end (epoch ms), gap (ms)]
    window.__liveBench = m;
    ide.build.onStarted.on(() => {
      m.streaming = true;
      ide.monitor.lastLive.onSnapshot = (snap, version) => {
        // the first record in the page: the frames before it are the Monitor opening while the job builds
        if (m.firstRecordFrame === undefined && snap.count > 0) m.firstRecordFrame = m.frames.length;
        m.meter.snapshot(snap, version);
      };
    });
    ide.build.onFinished.on(() => (m.streaming = false));
    let last = performance.now();
    const drawn = () => m.meter.drawn(ide.monitor.panel, ide.monitor.lastLive);
    const tick = (t) => {
      if (m.streaming) m.frames.push([performance.timeOrigin + t, t - last]);
      if (m.streaming && t - last > lateMs) performance.mark('late-frame', { detail: t - last }); // for FRAME_TRACE
      last = t;
      setTimeout(drawn, 0);
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }, { duration: runSeconds, lateMs: LATE_FRAME_MS });
  const steal = startStealSampler();
  // FRAME_TRACE=<file.json>: a trace of every Chromium process while the run streams (frame-trace.mjs)
  const frameTrace = process.env.FRAME_TRACE ? await startFrameTrace(context, page) : null;
  await page.locator('#btn-run').click();
  await page.waitForFunction(() => document.getElementById('status-job')?.dataset.status === 'succeeded' || document.getElementById('status-job')?.dataset.status === 'failed', undefined, { timeout: 150_000 });
  await page.waitForTimeout(500);
  const r = await page.evaluate((lateMs) => {
    const m = window.__liveBench;
    const pct = (xs, p) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor((xs.length * p) / 100))];
    const meter = m.meter;
    // from the first record on: the run streams; before it, Build & Run opened the Monitor (its first
    // diagram, the editor narrowed) while the job built, with no schema running yet
    const cut = Math.max(2, m.firstRecordFrame ?? 2);
    const frameEnds = m.frames.slice(cut);
    const g = frameEnds.map((f) => f[1]);
    const opening = m.frames.slice(2, cut).map((f) => f[1]);
    return { status: document.getElementById('status-job').dataset.status, p99: meter.pct('shown', 99), p50: meter.pct('shown', 50), n: meter.shown, p99Start: meter.pct('early', 99),
      received: meter.received, maxFrame: Math.max(...g), p99Frame: pct(g, 99), frames: g.length,
      openMax: opening.length ? Math.max(...opening) : 0, openFrames: opening.length, openLate: opening.filter((x) => x > lateMs).length,
      a99: meter.pct('arrived', 99), a50: meter.pct('arrived', 50), problems: window.__ide.monitor.lastLive?.problems ?? [], frameEnds };
  }, LATE_FRAME_MS);
  if (frameTrace) console.error(`[monitor-live] frame trace: ${process.env.FRAME_TRACE} ${JSON.stringify(await frameTrace.stop(process.env.FRAME_TRACE))}`);
  if (r.status !== 'succeeded' || !r.n) throw new Error(`the run did not stream: ${JSON.stringify(r)}`);
  const stolen = lateFramesAndSteal(r.frameEnds, await steal.stop());
  const round = (x, d = 1) => Math.round(x * 10 ** d) / 10 ** d;
  const result = {
    'monitor.trace_latency_ms_p99': round(r.p99),
    'monitor.trace_latency_ms_p50': round(r.p50),
    'monitor.trace_latency_ms_p99_first_5s': round(r.p99Start),
    'monitor.live_max_frame_ms': round(r.maxFrame),
    'monitor.live_open_max_frame_ms': round(r.openMax),
    'monitor.live_open_frames': r.openFrames,
    'monitor.live_open_late_frames': r.openLate,
    'monitor.live_frame_ms_p99': round(r.p99Frame),
    'monitor.live_trace_records': r.n,
    'monitor.arrival_latency_ms_p99': round(r.a99),
    'monitor.arrival_latency_ms_p50': round(r.a50),
    'monitor.live_late_frames': stolen.late,
    'monitor.live_late_frames_with_steal': stolen.lateStolen,
    'monitor.live_on_time_frames_with_steal_share': round(stolen.onTimeStolenShare, 3),
    'monitor.live_steal_ms_per_s': round(stolen.stealMsPerS),
  };
  writePart('monitor-live', result);
  console.log(JSON.stringify({ ...result, received: r.received, frames: r.frames, runSeconds, problems: r.problems }));
} finally {
  await context?.close().catch(() => undefined);
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
