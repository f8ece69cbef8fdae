import { chromium, type Browser, type Page } from 'playwright-core';
import { beforeAll, afterAll, expect } from 'vitest';
import { cpSync, mkdtempSync, rmSync, mkdirSync, realpathSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { startIdeServer, type IdeServer } from '../../server/ide-server.js';
import type {} from '../../src/app/ide-hook.js';

export const PKG = fileURLToPath(new URL('../..', import.meta.url));
export const TUTORIAL = join(PKG, '../../examples/tutorial');
export const MOBILE_ROBOT = join(PKG, '../../examples/mobile-robot');
export const SHOTS = join(PKG, 'test-output');

export const CHROMIUM_ARGS = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
  '--disable-component-update', '--no-first-run', '--disable-sync',
];

export interface Session {
  workspace: string;
  /** Replaceable: a test may restart the server on the same port. */
  server: IdeServer;
  browser: Browser;
  page: Page;
  userDataDir: string;
  close(): Promise<void>;
}

/**
 * A temp copy of the tutorial, the real IDE server on a free port, and a fresh headless Chromium.
 * `viewport` and `deviceScaleFactor` make a real screen: a 1366x768 laptop at 150 % is a viewport of
 * 911x512 CSS pixels at a scale of 1.5; `reducedMotion: 'reduce'` is the system's "reduce motion".
 */
export interface SessionOptions {
  buildService?: boolean; empty?: boolean; example?: string; limits?: Record<string, number>; port?: number;
  viewport?: { width: number; height: number }; deviceScaleFactor?: number; reducedMotion?: 'reduce' | 'no-preference';
}

export async function startSession(opts: SessionOptions = {}): Promise<Session> {
  const base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-e2e-')));
  // named after its example, as `contract serve examples/mobile-robot` names it (the top bar shows it)
  const workspace = join(base, opts.empty ? 'workspace' : basename(opts.example ?? TUTORIAL));
  if (opts.empty) mkdirSync(workspace);
  else cpSync(opts.example ?? TUTORIAL, workspace, { recursive: true, filter: (src) => !/[\/]logs$/.test(src) });
  const server = await startIdeServer({ workspace, port: opts.port ?? Number(process.env.E2E_PORT ?? 0), buildService: opts.buildService ?? true, ...(opts.limits ? { limits: opts.limits } : {}) });
  const userDataDir = join(base, 'chromium-profile');
  mkdirSync(userDataDir);
  mkdirSync(SHOTS, { recursive: true });
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: '/usr/bin/chromium', args: CHROMIUM_ARGS, viewport: opts.viewport ?? { width: 1440, height: 900 },
    ...(opts.deviceScaleFactor ? { deviceScaleFactor: opts.deviceScaleFactor } : {}),
    ...(opts.reducedMotion ? { reducedMotion: opts.reducedMotion } : {}),
  });
  const browser = context.browser() as Browser;
  const page = context.pages()[0] ?? (await context.newPage());
  page.on('pageerror', (e) => console.error('[page error]', e.message));
  if (process.env.E2E_CPU_THROTTLE) await (await context.newCDPSession(page)).send('Emulation.setCPUThrottlingRate', { rate: Number(process.env.E2E_CPU_THROTTLE) });
  const session: Session = {
    workspace, server, browser, page, userDataDir,
    async close() {
      await context.close().catch(() => undefined);
      await this.server.close().catch(() => undefined);
      rmSync(base, { recursive: true, force: true });
    },
  };
  return session;
}

/**
 * The session of the tests of a file (called at its top level) or of a describe block (called in
 * it): started in a beforeAll (startSession, then `beforeOpen` — files written in the workspace,
 * page listeners —, openIde, then `afterOpen`), closed in an afterAll. The object returned is the
 * session once started (a test or hook reads it as a Session; `s.server = …` replaces its server);
 * read before, it throws. `timeout`: the beforeAll's bound, 60 s unless given.
 */
export function ideSession(opts: SessionOptions & { timeout?: number } = {}, hooks: {
  beforeOpen?(s: Session): unknown; afterOpen?(s: Session): unknown;
} = {}): Session {
  let current: Session | undefined;
  const { timeout = 60_000, ...options } = opts;
  beforeAll(async () => {
    current = await startSession(options);
    await hooks.beforeOpen?.(current);
    await openIde(current);
    await hooks.afterOpen?.(current);
  }, timeout);
  afterAll(async () => {
    await current?.close();
  });
  const started = (): Session => {
    if (!current) throw new Error('the IDE session is not started: read it in a test or hook of the block that made it');
    return current;
  };
  return new Proxy({} as Session, {
    get: (_, key) => {
      const s = started();
      const value: unknown = Reflect.get(s, key, s);
      return typeof value === 'function' ? (value as (...a: unknown[]) => unknown).bind(s) : value;
    },
    set: (_, key, value) => Reflect.set(started(), key, value),
  });
}

export async function openIde(s: Session): Promise<number> {
  const t0 = Date.now();
  await s.page.goto(s.server.openUrl); // the token becomes the session cookie
  await s.page.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
  return Date.now() - t0;
}

export async function shot(page: Page, name: string): Promise<void> {
  // a picture for people, not a check: on a stalled host it is skipped (said), never the test's 30 s
  await page.screenshot({ path: join(SHOTS, `${name}.png`), timeout: 10_000 }).catch((e: Error) => console.error(`screenshot ${name} skipped: ${e.message.split('\n')[0]}`));
}

/** Puts the cursor of the active editor on the first occurrence of `text` (offset chars into it). */
export async function placeCursor(page: Page, text: string, offset = 0, occurrence = 0): Promise<void> {
  const ok = await page.evaluate(({ text, offset, occurrence }) => {
    const ide = window.__ide;
    const model = ide.editors.editor.getModel()!;
    const value = model.getValue();
    let at = -1;
    for (let i = 0; i <= occurrence; i++) at = value.indexOf(text, at + 1);
    if (at < 0) return false;
    const pos = model.getPositionAt(at + offset);
    ide.editors.editor.setPosition(pos);
    ide.editors.editor.revealPositionInCenter(pos);
    ide.editors.editor.focus();
    return true;
  }, { text, offset, occurrence });
  if (!ok) throw new Error(`text not found in the active editor: ${text}`);
}

/**
 * Waits until the language server answers a rename at the active editor's cursor with a range (its
 * `textDocument/prepareRename`): before that, F2 finds nothing to rename (the server still building
 * the documents after an edit) and no rename box opens.
 */
export async function waitRenameLocation(page: Page, timeout = 30_000): Promise<void> {
  await page.waitForFunction(async () => {
    const ide = window.__ide;
    const model = ide.editors.editor.getModel();
    const at = ide.editors.editor.getPosition();
    if (!model || !at) return false;
    const r = await ide.lsp.request('textDocument/prepareRename', { textDocument: { uri: model.uri.toString() }, position: { line: at.lineNumber - 1, character: at.column - 1 } }).catch(() => null);
    return r !== null && r !== undefined;
  }, undefined, { timeout, polling: 250 });
}

/** Opens `file`, puts the cursor `offset` characters into the first `text`, and renames what is there to `newName` with F2 (the editor's rename box, Enter). */
export async function renameWithF2(page: Page, file: string, text: string, offset: number, newName: string): Promise<void> {
  await openFile(page, file);
  await placeCursor(page, text, offset);
  await waitRenameLocation(page);
  await placeCursor(page, text, offset); // the editor focused again (the wait ran in the page, not in the editor)
  await page.keyboard.press('F2');
  await page.waitForFunction(() => document.activeElement?.classList.contains('rename-input'));
  await page.keyboard.press('Control+a');
  await page.keyboard.type(newName);
  await page.keyboard.press('Enter');
}

export async function activeValue(page: Page): Promise<string> {
  return page.evaluate(() => window.__ide.editors.editor.getModel()!.getValue());
}

export async function activeTab(page: Page): Promise<string | null> {
  return page.locator('.tab.active').getAttribute('data-path');
}

export async function openFile(page: Page, path: string): Promise<void> {
  const parts = path.split('/');
  for (let i = 1; i < parts.length; i++) {
    const dir = parts.slice(0, i).join('/');
    const row = page.locator(`.tree-row[data-path="${dir}"]`);
    if ((await row.locator('.twisty').textContent()) === '▸') await row.click();
  }
  await clickOrExplain(page, `.tree-row[data-path="${path}"]`);
  await page.waitForFunction((p) => document.querySelector('.tab.active')?.getAttribute('data-path') === p, path);
}

/**
 * Clicks. A click waits for two animation frames to see the element stable; when it times out, the
 * page is asked for one frame: none in 2 s (a page Chromium stopped drawing, seen once on a loaded CI
 * machine right after a reload) brings the page to the front and clicks once more, saying so on
 * stderr; otherwise the error says what the page did, with a screenshot.
 */
export async function clickOrExplain(page: Page, selector: string): Promise<void> {
  const drawsFrames = () => Promise.race([
    page.evaluate(() => new Promise<string>((r) => requestAnimationFrame(() => r('the page draws frames')))).catch((err: Error) => `evaluate failed: ${err.message}`),
    new Promise<string>((r) => setTimeout(() => r('no animation frame in 2 s: the page does not draw'), 2000)),
  ]);
  try {
    await page.locator(selector).click({ timeout: 15_000 });
  } catch (e) {
    const frame = await drawsFrames();
    const ready = await page.evaluate(() => document.body.dataset.ready).catch(() => '?');
    await page.screenshot({ path: join(SHOTS, `click-failed-${Date.now()}.png`), timeout: 5000 }).catch(() => undefined);
    if (frame.startsWith('no animation frame')) {
      console.error(`[harness] ${selector}: ${frame} (ready=${ready}); bringing the page to the front and clicking again`);
      await page.bringToFront();
      await page.locator(selector).click({ timeout: 15_000 });
      return;
    }
    (e as Error).message = `[harness] ${selector}: ${frame}; ready=${ready}\n${(e as Error).message}`;
    throw e;
  }
}

/**
 * A notice with `text` shown from now on: the wait starts at once, to be awaited later. A notice
 * stays 5 s on the page: waited for only after the checks of the files a step wrote (10 s and more
 * on a loaded machine), it had come and gone (a rename's toast, seen under load).
 */
export function toastAfter(page: Page, text: string, timeout = 30_000): Promise<void> {
  const shown = page.locator('.toast', { hasText: text }).first().waitFor({ timeout });
  shown.catch(() => undefined); // awaited by the caller: its failure is theirs, not an unhandled rejection
  return shown;
}

/** Waits until every file is saved (status bar). */
export async function waitSaved(page: Page): Promise<void> {
  await page.waitForFunction(() => document.getElementById('status-save')?.textContent?.includes('All saved'), undefined, { timeout: 10_000 });
}

/** A second browser on the same server (its own profile, so its own localStorage), the IDE ready in it. */
export async function openAnotherBrowser(s: Session, name: string): Promise<{ page: Page; close(): Promise<void> }> {
  const dir = join(s.userDataDir, '..', `chromium-${name}`);
  mkdirSync(dir, { recursive: true });
  const context = await chromium.launchPersistentContext(dir, {
    executablePath: '/usr/bin/chromium', args: CHROMIUM_ARGS, viewport: { width: 1440, height: 900 },
  });
  const page = context.pages()[0] ?? (await context.newPage());
  page.on('pageerror', (e) => console.error(`[page error ${name}]`, e.message));
  await page.goto(s.server.openUrl);
  await page.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
  return { page, close: () => context.close().catch(() => undefined) };
}

/** Another tab of the same browser as `page` (its own session storage, the same cookies), the IDE loaded in it. */
export async function openAnotherTab(s: Session, page: Page): Promise<Page> {
  const tab = await page.context().newPage();
  await tab.goto(`${s.server.url}/`);
  await tab.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
  return tab;
}

/** The line of the active editor's cursor (1-based). */
export async function cursorLine(page: Page): Promise<number> {
  return page.evaluate(() => window.__ide.editors.editor.getPosition()!.lineNumber);
}

/**
 * The IDE in two browsers (each its own storage) on one server, both with `path` open: the set-up
 * of the tests of one file edited in two places. `onPageError` hears both pages' errors.
 */
export async function startTwoBrowsersOn(path: string, name: string, onPageError?: (which: 'A' | 'B', message: string) => void): Promise<{ s: Session; other: { page: Page; close(): Promise<void> } }> {
  const s = await startSession({ buildService: false });
  if (onPageError) s.page.on('pageerror', (e) => onPageError('A', e.message));
  await openIde(s);
  const other = await openAnotherBrowser(s, name);
  if (onPageError) other.page.on('pageerror', (e) => onPageError('B', e.message));
  await openFile(s.page, path);
  await openFile(other.page, path);
  return { s, other };
}

/** Shows the Monitor in the side pane (a click on its button when it is not shown yet). */
export async function showMonitor(page: Page): Promise<void> {
  if (!(await page.locator('.side-pane .monitor-view').isVisible())) await page.locator('#btn-monitor').click();
  await page.locator('.side-pane .monitor-view').waitFor();
}

/**
 * Copies the trace file `fixture` into the session's workspace as `name` and replays it in the
 * Monitor (its entry in the run list, once the list offers it).
 */
export async function replayTraceFile(s: Session, fixture: string, name: string): Promise<void> {
  cpSync(fixture, join(s.workspace, name));
  await showMonitor(s.page);
  const option = s.page.locator(`.monitor-sources option[value="file:${name}"]`);
  await expect.poll(() => option.count(), { timeout: 10_000 }).toBe(1);
  await s.page.locator('.monitor-sources').selectOption(`file:${name}`);
}

/**
 * Types a step into the Simulate panel's step field (a one-line Monaco editor) and clicks Inject
 * (not Enter: under load a completion list can open late and take the Enter).
 */
export async function injectStep(page: Page, text: string): Promise<void> {
  await page.locator('.sim-step .view-lines').click();
  await page.keyboard.press('ControlOrMeta+A');
  await page.keyboard.press('Backspace');
  await page.keyboard.type(text, { delay: 5 });
  await page.keyboard.press('Escape'); // a suggestion list the typing opened
  await page.click('.sim-inject');
}
