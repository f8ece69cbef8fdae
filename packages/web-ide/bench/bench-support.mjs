// What the browser benchmarks of the IDE share (ide, monitor-panel, monitor-live): building the
// production IDE, launching headless Chromium the way the machine allows, writing a part of
// bench/results.json.
import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const pkg = fileURLToPath(new URL('..', import.meta.url));
export const root = join(pkg, '../..');

/** Builds the IDE server (tsc) and the production bundle (vite), then returns the server's module. */
export async function buildProductionIde() {
  const node = process.execPath;
  execFileSync(node, [join(root, 'node_modules/typescript/bin/tsc'), '-p', join(pkg, 'tsconfig.server.json')], { stdio: 'inherit' });
  execFileSync(node, [join(root, 'node_modules/vite/bin/vite.js'), 'build', '--logLevel', 'warn'], { cwd: pkg, stdio: 'inherit' });
  return import(join(pkg, 'dist-server/index.js'));
}

const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update', '--no-first-run', '--disable-sync'];

/** A persistent Chromium context on the profile folder `dir` (created), 1440x900; `extraArgs` e.g. `--js-flags=--expose-gc`. */
export async function launchChromium(dir, extraArgs = []) {
  const { chromium } = await import('playwright-core');
  mkdirSync(dir, { recursive: true });
  return chromium.launchPersistentContext(dir, { executablePath: '/usr/bin/chromium', args: [...CHROMIUM_ARGS, ...extraArgs], viewport: { width: 1440, height: 900 } });
}

/** The IDE's page in `context`, loaded from `server` and ready (its first page, or a new one). */
export async function openIdePage(context, server) {
  const page = context.pages()[0] ?? (await context.newPage());
  await page.goto(server.openUrl);
  await page.waitForSelector('body[data-ready=true]', { timeout: 60_000 });
  return page;
}

/** Writes bench/parts/<name>.json (flat metric -> number), which bench/run-all.mjs merges. */
export function writePart(name, result) {
  const out = join(root, 'bench/parts');
  mkdirSync(out, { recursive: true });
  writeFileSync(join(out, `${name}.json`), JSON.stringify(result, null, 2) + '\n');
}

/**
 * Puts `window.__frames` in the page: `start()` records the gaps between animation frames (ms),
 * `stop()` waits for two more frames (a gap the measured work caused is counted) and returns them,
 * the first two left out (the recorder's own start).
 */
export async function installFrameRecorder(page) {
  await page.evaluate(() => {
    let times = []; // the start, then the end of each frame (performance.now())
    let running = false;
    const tick = (t) => {
      times.push(t);
      if (running) requestAnimationFrame(tick);
    };
    window.__frames = {
      start() {
        times = [performance.now()];
        running = true;
        requestAnimationFrame(tick);
      },
      async stop() {
        await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
        running = false;
        return times.slice(1).map((t, i) => t - times[i]).slice(2);
      },
      /** The end (performance.now()) of each frame whose gap stop() returned. */
      ends() {
        return times.slice(3);
      },
    };
  });
}
