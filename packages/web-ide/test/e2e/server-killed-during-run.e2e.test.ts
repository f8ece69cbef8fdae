/**
 * The IDE server killed (SIGKILL) during a Build & Run followed by two tabs, then started again as
 * `contract serve` is, with a new session token (docs/ide.md "Several tabs"): the job died with the
 * server. Both tabs must end up telling that, alike — the status bar, the Build & Run panel's log
 * and the Monitor's run — and neither may show the run as still going. They said "disconnected:
 * lost the connection to the build service" for ever (a reloaded tab said the job was gone), and
 * the Monitor promised the run's CSV logs "if the build service is still there".
 * The server runs in a child process (the built dist-server/, `npm run build`) so that it can be
 * killed; real build service, bwrap sandbox, headless Chromium.
 * Then each tab is reloaded: both say the job gone again, alike. The tab that had only followed the
 * run said "No build yet" and its Monitor "No run yet" (it forgot a job it had seen lost), where
 * the tab that started it said it gone. And after the reload the Monitor's run list no longer had
 * the run (the status bar and the log said it gone, the Monitor nothing): it lists it, ended: lost.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { chromium, type BrowserContext, type Page } from 'playwright-core';
import { cpSync, mkdtempSync, realpathSync, chmodSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { tmpdir } from 'node:os';
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { CHROMIUM_ARGS, PKG, TUTORIAL, shot } from './harness.js';

const canBuild = spawnSync('bwrap', ['--version']).status === 0;
/** Fixed, as the restarted server must take the same port; another with E2E_KILLED_SERVER_PORT (two checkouts testing at once). */
const PORT = Number(process.env.E2E_KILLED_SERVER_PORT ?? 41420);
const SERVER = join(PKG, 'dist-server/ide-server.js');

/** `contract serve` in a child process on PORT: its process and the address with its new token. */
function startServer(workspace: string): Promise<{ child: ChildProcess; openUrl: string }> {
  const code = `import(${JSON.stringify(SERVER)}).then(async (m) => { const s = await m.startIdeServer({ workspace: ${JSON.stringify(workspace)}, port: ${PORT}, buildService: true }); console.log('READY ' + s.openUrl); })`;
  const child = spawn(process.execPath, ['-e', code], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((ready, fail) => {
    let out = '';
    child.stdout!.on('data', (d) => {
      out += String(d);
      const m = out.match(/READY (\S+)/);
      if (m) ready({ child, openUrl: m[1]! });
    });
    child.on('exit', (code) => fail(new Error(`the IDE server exited (${code}) before it was ready`)));
  });
}

/** What a tab tells of the job: the status bar, the panel's last log line, the Monitor's run and mode, Build & Run's button. */
const told = (page: Page) => page.evaluate(() => {
  const rows = [...document.querySelectorAll('.log-row')];
  return {
    status: document.getElementById('status-job')?.dataset.status,
    statusText: document.getElementById('status-job')?.textContent,
    lastLine: rows[rows.length - 1]?.textContent ?? '',
    monitor: (document.querySelector('.monitor-view') as HTMLElement | null)?.dataset.mode,
    monitorRun: document.querySelector('.monitor-source')?.textContent,
    /** The Monitor's run list (its picker's entries). */
    monitorRuns: [...document.querySelectorAll('.monitor-sources option')].map((o) => o.textContent ?? ''),
    canRun: !(document.getElementById('btn-run') as HTMLButtonElement).disabled,
  };
});

describe.skipIf(!canBuild)('the IDE server killed during a Build & Run', () => {
  let base: string;
  let server: { child: ChildProcess; openUrl: string } | undefined;
  let context: BrowserContext;
  beforeAll(async () => {
    base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-e2e-killed-')));
    chmodSync(base, 0o755); // the sandboxed job's uid walks through it
    const workspace = join(base, 'tutorial');
    cpSync(TUTORIAL, workspace, { recursive: true, filter: (src) => !/[\/]logs$/.test(src) });
    server = await startServer(workspace);
    context = await chromium.launchPersistentContext(join(base, 'profile'), { executablePath: '/usr/bin/chromium', args: CHROMIUM_ARGS, viewport: { width: 1440, height: 900 } });
  });
  afterAll(async () => {
    await context?.close().catch(() => undefined);
    server?.child.kill('SIGKILL');
    rmSync(base, { recursive: true, force: true });
  });

  it('both tabs end up saying the job was lost with the server (status, log, Monitor), neither shows it going on', async () => {
    const a = context.pages()[0] ?? (await context.newPage());
    await a.goto(server!.openUrl);
    await a.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    const b = await context.newPage();
    await b.goto(`http://127.0.0.1:${PORT}/`);
    await b.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    await a.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 60, start: 'GLB.mission(consigne={1.0,2.0,3.0})', cpus: '0' })));
    await a.locator('#btn-run').click();
    // tab B follows A's run (Several tabs): both stream its log, both Monitors live
    for (const tab of [a, b]) await tab.locator('.log-row[data-source="MSC"]').first().waitFor({ timeout: 140_000 });
    for (const tab of [a, b]) expect(await told(tab)).toMatchObject({ status: 'running', monitor: 'live', canRun: false });

    server!.child.kill('SIGKILL');
    await new Promise((r) => setTimeout(r, 1500));
    const workspace = join(base, 'tutorial');
    server = await startServer(workspace); // as `contract serve` again: a new token
    // until a tab has the new session, the service cannot be asked: neither says running, nor gone yet
    await new Promise((r) => setTimeout(r, 6000)); // past the job stream's retries (4.5 s)
    for (const tab of [a, b]) {
      const t = await told(tab);
      expect(t.status, JSON.stringify(t)).toBe('disconnected');
      expect(t.canRun).toBe(true);
      expect(t.monitor).toBe('replay');
    }
    // the new address opened in a third tab: the browser has the session again, for every tab
    const c = await context.newPage();
    await c.goto(server.openUrl);
    await c.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    await c.close();
    for (const tab of [a, b]) await expect.poll(async () => (await told(tab)).status, { timeout: 15_000 }).toBe('gone');
    await shot(a, 'server-killed-01-tab-a');
    await shot(b, 'server-killed-02-tab-b');
    const [ta, tb] = [await told(a), await told(b)];
    // the same words in both tabs
    expect(ta.statusText).toBe(tb.statusText);
    expect(ta.monitorRun).toBe(tb.monitorRun);
    expect(ta.statusText).toContain('no longer known to the build service: the IDE server was restarted');
    for (const t of [ta, tb]) {
      expect(t.lastLine).toContain('no longer known to the build service');
      expect(t.monitorRun).toContain('ended: lost with the IDE server');
      expect(t.monitorRun).not.toContain('if the build service is still there');
      expect(t.monitor).toBe('replay');
      expect(t.canRun).toBe(true);
    }
    // and it stays so
    await new Promise((r) => setTimeout(r, 3000));
    expect(await told(a)).toEqual(ta);
    expect(await told(b)).toEqual(tb);

    // a reload of either tab says it gone again, the tab that followed the run as the one that started it
    const reloaded = async (tab: Page) => {
      await tab.reload();
      await tab.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
      await expect.poll(async () => (await told(tab)).status, { timeout: 15_000 }).toBe('gone');
      // the Monitor lists the run again, said lost as before the reload (its records were the page's: none left to read)
      await expect.poll(async () => (await told(tab)).monitorRun ?? '', { timeout: 15_000 }).toContain('ended: lost with the IDE server');
      return told(tab);
    };
    const rb = await reloaded(b);
    const ra = await reloaded(a);
    await shot(a, 'server-killed-03-tab-a-reloaded');
    await shot(b, 'server-killed-04-tab-b-reloaded');
    expect(rb).toEqual(ra);
    expect(rb.statusText).toBe(tb.statusText);
    const job = /Build & Run job (\S+)/.exec(tb.monitorRun ?? '')?.[1];
    expect(job, tb.monitorRun ?? '').toBeTruthy();
    expect(rb.monitorRun).toBe(`Build & Run job ${job} · ended: lost with the IDE server (it was stopped or restarted, which ends its jobs)`);
    expect(rb.monitorRuns.filter((o) => o.includes(`Build & Run job ${job} `)), rb.monitorRuns.join('\n')).toEqual([rb.monitorRun]);
    expect(rb.monitor).toBe('replay');
    expect(rb.canRun).toBe(true);
    // and again: the lost job stays the tab's last until it follows another
    expect(await reloaded(b)).toEqual(rb);
  }, 300_000);
});
