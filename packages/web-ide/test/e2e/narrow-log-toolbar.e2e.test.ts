/**
 * End-to-end: the Build & Run panel's toolbar in a narrow window (1000 px, the explorer open) of a
 * tab following another tab's run: the origin text gives way (cut, whole in its tooltip), the
 * source chips and the controls stay on screen. Before, "(Build & Run of another tab)" took the
 * row: no chip was left, and Clear was cut off at the right edge.
 */
import { describe, expect, it } from 'vitest';
import { ideSession, shot } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

describe('the Build & Run panel\'s toolbar, narrow', () => {
  const s = ideSession();

  it('keeps the chips and the controls on screen; the origin is cut, whole in its tooltip', async () => {
    const { page } = s;
    await page.setViewportSize({ width: 1000, height: 700 });
    await page.evaluate(() => {
      const b = window.__ide.build;
      b.setOrigin('(Build & Run of another tab)');
      b.setStatus('running', 'run', true);
      for (const src of ['GLB', 'MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD', 'ORD', 'SUP', 'launcher']) b.append({ t: Date.now(), step: 'run', source: src, stream: 'stdout', line: `hello from ${src}` });
    });
    await page.locator('.panel-tab[data-panel=output]').click();
    await page.locator('.build-panel .chip').first().waitFor();
    const box = (sel: string) => page.locator(sel).evaluate((e) => { const r = e.getBoundingClientRect(); return { left: r.left, right: r.right, width: r.width }; });
    const toolbar = await box('.build-panel .log-toolbar');
    const chips = await box('.build-panel .chips');
    const clear = await box('.build-panel .log-toolbar > button');
    expect(chips.width).toBeGreaterThanOrEqual(96);
    expect(clear.right).toBeLessThanOrEqual(toolbar.right);
    expect(await page.locator('.job-origin').getAttribute('title')).toBe('(Build & Run of another tab)');
    await shot(page, 'narrow-log-toolbar');
  });
});
