/**
 * End-to-end, in headless Chromium on the real IDE server: a string event value holding a
 * bidirectional override (U+202E), in the real run of src/monitor/fixtures/lsot-run with CAM's
 * "found" made "\u202efound" and FOLLOW's last change caused by it. Shown raw, the rule's cause, its
 * tooltip and the Deliveries row read reversed; the Monitor writes the override as its escape, as
 * the CLI does (docs/watching-a-run.md "Characters shown as escapes").
 */
import { describe, it, expect } from 'vitest';
import { mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { ideSession, shot, showMonitor } from './harness.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/lsot-run', import.meta.url));
/** CAM's value with an override, and FOLLOW's last change caused by it (its log's own words otherwise). */
const withOverride = (text: string) => text
  .replace(/value=""found"""/g, 'value=""\u202efound"""')
  .replace(/,drive\.FOLLOW inactive cause=stop$/m, ',"drive.FOLLOW inactive cause=CAM:0 value=""\u202efound"""');
const RAW = /[\u202a-\u202e\u2066-\u2069]/;

describe('Monitor: a recorded value holding a bidi override', () => {
  const s = ideSession({ buildService: false, port: 7241 }, {
    beforeOpen: (s) => {
      mkdirSync(join(s.workspace, 'bidi'));
      for (const name of readdirSync(FIXTURE).filter((n) => n.endsWith('.csv'))) writeFileSync(join(s.workspace, 'bidi', name), withOverride(readFileSync(join(FIXTURE, name), 'utf8')));
    },
  });

  it('the rule\'s cause, its tooltip and the flow\'s Deliveries row show the override as \\u202e', async () => {
    const { page } = s;
    await showMonitor(page);
    await page.locator('.monitor-sources').selectOption('dir:bidi');
    const row = page.locator('.monitor-flows .monitor-flow.event[data-flow="CAM:0->LFR:0"]');
    await expect.poll(() => row.textContent()).toBe('┅ CAM:0 → LFR:0 ×2 · last +1.652499 s · value "\\u202efound" · ⚠ 2 changed no rule');
    const rule = page.locator('.monitor-rule[data-rule="LFR.drive.FOLLOW"]');
    await expect.poll(() => rule.locator('.rule-cause').textContent()).toBe('off ← CAM:0 = "\\u202efound"');
    expect(await rule.getAttribute('title')).toMatch(/^drive\.FOLLOW inactive since \+\d+\.\d{6} s ← CAM:0 = "\\u202efound" · not in the model/);
    expect(await rule.getAttribute('aria-label')).toContain('← CAM:0 = "\\u202efound"');
    // nothing the panel shows or says holds the override raw; the record keeps it (data-cause)
    expect(await page.locator('.monitor-view').evaluate((el) => el.textContent ?? '')).not.toMatch(RAW);
    const shown = await page.locator('.monitor-view [title], .monitor-view [aria-label]').evaluateAll((els) => els.flatMap((e) => [e.getAttribute('title') ?? '', e.getAttribute('aria-label') ?? '']));
    expect(shown.filter((t) => RAW.test(t))).toEqual([]);
    expect(await rule.getAttribute('data-cause')).toContain('\u202efound');
    await page.locator('.monitor-flows').scrollIntoViewIfNeeded();
    await shot(page, 'monitor-escaped-values-01-bidi');
  }, 60_000);
});
