#!/usr/bin/env node
// Log flood benchmark -> bench/parts/log-flood.json (flat metric -> number).
// A real Build & Run in the IDE (production build, real server with the build service, bwrap) of
// the tutorial whose module MSA prints FLOOD_RATE lines a second (default 10,000) for
// FLOOD_SECONDS (default 20) from a thread its init starts, the Build & Run panel and the Monitor
// open (Build & Run opens it): the field report was "a printf flood (6 to 15 k lines/s) froze the
// IDE page for 15 to 20 s". The job's output limit is raised (OUTPUT_MIB, default 64 MiB a stream)
// so that the whole flood reaches the page, as for a long run watched in the IDE (docs/ide.md).
//   ide.flood_max_frame_ms            longest gap between two animation frames, from the flood's first line in the page to the job's end there
//   ide.flood_frame_ms_p99            the same, 99th percentile
//   ide.flood_max_long_task_ms        longest task of the page's main thread (PerformanceObserver 'longtask')
//   ide.flood_long_task_ms_per_s      main-thread time in long tasks per second of the flood
//   ide.flood_input_delay_ms_max / _p50   a key pressed every 250 ms in a text field of the page during the flood:
//                                     its keydown handled, ms after the browser took it (performance.now() - event.timeStamp)
//   ide.flood_key_ms_max / _p50       the same key seen from the test driver: sent (Chrome DevTools Protocol) -> handled by the page
//                                     (the browser's queues included: with the page behind, a key waited seconds)
//   ide.flood_line_lag_ms_max / _p50  a flood line's time in the build service -> its arrival in the page's log (every 100th line)
//   ide.flood_end_lag_ms              the job's end in the build service -> its end shown in the page (a backlog of lines)
//   ide.flood_lines_received          log lines the page received
//   ide.flood_lines_per_s             the flood's rate as received
//   ide.flood_log_rows_max            most rows the log view held in the DOM at once
// PROFILE=<file.cpuprofile> records a CPU profile of the page (Chrome DevTools Protocol) during the flood.
import { mkdtempSync, rmSync, realpathSync, chmodSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { buildProductionIde, launchChromium, openIdePage, writePart } from './bench-support.mjs';
import { floodProject } from './flood-project.mjs';

const rate = Number(process.env.FLOOD_RATE ?? 10_000);
const floodSeconds = Number(process.env.FLOOD_SECONDS ?? 20);
const outputMiB = Number(process.env.OUTPUT_MIB ?? 64);
const runSeconds = floodSeconds + 8;

const { startIdeServer } = await buildProductionIde();
const base = realpathSync(mkdtempSync(join(tmpdir(), 'log-flood-bench-')));
chmodSync(base, 0o755); // the sandboxed job's uid walks through it
const workspace = join(base, 'tutorial');
floodProject(workspace, rate, floodSeconds);
const server = await startIdeServer({
  workspace, port: Number(process.env.PORT ?? 0), buildService: true,
  limits: { outputBytesPerStream: outputMiB * 1024 * 1024, runSeconds: runSeconds + 20 },
});
let context;
try {
  context = await launchChromium(join(base, 'profile'));
  const page = await openIdePage(context, server);
  await page.evaluate(({ duration }) => {
    localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration }));
    const ide = window.__ide;
    const m = { frames: [], longTasks: [], inputs: [], streaming: false, rowsMax: 0, received: 0, flood: 0, slow: [], startedAt: 0, endedAt: 0, endWall: 0 };
    window.__flood = m;
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) if (m.streaming) m.longTasks.push([Math.round(e.startTime - m.startedAt), e.duration]);
    }).observe({ type: 'longtask' });
    const probe = document.createElement('input');
    probe.id = 'flood-probe';
    probe.style.cssText = 'position:fixed;left:0;bottom:0;width:40px;height:16px;z-index:99999';
    probe.addEventListener('keydown', (e) => {
      if (m.streaming) m.inputs.push(performance.now() - e.timeStamp);
    });
    document.body.append(probe);
    ide.build.onStarted.on(({ jobId }) => (m.jobId = jobId));
    // how far behind the page reads the log: a line's arrival -> its time in the service (same host clock), every 100th line
    m.lags = [];
    const append = ide.build.append.bind(ide.build);
    let n = 0;
    ide.build.append = (l) => {
      // measured from the flood's first line in the page (before it: the build, the Monitor opening)
      if (!m.streaming && !m.endedAt && l.source === 'MSA') {
        m.streaming = true;
        m.startedAt = performance.now();
      }
      m.received++;
      if (l.source === 'MSA') m.flood++;
      if (++n % 100 === 0 && l.source === 'MSA') m.lags.push(Date.now() - l.t);
      append(l);
    };
    ide.build.onFinished.on(() => {
      m.endedAt = performance.now();
      m.endWall = Date.now();
      setTimeout(() => (m.streaming = false), 500);
    });
    let last = performance.now();
    const tick = (t) => {
      if (m.streaming) {
        m.frames.push(t - last);
        if (t - last > 100) m.slow.push([Math.round(t - m.startedAt), Math.round(t - last)]);
        const rows = document.querySelector('.log-rows')?.childElementCount ?? 0;
        if (rows > m.rowsMax) m.rowsMax = rows;
      }
      last = t;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }, { duration: floodSeconds + 3 });
  let cdp;
  if (process.env.PROFILE) {
    cdp = await context.newCDPSession(page);
    await cdp.send('Profiler.enable');
    await cdp.send('Profiler.setSamplingInterval', { interval: 500 });
  }
  await page.locator('#btn-run').click();
  // the flood begins with MSA's init, a few seconds after the build
  await page.waitForFunction(() => window.__ide.build.store.total > 0 && [...window.__ide.build.store.sources.keys()].includes('MSA'), undefined, { timeout: 120_000 });
  if (cdp) await cdp.send('Profiler.start');
  const probe = page.locator('#flood-probe');
  await probe.focus();
  const driverKeys = [];
  let done = false;
  const finished = page.waitForFunction(() => window.__flood.endedAt > 0, undefined, { timeout: (runSeconds + 120) * 1000, polling: 500 }).then(() => (done = true));
  while (!done) {
    const t0 = Date.now();
    await page.keyboard.press('a');
    driverKeys.push(Date.now() - t0);
    if (process.env.VERBOSE) console.error(`key ${new Date(t0).toISOString().slice(17, 23)} ${Date.now() - t0} ms`);
    await new Promise((r) => setTimeout(r, 250));
  }
  await finished;
  if (cdp) {
    const { profile } = await cdp.send('Profiler.stop');
    writeFileSync(process.env.PROFILE, JSON.stringify(profile));
  }
  await page.waitForTimeout(800);
  const job = await page.evaluate(async () => (await fetch(`/api/jobs/${window.__flood.jobId}`)).json()).catch(() => null);
  const r = await page.evaluate(() => {
    const m = window.__flood;
    return { slow: m.slow, lags: m.lags, frames: m.frames, longTasks: m.longTasks, inputs: m.inputs, rowsMax: m.rowsMax, total: m.received, flood: m.flood, seconds: (m.endedAt - m.startedAt) / 1000, endWall: m.endWall,
      status: document.getElementById('status-job')?.dataset.status };
  });
  const pct = (xs, p) => (xs.length ? [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor((xs.length * p) / 100))] : 0);
  const round = (x, d = 1) => Math.round(x * 10 ** d) / 10 ** d;
  const result = {
    'ide.flood_max_frame_ms': round(Math.max(...r.frames)),
    'ide.flood_frame_ms_p99': round(pct(r.frames, 99)),
    'ide.flood_max_long_task_ms': round(Math.max(0, ...r.longTasks.map((t) => t[1]))),
    'ide.flood_long_task_ms_per_s': round(r.longTasks.reduce((a, t) => a + t[1], 0) / Math.max(1, r.seconds)),
    'ide.flood_input_delay_ms_max': round(Math.max(0, ...r.inputs)),
    'ide.flood_input_delay_ms_p50': round(pct(r.inputs, 50)),
    'ide.flood_key_ms_max': Math.max(0, ...driverKeys),
    'ide.flood_key_ms_p50': pct(driverKeys, 50),
    'ide.flood_line_lag_ms_max': round(Math.max(0, ...r.lags)),
    'ide.flood_line_lag_ms_p50': round(pct(r.lags, 50)),
    'ide.flood_end_lag_ms': job?.finishedAt ? Math.max(0, r.endWall - job.finishedAt) : -1,
    'ide.flood_lines_received': r.total,
    'ide.flood_lines_per_s': Math.round(r.flood / floodSeconds),
    'ide.flood_log_rows_max': r.rowsMax,
  };
  if (!process.env.NO_PART) writePart('log-flood', result);
  console.log(JSON.stringify({ ...result, status: r.status, seconds: round(r.seconds), frames: r.frames.length, framesOver50: r.frames.filter((f) => f > 50).length, slowFrames: r.slow,
    longTasks: r.longTasks, inputs: r.inputs.length, keys: driverKeys.length, rate, floodSeconds, outputMiB, jobFinishedAt: job?.finishedAt }));
} finally {
  await context?.close().catch(() => undefined);
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
