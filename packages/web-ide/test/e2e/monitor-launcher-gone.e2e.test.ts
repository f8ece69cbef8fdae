/**
 * A module SIGKILLed from outside mid-run, in a real Build & Run of the tutorial (bubblewrap),
 * which no other module sends a request to afterwards: the Monitor shows it gone while the job still
 * runs, from the launcher's own line of the job's output (`contract-launch: module MAB (pid N) died
 * by signal 9 (Killed)`): the alert line, the strip mark, `Running now … · gone: MAB`. Before, it
 * said nothing of it until the job ended. Then the job's CSV logs replayed: MAB gone there too, at
 * the line's time on the run's time line. Real IDE server and build service, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { spawnSync } from 'node:child_process';
import { modulePid } from '@contract-studio/build-service/test-support/module-pid';
import { ideSession, openFile, shot } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const canBuild = spawnSync('bwrap', ['--version']).status === 0;
/** One of the ports this test may use (E2E_LAUNCHER_GONE_PORT to choose another). */
const PORT = Number(process.env.E2E_LAUNCHER_GONE_PORT ?? 7812);
const MODULE = 'MAB';

describe.skipIf(!canBuild)('a module SIGKILLed mid-run, followed live', () => {
  const s = ideSession({ port: PORT });

  it("is shown gone from the launcher's line before the job ends: alert, strip mark, Running now", async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 12, start: 'GLB.mission(consigne={1.0,2.0,3.0})' })));
    await page.locator('#btn-run').click();
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode'), { timeout: 10_000 }).toBe('live');
    const status = () => page.locator('#status-job').getAttribute('data-status');
    // the run has started and the Monitor follows it: MAB's start record was read (its pid: the one the launcher's line names)
    const started = () => page.evaluate((m) => window.__ide.monitor.current?.live?.modules?.get(m)?.alive === true, MODULE);
    await expect.poll(started, { timeout: 240_000 }).toBe(true);
    let pid: number | undefined;
    await expect.poll(() => (pid = modulePid(MODULE)), { timeout: 20_000 }).toBeDefined();
    await new Promise((r) => setTimeout(r, 1000));
    expect(await status()).toBe('running');
    process.kill(pid!, 'SIGKILL');
    const killedAt = Date.now();
    await expect.poll(() => page.locator('.monitor-crashed').textContent(), { timeout: 5000 })
      .toMatch(new RegExp(`^⚠ ${MODULE} gone at \\+\\d+\\.\\d{6} s: contract-launch: module ${MODULE} \\(pid \\d+\\) died by signal 9 \\(Killed\\)$`));
    const shownAfterMs = Date.now() - killedAt;
    // while the job still runs (the run lasts 12 s more or less: the kill came a second into it)
    expect(await status()).toBe('running');
    // (the modules' line is redrawn at most a few times a second, the alert at once)
    await expect.poll(() => page.locator('.monitor-modules').textContent(), { timeout: 5000 }).toMatch(new RegExp(`· gone: ${MODULE}$`));
    const marks = await page.evaluate(() => (window.__ide.monitor.current?.marks ?? []).filter((m: { kind: string }) => m.kind === 'crash').map((m: { where: string; label: string }) => `${m.where} ${m.label}`));
    expect(marks).toEqual([expect.stringMatching(new RegExp(`^${MODULE} ${MODULE} gone: contract-launch: module ${MODULE} \\(pid \\d+\\) died by signal 9 \\(Killed\\)$`))]);
    console.log(`launcher-gone: ${MODULE} shown gone ${shownAfterMs} ms after its SIGKILL, the job still running`);
    await shot(page, 'monitor-launcher-gone');
    // the job ends (failed: a module was killed); the page says so
    await expect.poll(status, { timeout: 60_000 }).not.toBe('running');
    // its CSV logs replayed: MAB gone from the launcher's line of the job's log, at its time on the run's time line
    const jobOption = page.locator('.monitor-sources option[value^="job:"]');
    await expect.poll(() => jobOption.count(), { timeout: 30_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption(await jobOption.getAttribute('value'));
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toMatch(/· CSV logs/);
    const replayed = () => page.evaluate((m): { gone: string | undefined; marks: Array<{ t: number; where: string }>; end: number | undefined } => {
      const run = window.__ide.monitor.current;
      return { gone: run?.stateAt(run.end)?.modules?.get(m)?.gone, marks: (run?.marks ?? []).filter((k: { kind: string }) => k.kind === 'crash').map((k: { t: number; where: string }) => ({ t: k.t, where: k.where })), end: run?.end };
    }, MODULE);
    await expect.poll(async () => (await replayed()).gone, { timeout: 20_000 }).toMatch(new RegExp(`^gone: contract-launch: module ${MODULE} \\(pid \\d+\\) died by signal 9 \\(Killed\\)$`));
    const { marks: replayMarks, end } = await replayed();
    expect(replayMarks.map((k) => k.where)).toEqual([MODULE]);
    // a second or so into the run (the kill came then), well before its end
    expect(replayMarks[0]!.t).toBeGreaterThan(0);
    expect(end).toBeTypeOf('number');
    expect(replayMarks[0]!.t).toBeLessThan(end! - 5e9);
  }, 300_000);
});
