/**
 * End-to-end, from the editing field test: the Outline of a file of 6,000 datatypes (12,000 symbols) lists its
 * first 5,000 symbols and counts the others (a row each made the panel fail, too many arguments
 * to one call, and left the previous file's symbols shown); Open Architecture diagram (Alt+Shift+D)
 * puts the keyboard focus in the diagram (it stayed on the page's body), as Open Timeline does.
 */
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { openFile, openIde, startSession, type Session } from './harness.js';

describe('large files and the diagram\'s focus', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession();
    writeFileSync(join(s.workspace, 'many-types.contract'), Array.from({ length: 6000 }, (_, i) => `datatype T${i} {int x};`).join('\n') + '\n');
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('the Outline lists the first 5,000 symbols of a file of 12,000 (6,000 datatypes and their fields), and says how many more', async () => {
    const { page } = s;
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await openFile(page, 'supervisor.contract');
    await expect.poll(() => page.locator('.outline-row').count(), { timeout: 20_000 }).toBeGreaterThan(0);
    await openFile(page, 'many-types.contract');
    await expect.poll(() => page.locator('.outline-more').textContent(), { timeout: 30_000 }).toMatch(/^… 7000 more symbols: the outline lists the file's first 5000/); // 12,000: a datatype and its field each
    expect(await page.locator('.outline-row').count()).toBe(5000);
    expect(await page.locator('.outline-row').first().getAttribute('data-name')).toBe('T0');
    expect(errors).toEqual([]);
  }, 60_000);

  it('Alt+Shift+D opens the architecture diagram with the keyboard focus in it', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await page.keyboard.press('Alt+Shift+D');
    await page.locator('.arch-svg').first().waitFor({ timeout: 20_000 });
    await expect.poll(() => page.evaluate(() => !!document.activeElement?.closest('.arch-canvas, .view-host'))).toBe(true);
    expect(await page.evaluate(() => document.activeElement?.tagName)).not.toBe('BODY');
  }, 60_000);
});
