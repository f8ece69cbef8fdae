/**
 * The Monitor's list of recent Build & Run jobs is read again (GET /api/recent-runs) every
 * RECENT_RUNS_MS while it is shown, and at once when the window is focused or the tab seen again
 * (a job another tab started meanwhile is listed without waiting for the next read): a `focus`
 * event on the window, a real DOM event, brings a read well before the next timed one; with the
 * Monitor hidden it brings none. Before this test, removing the focus listener failed no test.
 * Real IDE server and build service, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { ideSession } from './harness.js';
import { RECENT_RUNS_MS } from '../../src/monitor/monitor-controller.js';

/** One of the ports this test may use (E2E_RECENT_FOCUS_PORT to choose another). */
const PORT = Number(process.env.E2E_RECENT_FOCUS_PORT ?? 7122);

describe('Monitor: the recent jobs read again when the window is focused', () => {
  const s = ideSession({ port: PORT });

  it('at once while the Monitor is shown, not waiting for the next timed read; not at all while it is hidden', async () => {
    const { page } = s;
    // the list's reads as the page sends them, and when each ended (this test's clock)
    const sent: number[] = [];
    const ended: number[] = [];
    const isRecent = (url: string) => new URL(url).pathname === '/api/recent-runs';
    page.on('request', (r) => isRecent(r.url()) && sent.push(Date.now()));
    page.on('requestfinished', (r) => isRecent(r.url()) && ended.push(Date.now()));
    page.on('requestfailed', (r) => isRecent(r.url()) && ended.push(Date.now()));

    await page.locator('#btn-monitor').click();
    await expect.poll(() => page.locator('.side-pane .monitor-view').isVisible(), { timeout: 10_000 }).toBe(true);
    // the read on show, then a timed one: the timer runs
    await expect.poll(() => ended.length, { timeout: 4 * RECENT_RUNS_MS }).toBeGreaterThanOrEqual(2);

    const focusAfterRead = async (event: 'focus' | 'visibilitychange'): Promise<{ afterEventMs: number | undefined; sinceLastReadMs: number }> => {
      // just after a read ended (the next timed one RECENT_RUNS_MS after it), and none under way
      const before = ended.length;
      await expect.poll(() => ended.length, { timeout: 3 * RECENT_RUNS_MS, interval: 20 }).toBeGreaterThan(before);
      const lastEnded = ended[ended.length - 1]!;
      await new Promise((r) => setTimeout(r, 300));
      const count = sent.length;
      const at = Date.now();
      await page.evaluate((e) => (e === 'focus' ? window : document).dispatchEvent(new Event(e)), event);
      // a read within a second (the timed one is due RECENT_RUNS_MS after the last ended)
      await new Promise((r) => setTimeout(r, 1000));
      const next = sent.slice(count).find((t) => t >= at);
      return { afterEventMs: next === undefined ? undefined : next - at, sinceLastReadMs: (next ?? Date.now()) - lastEnded };
    };

    const focused = await focusAfterRead('focus');
    console.log(`recent-jobs-focus: read ${focused.afterEventMs} ms after the focus event, ${focused.sinceLastReadMs} ms after the last read (timed: ${RECENT_RUNS_MS} ms)`);
    expect(focused.afterEventMs).toBeDefined();
    expect(focused.afterEventMs!).toBeLessThan(1000);
    expect(focused.sinceLastReadMs).toBeLessThan(RECENT_RUNS_MS - 1000);
    // the tab seen again: the same
    const seen = await focusAfterRead('visibilitychange');
    expect(seen.afterEventMs).toBeDefined();
    expect(seen.sinceLastReadMs).toBeLessThan(RECENT_RUNS_MS - 1000);

    // the Monitor hidden: no read, on focus or by the timer
    await page.locator('#btn-monitor').click();
    await expect.poll(() => page.locator('.side-pane .monitor-view').isVisible(), { timeout: 10_000 }).toBe(false);
    await new Promise((r) => setTimeout(r, RECENT_RUNS_MS + 500)); // a timed read under way when it hid has ended
    const count = sent.length;
    await page.evaluate(() => window.dispatchEvent(new Event('focus')));
    await new Promise((r) => setTimeout(r, 1000));
    expect(sent.length).toBe(count);
  }, 120_000);
});
