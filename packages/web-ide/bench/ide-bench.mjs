#!/usr/bin/env node
// IDE benchmark -> /work/main/bench/parts/ide.json (flat metric -> number).
//   ide.bundle_bytes            JS+CSS of the production build (all chunks and workers)
//   ide.initial_bundle_bytes    what the first load fetches (entry JS+CSS, Monaco editor worker, language worker)
//   ide.first_load_ms           navigation start -> editor ready (performance mark 'ide:ready': files open, all 13
//                               tutorial files built and diagnosed in the worker), median of 3 cold loads, headless Chromium
//   ide.editor_open_ms          navigation start -> first file shown in Monaco with the language server connected
//   ide.first_load_wall_ms      the same seen from the test driver (page.goto -> ready selector, includes polling)
//   ide.diagnostics_latency_ms  keystroke -> error marker in the editor (median of 7)
//   ide.log_10k_lines_max_frame_ms  longest frame while 10k log lines/s stream into the log panel for 3 s
import { readdirSync, statSync, readFileSync, cpSync, mkdtempSync, rmSync, realpathSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { buildProductionIde, installFrameRecorder, launchChromium, pkg, root, writePart } from './bench-support.mjs';

const { startIdeServer } = await buildProductionIde();

const assets = join(pkg, 'dist/assets');
const files = readdirSync(assets).filter((f) => /\.(js|css)$/.test(f));
const size = (f) => statSync(join(assets, f)).size;
const bundleBytes = files.reduce((a, f) => a + size(f), 0);
const html = readFileSync(join(pkg, 'dist/index.html'), 'utf8');
const entry = files.filter((f) => html.includes(f));
const initial = [...entry, ...files.filter((f) => /^(editor\.worker|language-worker)-/.test(f))];
const initialBytes = [...new Set(initial)].reduce((a, f) => a + size(f), 0);

const base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-bench-')));
const workspace = join(base, 'tutorial');
cpSync(join(root, 'examples/tutorial'), workspace, { recursive: true });
const server = await startIdeServer({ workspace, port: 0, buildService: false });
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

const loads = [];
const marks = [];
let page;
let context;
try {
  for (let i = 0; i < 3; i++) {
    context = await launchChromium(join(base, `profile-${i}`));
    page = context.pages()[0] ?? (await context.newPage());
    const t0 = Date.now();
    await page.goto(server.openUrl);
    await page.waitForSelector('body[data-ready=true]', { timeout: 60_000 });
    loads.push(Date.now() - t0);
    marks.push(await page.evaluate(() => Object.fromEntries(performance.getEntriesByType('mark').filter((m) => m.name.startsWith('ide:')).map((m) => [m.name.slice(4), Math.round(m.startTime)]))));
    if (i < 2) await context.close();
  }

  // keystroke -> marker, measured inside the page
  await page.evaluate(async () => {
    const ide = window.__ide;
    await ide.editors.open('smodule3.contract');
  });
  const latencies = [];
  for (let i = 0; i < 7; i++) {
    const wantError = i % 2 === 0;
    await page.evaluate((wantError) => {
      const ide = window.__ide;
      const model = ide.editors.editor.getModel();
      const off = model.getValue().indexOf(wantError ? 'C=1ms' : 'C=1xms') + 3;
      ide.editors.editor.setPosition(model.getPositionAt(off));
      ide.editors.editor.focus();
      window.__lat = new Promise((resolve) => {
        let t0 = 0;
        window.addEventListener('keydown', () => (t0 = performance.now()), { capture: true, once: true });
        const sub = ide.monaco.editor.onDidChangeMarkers(() => {
          const errs = ide.monaco.editor.getModelMarkers({ resource: model.uri }).filter((m) => m.severity === 8).length;
          if (t0 && (errs > 0) === wantError) {
            sub.dispose();
            resolve(performance.now() - t0);
          }
        });
      });
    }, wantError);
    await page.keyboard.press(wantError ? 'x' : 'Delete');
    latencies.push(await page.evaluate(() => window.__lat));
  }

  // log panel under 10k lines/s for 3 s
  await installFrameRecorder(page);
  const maxFrame = await page.evaluate(async () => {
    const ide = window.__ide;
    document.querySelector('.panel-tab[data-panel=output]').click();
    window.__frames.start();
    const sources = ['MSA', 'MSC', 'MSD', 'ORD', 'SUP'];
    let n = 0;
    const start = performance.now();
    await new Promise((resolve) => {
      const timer = setInterval(() => {
        const due = Math.floor(((performance.now() - start) / 1000) * 10_000);
        for (; n < due; n++) ide.build.append({ t: Date.now(), step: 'run', source: sources[n % 5], stream: n % 7 ? 'stdout' : 'stderr', line: `line ${n} activation period ${n >> 4}` });
        if (performance.now() - start > 3000) {
          clearInterval(timer);
          resolve();
        }
      }, 10);
    });
    return Math.max(...(await window.__frames.stop()));
  });

  const result = {
    'ide.bundle_bytes': bundleBytes,
    'ide.initial_bundle_bytes': initialBytes,
    'ide.first_load_ms': median(marks.map((m) => m.ready)),
    'ide.first_load_wall_ms': median(loads),
    'ide.editor_open_ms': median(marks.map((m) => m['editor-open'])),
    'ide.diagnostics_latency_ms': Math.round(median(latencies) * 10) / 10,
    'ide.log_10k_lines_max_frame_ms': Math.round(maxFrame * 10) / 10,
  };
  writePart('ide', result);
  console.log(JSON.stringify({ ...result, loads, latencies: latencies.map((l) => Math.round(l)) }));
  console.log('load phases (ms since navigation start):', JSON.stringify(marks));
} finally {
  await context?.close().catch(() => undefined);
  await server.close();
  rmSync(base, { recursive: true, force: true });
}
