/**
 * End-to-end, in headless Chromium on the real IDE server: a supervisor's events that changed no
 * rule, as the Monitor shows them, in the real run of src/monitor/fixtures/lsot-run (its README:
 * LFR's rule waits for "lsot", CAM sends "lost" and "found"): their flow's Deliveries row says the
 * last value received and, in the warning colour, how many changed no rule.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseTrace, renderStory } from '@contract-studio/build-service/trace';
import { startSession, openIde, shot, type Session, showMonitor } from './harness.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/lsot-run', import.meta.url));
const FILES = readdirSync(FIXTURE).filter((n) => n.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));

describe('Monitor: a supervisor\'s events that changed no rule', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession({ port: 7881 });
    mkdirSync(join(s.workspace, 'lsot'));
    cpSync(FIXTURE, join(s.workspace, 'lsot'), { recursive: true, filter: (src) => !src.endsWith('README.md') });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('a recorded run: CAM:0 → LFR:0 says its last value and that its 2 events changed no rule, as contract trace counts them', async () => {
    const { page } = s;
    expect(renderStory(parseTrace(FILES))).toContain('LFR got CAM:0 ×2 that changed no rule: "lost" ×1, "found" ×1');
    await showMonitor(page);
    await page.locator('.monitor-sources').selectOption('dir:lsot');
    const row = page.locator('.monitor-flows .monitor-flow.event[data-flow="CAM:0->LFR:0"]');
    await expect.poll(() => row.textContent()).toBe('┅ CAM:0 → LFR:0 ×2 · last +1.652499 s · value "found" · ⚠ 2 changed no rule');
    expect(await row.getAttribute('data-unmatched')).toBe('2');
    // in the warning colour, as a flow that dropped values or waited for room
    const warn = await page.evaluate(() => getComputedStyle(document.documentElement).getPropertyValue('--warn').trim());
    expect(await row.evaluate((el) => getComputedStyle(el).color)).toBe(await page.evaluate((c) => { const d = document.createElement('div'); d.style.color = c; document.body.append(d); const v = getComputedStyle(d).color; d.remove(); return v; }, warn));
    await page.locator('.monitor-flows').scrollIntoViewIfNeeded();
    await shot(page, 'monitor-event-values-01-recorded');
  }, 60_000);
});
