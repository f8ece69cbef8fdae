/**
 * The Timeline's "last Build & Run" source reads the job's launcher lines as its trace-file and
 * folder sources read theirs: a module SIGKILLed from outside mid-run, in a real Build & Run of the
 * tutorial (bubblewrap), is marked in its lane at the line's time, and the header says it (`gone: MAB
 * at … ms (contract-launch: module MAB (pid N) died by signal 9 (Killed))`, the pid the one
 * its own `module_started` gave (in the sandbox's pid namespace).
 * The line's wall time is put on the records' clock as the Monitor's replay of the same job puts it
 * (job-launcher-lines.ts launcherLinesOnRecordClock): the two show it at the same moment of the run.
 * Before, this source read none of the job's launcher lines and marked nothing. Real IDE server and
 * build service, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { spawnSync } from 'node:child_process';
import { modulePid } from '@contract-studio/build-service/test-support/module-pid';
import { activationsFromLogs } from '../../src/views/run-logs.js';
import { startedPids } from '../../src/views/gone-activations.js';
import type { Page } from 'playwright-core';
import { ideSession, openFile, shot } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const canBuild = spawnSync('bwrap', ['--version']).status === 0;
/** One of the ports this test may use (E2E_TIMELINE_JOB_GONE_PORT to choose another). */
const PORT = Number(process.env.E2E_TIMELINE_JOB_GONE_PORT ?? 7121);
const MODULE = 'MAB';

describe.skipIf(!canBuild)("the Timeline's last Build & Run: a module SIGKILLed mid-run", () => {
  const s = ideSession({ port: PORT });

  it("is marked gone in its lane at the launcher's line's time, as the Monitor's replay of the job shows it", async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 10, start: 'GLB.mission(consigne={1.0,2.0,3.0})' })));
    await page.locator('#btn-run').click();
    const status = () => page.locator('#status-job').getAttribute('data-status');
    // the run has started (MAB's start record read live): its pid is the one the launcher's line will name
    const started = () => page.evaluate((m) => window.__ide.monitor.current?.live?.modules?.get(m)?.alive === true, MODULE);
    await expect.poll(started, { timeout: 240_000 }).toBe(true);
    let pid: number | undefined;
    await expect.poll(() => (pid = modulePid(MODULE)), { timeout: 20_000 }).toBeDefined();
    // the Timeline opened during the run reads the local logs: its read of the tree is held until
    // the job's logs are shown. That read's end, later, must not draw the local logs over the job's
    // (it did: the view said "No CSV logs in logs/ ..." with the last Build & Run selected)
    let releaseTree!: () => void;
    const treeHeld = new Promise<void>((r) => (releaseTree = r));
    let held = 0;
    let heldDone: Promise<void> | undefined;
    await page.route('**/api/tree', (route) => {
      if (held++ === 0) heldDone = treeHeld.then(() => route.continue());
      else void route.continue();
    });
    await page.locator('#btn-timeline').click();
    await page.locator('.timeline-view').waitFor();
    await expect.poll(() => held, { timeout: 10_000 }).toBeGreaterThan(0);
    await new Promise((r) => setTimeout(r, 1000));
    expect(await status()).toBe('running');
    process.kill(pid!, 'SIGKILL');
    await expect.poll(status, { timeout: 60_000 }).not.toBe('running');

    // the job's CSV logs fetched when it ended (the page says so): the Timeline's source is the last Build & Run
    await page.locator('.toast', { hasText: 'Run logs of' }).first().waitFor({ timeout: 60_000 });
    await expect.poll(() => page.locator('.timeline-source').inputValue(), { timeout: 30_000 }).toBe('run');
    await page.locator('.timeline-view .gone-mark').first().waitFor({ state: 'attached', timeout: 20_000 });
    releaseTree();
    await heldDone;
    await page.unroute('**/api/tree');
    await new Promise((r) => setTimeout(r, 1500)); // the held read ends, and its update with it
    await expect.poll(() => page.locator('.timeline-source').inputValue(), { timeout: 30_000 }).toBe('run');
    const info = () => page.locator('.timeline-view .muted').first().textContent();
    const header = new RegExp(`· gone: ${MODULE} at (\\d+\\.\\d{3}) ms \\(contract-launch: module ${MODULE} \\(pid \\d+\\) died by signal 9 \\(Killed\\)\\) ·`);
    await expect.poll(info, { timeout: 20_000 }).toMatch(header);
    const mark = page.locator(`.timeline-view .gone-mark[data-module="${MODULE}"]`);
    expect(await mark.count()).toBe(1);
    expect(await mark.locator('title').textContent()).toMatch(new RegExp(`^${MODULE} gone at \\d+\\.\\d{3} ms: contract-launch: module ${MODULE} \\(pid \\d+\\) died by signal 9 \\(Killed\\)$`));
    // the other modules' end lines (exited with status 0 at the run's end) mark nothing
    expect(await page.locator('.timeline-view .gone-mark').count()).toBe(1);
    const text = (await info())!;
    const goneMs = Number(header.exec(text)![1]);
    const spanMs = Number(/ · (\d+\.\d) ms(?: · |$)/.exec(text)![1]);
    // a second or so into the run (the kill came then), well before its end
    expect(goneMs).toBeGreaterThan(0);
    expect(goneMs).toBeLessThan(spanMs - 4000);
    await shot(page, 'timeline-job-launcher-gone');

    // the Monitor's replay of the same job: MAB gone at the same moment of the run. Its time line
    // starts at the run's first record, the Timeline's at its first activation: the same clock
    // (mono_ns), so the two differ by the time between them, read from the job's logs here
    const jobOption = page.locator('.monitor-sources option[value^="job:"]');
    await expect.poll(() => jobOption.count(), { timeout: 30_000 }).toBe(1);
    const job = (await jobOption.getAttribute('value'))!;
    await page.locator('.monitor-sources').selectOption(job);
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toMatch(/· CSV logs/);
    const replayMarkNs = () => page.evaluate((m) => (window.__ide.monitor.current?.marks ?? []).find((k) => k.kind === 'crash' && k.where === m)?.t, MODULE);
    await expect.poll(replayMarkNs, { timeout: 20_000 }).toBeTypeOf('number');
    const { firstRecord, firstActivation, pids } = await firstMonos(page, job.slice(4));
    expect(text).toContain(`(contract-launch: module ${MODULE} (pid ${pids.get(MODULE)}) died by signal 9 (Killed))`);
    expect(goneMs).toBeCloseTo(((await replayMarkNs())! - (firstActivation - firstRecord)) / 1e6, 2);
  }, 300_000);
});

/**
 * The mono_ns of the first record of job `id`'s CSV logs (the Monitor's time 0) and of its first
 * activation (the Timeline's: its first bar, as activationsFromLogs reads them), and each module's
 * pid its `module_started` gave; the logs read by the page through the IDE's API.
 */
async function firstMonos(page: Page, id: string): Promise<{ firstRecord: number; firstActivation: number; pids: Map<string, number> }> {
  const files = await page.evaluate(async (job) => {
    const base = `/api/jobs/${encodeURIComponent(job)}/artifacts`;
    const listing = (await (await fetch(base)).json()) as { artifacts?: { files?: Array<{ name: string }> } };
    const out: Array<{ name: string; text: string }> = [];
    for (const f of (listing.artifacts?.files ?? []).filter((x) => x.name.endsWith('.csv'))) out.push({ name: f.name, text: await (await fetch(`${base}/${encodeURIComponent(f.name)}`)).text() });
    return out;
  }, id);
  expect(files.length).toBeGreaterThan(0);
  const firstRecord = Math.min(...files.map((f) => Number(f.text.split('\n')[1]?.split(',')[0] || Infinity)));
  return { firstRecord, firstActivation: activationsFromLogs(files).acts[0]!.start, pids: startedPids(files) };
}
