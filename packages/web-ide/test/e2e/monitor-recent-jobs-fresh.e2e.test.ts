/**
 * End-to-end, in headless Chromium on the real IDE server and its build service (bwrap): the
 * Monitor's list of recent Build & Run jobs stays fresh while it is open. Tab B opens the Monitor
 * and keeps it open; it does not hear the IDE server's announcements of the jobs the tabs start (its
 * /api/events frames `job` and `jobs` are dropped on their way, as a tab whose events socket is
 * down would miss them; everything else comes through), so it does not follow tab A's run by
 * itself. Tab A then runs the tutorial: B's open list offers A's job, still running, within a few
 * seconds (read again every RECENT_RUNS_MS while shown), and picking it follows it live. Before,
 * the list was read only when the Monitor was shown again or a job of B's own ended: A's job never
 * appeared in it.
 */
import { describe, it, expect } from 'vitest';
import { spawnSync } from 'node:child_process';
import type { Page } from 'playwright-core';
import { ideSession, shot } from './harness.js';

const canBuild = spawnSync('bwrap', ['--version']).status === 0;
/** One of the ports this test may use (E2E_RECENT_FRESH_PORT to choose another). */
const PORT = Number(process.env.E2E_RECENT_FRESH_PORT ?? 8111);

const records = (page: Page) => page.evaluate(() => ((window as any).__ide.monitor.current?.recordCount as number | undefined) ?? 0);

describe.skipIf(!canBuild)("Monitor: another tab's running job in an open run list", () => {
  const s = ideSession({ port: PORT });

  it("appears while the list is open, still running, and is followed live once picked", async () => {
    const a = s.page;
    const b = await a.context().newPage();
    b.on('pageerror', (e) => console.error('[page error B]', e.message));
    // B misses the announcements of the tabs' jobs (and so follows none by itself): only its run list can offer A's job
    await b.routeWebSocket(/\/api\/events/, (ws) => {
      const server = ws.connectToServer();
      server.onMessage((m) => {
        if (!/^\{"event":"jobs?"/.test(String(m))) ws.send(m);
      });
    });
    await b.goto(`${s.server.url}/`);
    await b.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    await b.locator('#btn-monitor').click();
    await expect.poll(() => b.locator('.side-pane .monitor-view').isVisible(), { timeout: 10_000 }).toBe(true);

    // tab A runs the tutorial for a while
    await a.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 25 })));
    await a.locator('#btn-run').click();
    let jobId: string | undefined;
    await expect.poll(async () => (jobId = await a.evaluate(() => (JSON.parse(sessionStorage.getItem('contract-studio:followed-job') ?? '{}') as { jobId?: string }).jobId)), { timeout: 30_000 }).toMatch(/^j-[0-9a-f]{32}$/);
    // its run has begun: A's Monitor has its records
    await expect.poll(() => records(a), { timeout: 240_000, interval: 500 }).toBeGreaterThan(20);
    const status = () => a.locator('#status-job').getAttribute('data-status');
    expect(await status()).toBe('running');

    // B, its list open all along, offers it, running
    const listed = b.locator(`.monitor-sources option[value="job:${jobId}"]`);
    const seenAt = Date.now();
    await expect.poll(() => listed.count(), { timeout: 10_000, interval: 200 }).toBe(1);
    console.log(`recent-jobs-fresh: A's running job listed in B's open run list ${Date.now() - seenAt} ms after its first records`);
    expect(await listed.textContent()).toMatch(new RegExp(`^Build & Run job ${jobId} · started (\\d{4}-\\d\\d-\\d\\d )?\\d\\d:\\d\\d:\\d\\d · running: pick it to follow it live$`));
    // B follows no job by itself (it heard of none)
    expect(await b.evaluate(() => sessionStorage.getItem('contract-studio:followed-job'))).toBeNull();
    await shot(b, 'monitor-recent-job-running-listed');

    // picked: followed live, its records coming while A's run goes on
    await b.locator('.monitor-sources').selectOption(`job:${jobId}`);
    await expect.poll(() => b.locator('.monitor-view').getAttribute('data-mode'), { timeout: 10_000 }).toBe('live');
    await expect.poll(() => b.locator('.monitor-source').textContent(), { timeout: 10_000 }).toContain(jobId!);
    const first = await records(b);
    await expect.poll(() => records(b), { timeout: 10_000, interval: 300 }).toBeGreaterThan(first);
    expect(await status()).toBe('running');
    await shot(b, 'monitor-recent-job-followed-live');
    // the job ends; B's entry says how, as A's status does
    await expect.poll(status, { timeout: 120_000, interval: 1000 }).not.toBe('running');
  }, 400_000);
});
