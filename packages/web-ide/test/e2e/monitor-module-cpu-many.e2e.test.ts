/**
 * End-to-end, in headless Chromium on the real IDE server: a periodic schema whose ORD released
 * more modules than its block shows (20, the block shows 16) says how many more said their CPU
 * per release, so that the list is not taken for the whole (docs/watching-a-run.md, the Monitor's
 * schema block).
 */
import { describe, it, expect } from 'vitest';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ideSession, shot, showMonitor } from './harness.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const W = '2026-12-07T11:02:48.568320Z';
const NAMES = Array.from({ length: 20 }, (_, k) => `M${String(k).padStart(2, '0')}`);

describe("Monitor: a schema's CPU per release with more modules than shown", () => {
  const s = ideSession({ port: 7180 }, {
    beforeOpen: (s) => {
      const dir = join(s.workspace, 'wide-run');
      mkdirSync(dir);
      const ord = [HEADER, `1000000000,${W},ORD,module_started,,,0,pid=39 priority=50`,
        ...NAMES.map((m, k) => `${1100000000 + k * 1000},${W},ORD,ord_release,${m},,0,schema=wide cycle=0 tick_ns=1100000000 release_ns=${1100000000 + k * 1000} release=${k + 1}`)];
      writeFileSync(join(dir, 'ORD_07-Dec-2026-11h02m48s.csv'), ord.join('\n') + '\n');
      NAMES.forEach((m, k) => writeFileSync(join(dir, `${m}_07-Dec-2026-11h02m48s.csv`), [HEADER,
        `${1100000500 + k * 1000},${W},${m},run_started,ORD,,0,activation=1`,
        `${1150000000 + k * 1000},${W},${m},run_finished,,,0,activation=1 cpu_ns=${(k + 1) * 1_000_000} ACK_FINISHED`].join('\n') + '\n'));
    },
  });

  it('shows the first 16 modules and says the 4 more', async () => {
    const { page } = s;
    await showMonitor(page);
    await page.locator('.monitor-sources').selectOption('dir:wide-run');
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('End');
    const stats = page.locator('.monitor-pschema[data-periodic="wide"] .monitor-pstats');
    await expect.poll(() => stats.textContent(), { timeout: 15_000 }).toContain('; 4 more modules not shown: contract trace tells each');
    const text = (await stats.textContent())!;
    expect(text).toContain(' · CPU per release: M00 last 1 ms, max 1 ms;');
    expect(text).toContain('M15 last 16 ms, max 16 ms; 4 more modules not shown');
    expect(text).not.toContain('M16');
    await stats.scrollIntoViewIfNeeded();
    await shot(page, 'monitor-module-cpu-many-01');
  }, 60_000);
});
