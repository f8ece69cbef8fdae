/**
 * End-to-end, in headless Chromium on the real IDE server and its build service (bwrap): a Build &
 * Run watched in one tab stays within reach once that tab is closed. Tab A runs the tutorial (a
 * short run) and is closed; tab B, opened after the job ended (so it followed nothing), opens the
 * Monitor: its run list offers the job (`GET /api/recent-runs`, the build service's listing of the
 * IDE server's jobs), labelled with its start time and how it ended, and picking it replays the
 * job's CSV logs as tab A replayed them: the same records.
 */
import { describe, it, expect } from 'vitest';
import { spawnSync } from 'node:child_process';
import type { Page } from 'playwright-core';
import { ideSession, shot, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const canBuild =
  (await import('@contract-studio/build-service').then((m) => typeof (m as Record<string, unknown>).createBuildServer === 'function').catch(() => false)) &&
  spawnSync('bwrap', ['--version']).status === 0;

const IDE_PORT = 8001;

let s: Session;

const shownRecords = (page: Page) => page.evaluate(() => window.__ide.monitor.current?.recordCount as number | undefined);
const label = (page: Page) => page.locator('.monitor-source').textContent();

describe.skipIf(!canBuild)("Monitor: a Build & Run job of a closed tab, from another tab's run list", () => {
  s = ideSession({ port: IDE_PORT });

  it('tab A runs the tutorial and is closed; tab B opens the Monitor and replays that job from its run list', async () => {
    const a = s.page;
    await a.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 2 })));
    await a.locator('#btn-run').click();
    await expect.poll(() => a.locator('#status-job').getAttribute('data-status'), { timeout: 150_000, interval: 1000 }).toBe('succeeded');
    const jobId = await a.evaluate(() => (JSON.parse(sessionStorage.getItem('contract-studio:followed-job') ?? '{}') as { jobId?: string }).jobId);
    expect(jobId).toMatch(/^j-[0-9a-f]{32}$/);
    // tab A's own replay of the job's CSV logs: what tab B must show
    if (!(await a.locator('.side-pane .monitor-view').isVisible())) await a.locator('#btn-monitor').click();
    const mine = a.locator(`.monitor-sources option[value="job:${jobId}"]`);
    await expect.poll(() => mine.count(), { timeout: 30_000 }).toBe(1);
    await a.locator('.monitor-sources').selectOption(`job:${jobId}`);
    await expect.poll(() => label(a), { timeout: 20_000 }).toContain(`Build & Run job ${jobId} · CSV logs`);
    const records = await shownRecords(a);
    expect(records).toBeGreaterThan(100);
    // tab A's own list offers the job once (its own runs, not the listed entry again)
    expect(await a.locator('.monitor-sources option', { hasText: jobId }).allTextContents()).not.toContainEqual(expect.stringContaining('· started '));

    // tab B: opened after the job ended (nothing to follow), tab A closed
    const context = a.context();
    const b = await context.newPage();
    b.on('pageerror', (e) => console.error('[page error B]', e.message));
    await a.close();
    await b.goto(`${s.server.url}/`);
    await b.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    expect(await b.evaluate(() => sessionStorage.getItem('contract-studio:followed-job'))).toBeNull();
    await b.locator('#btn-monitor').click();
    const listed = b.locator(`.monitor-sources option[value="job:${jobId}"]`);
    await expect.poll(() => listed.count(), { timeout: 20_000 }).toBe(1);
    expect(await listed.textContent()).toMatch(new RegExp(`^Build & Run job ${jobId} · started (\\d{4}-\\d\\d-\\d\\d )?\\d\\d:\\d\\d:\\d\\d · ended: succeeded$`));
    await shot(b, 'monitor-recent-job-listed');
    await b.locator('.monitor-sources').selectOption(`job:${jobId}`);
    await expect.poll(() => label(b), { timeout: 30_000 }).toBe(`Build & Run job ${jobId} · CSV logs · ended: succeeded`);
    expect(await shownRecords(b)).toBe(records);
    // picked, it is the job's replay in the list, not a second entry of it
    expect(await b.locator('.monitor-sources option', { hasText: jobId }).count()).toBe(1);
    await shot(b, 'monitor-recent-job-replayed');
  }, 240_000);
});
