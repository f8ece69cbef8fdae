/**
 * What a module's code may leave in its run's logs folder, on a real run's logs (the tutorial,
 * src/monitor/fixtures/tutorial-run, under the names the runtime gives them, in the project's
 * `logs/`): `ORD_<date>.csv` of its own with no header (one deadline miss of ORD, its clock
 * consistent), and two supervisor lines appended to MSC's log (MSC: a synchronous module).
 * The Monitor's replay says the file first and folds none of it, does not list MSC among the
 * supervisors (the model says it is a synchronous module) and says its records once; the
 * scheduling note is not under *Active schemas*; the Timeline keeps MSC's lane.
 * Real IDE server (no build service), headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { appendFileSync, cpSync, mkdirSync, readdirSync, renameSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { ideSession, shot } from './harness.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/tutorial-run', import.meta.url));
const DATE = '4-Dec-2026-05h49m24s';
const FORGED = 'ORD_4-Dec-2026-05h49m59s.csv';
const PORT = Number(process.env.E2E_FORGED_LOGS_PORT ?? 7261);

describe('Monitor and Timeline on a logs folder a module forged into', () => {
  const s = ideSession({ port: PORT, buildService: false }, {
    beforeOpen: (s) => {
      const logs = join(s.workspace, 'logs');
      mkdirSync(logs);
      cpSync(FIXTURE, logs, { recursive: true });
      for (const f of readdirSync(logs).filter((n) => n.endsWith('.csv'))) renameSync(join(logs, f), join(logs, `${f.slice(0, -4)}_${DATE}.csv`));
      appendFileSync(join(logs, FORGED), '52092900000000,2026-12-04T05:49:27.253000Z,ORD,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=3 tick_ns=52092787155629\n');
      appendFileSync(join(logs, `MSC_${DATE}.csv`), [
        '52094200000000,2026-12-04T05:49:28.553000Z,MSC,supervisor,,,0,function <img src=x onerror=alert(1)>() started',
        '52094200000100,2026-12-04T05:49:28.553000Z,MSC,sup_rule,,,0,rule <b>X</b>.Y active', ''].join('\n'));
    },
  });

  it('the replay says the file that is no log first, counts no miss of ORD, lists MSC as no supervisor; the scheduling note stands apart', async () => {
    const { page } = s;
    await page.locator('#btn-monitor').click();
    await page.locator('.side-pane .monitor-view').waitFor();
    await page.evaluate(() => window.__ide.monitor.openFolder('logs'));
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 })
      .toMatch(new RegExp(`^10 CSV log\\(s\\) in logs · [\\d,]+ record\\(s\\), 2 unreadable line\\(s\\) \\(not whole: ${FORGED.replace('.', '\\.')}: not a ContrACT CSV log \\(it does not begin with the runtime's header`));
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('End');
    const block = page.locator('.monitor-pschema[data-periodic="schemaCommande1"]');
    await expect.poll(() => block.getAttribute('data-misses'), { timeout: 10_000 }).toBe('0');
    // the model (the language server) says MSC is a synchronous module: not listed as a supervisor, said once
    await expect.poll(() => page.locator('.monitor-not-supervisor[data-module="MSC"]').textContent(), { timeout: 30_000 })
      .toBe('MSC: supervisor records in its log, not taken for a supervisor\'s: the model says MSC is a synchronous module (its code wrote them into its log?)');
    expect(await page.locator('.monitor-sup[data-supervisor="MSC"]').count()).toBe(0);
    expect(await page.locator('.monitor-sup[data-supervisor="SUP"]').count()).toBe(1);
    // ORD's priority note: shown, not under the Active schemas heading
    await expect.poll(() => page.locator('.monitor-sched').isVisible(), { timeout: 10_000 }).toBe(true);
    expect(await page.locator('.monitor-sched').textContent()).toMatch(/^Scheduling: ORD priority nice 1/);
    expect(await page.locator('.monitor-section .monitor-sched').count()).toBe(0);
    await shot(page, 'monitor-forged-logs');
  }, 120_000);

  it('the Timeline keeps MSC\'s lane and says the file that is no log', async () => {
    const { page } = s;
    await page.locator('#btn-timeline').click();
    await page.locator('.timeline-svg').waitFor({ timeout: 30_000 });
    const labels = await page.locator('.lane-label').allTextContents();
    expect(labels).toContain('MSC');
    expect(labels).toContain('MSA');
    expect(await page.locator('.timeline-view').textContent()).toContain(`${FORGED}: not a ContrACT CSV log`);
    expect(await page.locator('.timeline-view').textContent()).not.toContain('logs of it'); // no second log of ORD
    await shot(page, 'timeline-forged-logs');
  }, 60_000);
});
