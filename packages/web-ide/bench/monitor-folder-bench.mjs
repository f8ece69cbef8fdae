#!/usr/bin/env node
// A long run's log folder opened in the Monitor -> bench/parts/monitor-folder.json (flat metric -> number).
// The real IDE (production build, real server on a copy of examples/tutorial) in headless Chromium;
// the workspace's logs/ holds FOLDER_SECONDS (default 90) of a 1 kHz schema's CSV logs, every record
// a cycle writes (monitor/khz-cycle.mjs, full: about 190 MB in five logs, ORD's about 100 MB), and the
// page opens it as a user does (the Monitor's "Open logs…": GET /api/log-folder, then each log downloaded
// through GET /api/log and the recorded run's model built). Unlike monitor-panel's replay, whose logs
// are handed to the page as strings, the download and the decoding of the text are measured too.
//   monitor.folder_replay_ms              asked -> the run shown
//   monitor.folder_replay_max_frame_ms    longest gap between two animation frames meanwhile
//   monitor.folder_replay_late_frames     frames over LATE_FRAME_MS (25) meanwhile (the output line gives each one's time and gap)
//   monitor.folder_replay_mb              MB of CSV text read
//   monitor.folder_replay_records         records the model holds
import { cpSync, mkdirSync, mkdtempSync, realpathSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { buildProductionIde, installFrameRecorder, launchChromium, openIdePage, root, writePart } from './bench-support.mjs';
import { khzCycle } from './khz-cycle.mjs';
import { LATE_FRAME_MS } from './steal-sampler.mjs';

const seconds = Number(process.env.FOLDER_SECONDS ?? 90);
const { startIdeServer } = await buildProductionIde();
const base = realpathSync(mkdtempSync(join(tmpdir(), 'monitor-folder-bench-')));
const workspace = join(base, 'tutorial');
cpSync(join(root, 'examples/tutorial'), workspace, { recursive: true });
mkdirSync(join(workspace, 'logs'));
const W = '2026-11-26T12:00:00.000000Z';
const texts = { ORD: [], SUP: [], MSA: [], MSC: [], MSD: [] };
const L = (ns, m, ev, peer, port, size, detail) => texts[m].push(`${ns},${W},${m},${ev},${peer},${port},${size},${detail}`);
L(500_000_000_000, 'ORD', 'scheduler', '', '', 0, 'activate schemaCommande1');
const state = { release: 0 };
for (let c = 0; c < seconds * 1000; c++) khzCycle(L, c, state, true);
let bytes = 0;
for (const [m, lines] of Object.entries(texts)) {
  const p = join(workspace, 'logs', `${m}_26-Nov-2026-12h00m00s.csv`);
  writeFileSync(p, ['mono_ns,wall_time,module,event,peer,port,size,detail', ...lines].join('\n') + '\n');
  bytes += statSync(p).size;
}
for (const k of Object.keys(texts)) texts[k] = null;
const server = await startIdeServer({ workspace, port: 0, buildService: false });
let context;
try {
  context = await launchChromium(join(base, 'profile'));
  const page = await openIdePage(context, server);
  await installFrameRecorder(page);
  const r = await page.evaluate(async (lateMs) => {
    const ide = window.__ide;
    // the frames over 50 ms, with the scripts that ran in them (Long Animation Frames)
    const longFrames = [];
    const observer = new PerformanceObserver((list) => {
      for (const e of list.getEntries()) {
        if (longFrames.length < 20) longFrames.push({ ms: Math.round(e.duration), blocking: Math.round(e.blockingDuration),
          scripts: e.scripts.map((x) => `${x.invoker} ${x.sourceFunctionName || ''} ${Math.round(x.duration)}ms`).slice(0, 4) });
      }
    });
    observer.observe({ type: 'long-animation-frame' });
    window.__frames.start();
    await new Promise((done) => setTimeout(done, 100));
    const start = performance.now();
    await ide.monitor.openFolder('logs');
    const ms = performance.now() - start;
    const gaps = await window.__frames.stop();
    const ends = window.__frames.ends();
    const late = gaps.flatMap((g, i) => (g > lateMs ? [[Math.round(ends[i] - start), Math.round(g)]] : []));
    observer.disconnect();
    return { longFrames, ms, max: Math.max(...gaps), late, records: ide.monitor.runs.get('dir:logs')?.model.recordCount, label: ide.monitor.runs.get('dir:logs')?.label };
  }, LATE_FRAME_MS);
  const expected = Object.keys(texts).length;
  if (!r.label?.startsWith(`${expected} CSV log(s) in logs`)) throw new Error(`the folder was not read whole: ${r.label}`);
  const round = (x) => Math.round(x * 10) / 10;
  writePart('monitor-folder', {
    'monitor.folder_replay_ms': Math.round(r.ms),
    'monitor.folder_replay_max_frame_ms': round(r.max),
    'monitor.folder_replay_late_frames': r.late.length,
    'monitor.folder_replay_mb': round(bytes / 1e6),
    'monitor.folder_replay_records': r.records,
  });
  if (r.longFrames.length) console.error(`[monitor-folder] frames over 50 ms: ${JSON.stringify(r.longFrames)}`);
  console.log(`[monitor-folder] ${round(bytes / 1e6)} MB, ${r.records} records: shown after ${Math.round(r.ms)} ms, longest frame ${round(r.max)} ms, late frames (ms since asked, gap): ${JSON.stringify(r.late)}`);
} finally {
  await context?.close();
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
