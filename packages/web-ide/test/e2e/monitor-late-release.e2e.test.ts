/**
 * A cycle ORD itself released past its CRITICAL_DELAY, in a real Build & Run of the tutorial
 * (bubblewrap) whose schemaCommande1 has a CRITICAL_DELAY of 200 ms (PERIOD 1 s): ORD is stopped from
 * outside (SIGSTOP) just after the schema's first cycle and let go (SIGCONT) 1.4 s later, as a
 * loaded machine stalls it, so it releases cycle 1 about 0.4-0.7 s after its tick and writes `late
 * release: ...` (no ORD:0). The Monitor, live, counts it for the schema beside its deadline misses in
 * `contract trace`'s words, lists it as a chip whose tooltip is ORD's line and which takes the cursor
 * there, and marks it on the strip; the job's CSV logs replayed say the same. Before, the Monitor
 * showed nothing of it. Real IDE server and build service, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { spawnSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { modulePid } from '@contract-studio/build-service/test-support/module-pid';
import { ideSession, openFile, shot } from './harness.js';

const canBuild = spawnSync('bwrap', ['--version']).status === 0;
/** One of the ports this test may use (E2E_LATE_RELEASE_PORT to choose another). */
const PORT = Number(process.env.E2E_LATE_RELEASE_PORT ?? 8112);
const SCHEMA = 'schemaCommande1';
const LATE = /^late release: schemaCommande1 cycle (\d+) released (\d+) us after its tick, past CRITICAL_DELAY 200000 us \(ORD late, no ORD:0\)$/;

describe.skipIf(!canBuild)("ORD's late release in a real run", () => {
  const s = ideSession({ port: PORT });

  it('is counted, listed as a chip that seeks, and marked, live and in the replay', async () => {
    const { page } = s;
    const file = join(s.workspace, 'sschema1.contract');
    writeFileSync(file, readFileSync(file, 'utf8').replace('CRITICAL_DELAY=1s;', 'CRITICAL_DELAY=200ms;'));
    await openFile(page, 'sschema1.contract');
    await expect.poll(() => page.evaluate(() => document.querySelector('.monaco-editor')?.textContent?.includes('CRITICAL_DELAY=200ms') ?? false), { timeout: 20_000 }).toBe(true);
    await page.locator('#btn-generate').click();
    await page.locator('.gen-summary').waitFor({ timeout: 60_000 });
    await expect.poll(() => readFileSync(join(s.workspace, 'src-gen/generated/architecture/modules/ORD_mod/vocabulary.c'), 'utf8').includes(`"${SCHEMA}", CONTRACT_SCHEMA_PERIODIC, 1000000000, 200000000,`), { timeout: 20_000 }).toBe(true);
    await page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 8 })));
    await page.locator('#btn-run').click();
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode'), { timeout: 10_000 }).toBe('live');
    // the schema's activation seen live, ORD is stopped at once (its cycle 0 released on its tick), for 1.4 s
    const active = () => page.evaluate((n) => (window as any).__ide.monitor.current?.live?.schemas?.get(n)?.active === true, SCHEMA);
    const until = Date.now() + 240_000;
    while (!(await active())) {
      expect(Date.now()).toBeLessThan(until);
      await new Promise((r) => setTimeout(r, 20));
    }
    const pid = modulePid('ORD');
    expect(pid).toBeDefined();
    process.kill(pid!, 'SIGSTOP');
    await new Promise((r) => setTimeout(r, 1400));
    process.kill(pid!, 'SIGCONT');
    const block = page.locator(`.monitor-pschema[data-periodic="${SCHEMA}"]`);
    await expect.poll(() => block.getAttribute('data-late-releases'), { timeout: 10_000 }).toBe('1');
    expect(await block.getAttribute('data-misses')).toBe('0');
    await expect.poll(() => block.locator('.monitor-pstats').textContent(), { timeout: 5000 })
      .toContain('0 deadline miss(es) · 1 cycle released past CRITICAL_DELAY (ORD itself late, no ORD:0) ·');
    const chip = block.locator('.late-release');
    await expect.poll(() => chip.count(), { timeout: 5000 }).toBe(1);
    const title = (await chip.getAttribute('title'))!;
    expect(title.replace(/ \(click: the cursor goes there\)$/, '')).toMatch(LATE);
    expect(await chip.textContent()).toMatch(/^late release cycle 1 at \+\d+\.\d{6} s$/);
    const marks = await page.evaluate(() => ((window as any).__ide.monitor.current?.marks ?? []).filter((k: { kind: string }) => k.kind === 'late').map((k: { t: number; where: string; label: string }) => ({ t: k.t, where: k.where, label: k.label })));
    expect(marks).toHaveLength(1);
    expect(marks[0].where).toBe(SCHEMA);
    expect(marks[0].label).toMatch(LATE);
    const lateUs = Number(LATE.exec(marks[0].label)![2]);
    console.log(`late-release: ORD released cycle 1 ${lateUs} us after its tick (CRITICAL_DELAY 200000 us)`);
    expect(lateUs).toBeGreaterThanOrEqual(200_000);
    await chip.click();
    await expect.poll(() => page.evaluate(() => (window as any).__ide.monitor.panel.cursor as number)).toBe(marks[0].t);
    await shot(page, 'monitor-late-release-live');

    // the job ends; its CSV logs replayed say the same
    await expect.poll(() => page.locator('#status-job').getAttribute('data-status'), { timeout: 120_000, interval: 1000 }).not.toBe('running');
    const jobOption = page.locator('.monitor-sources option[value^="job:"]');
    await expect.poll(() => jobOption.count(), { timeout: 30_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption(await jobOption.getAttribute('value'));
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toMatch(/· CSV logs/);
    await expect.poll(() => block.getAttribute('data-late-releases'), { timeout: 10_000 }).toBe('1');
    const replayed = await page.evaluate(() => ((window as any).__ide.monitor.current?.marks ?? []).filter((k: { kind: string }) => k.kind === 'late').map((k: { label: string }) => k.label));
    expect(replayed).toEqual([marks[0].label]);
    await shot(page, 'monitor-late-release-replayed');
  }, 400_000);
});
