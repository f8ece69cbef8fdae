/**
 * End-to-end: a reload brings the workspace back as it was — open tabs in order, the active tab,
 * each tab's cursor and scroll, the sidebar and bottom panel sizes, the bottom panel shown and the
 * open views — and a stored layout that is corrupt or names a deleted file does no harm
 * (docs/ide.md, "Reload keeps the workspace"). Real server, real Chromium.
 */
import { describe, it, expect } from 'vitest';
import { ideSession, shot, placeCursor, openFile, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

let s: Session;
const FILES = ['sched.contract', 'smodule1.contract', 'smodule2.contract', 'smodule3.contract', 'sschema1.contract', 'sschema2.contract', 'datatype.contract'];
const CURSOR_AT: Record<string, string> = {
  'sched.contract': 'MSC;', 'smodule1.contract': 'C=500us', 'smodule2.contract': 'module', 'smodule3.contract': 'C=1ms',
  'sschema1.contract': 'MSC (consigne', 'sschema2.contract': 'schema', 'datatype.contract': 'datatype',
};

type Snapshot = { tabs: string[]; active: string | null; cursors: Record<string, { lineNumber: number; column: number }>; scrollTop: number; sidebar: number; panel: number; shownPanel: string | null };

/** What the user sees: tabs in order, the active one, each file tab's cursor (by activating it), sizes. */
async function snapshot(): Promise<Snapshot> {
  const { page } = s;
  const tabs = await page.locator('.tabs .tab').evaluateAll((els) => els.map((e) => e.getAttribute('data-path')!));
  const active = await page.locator('.tab.active').getAttribute('data-path');
  const scrollTop = await page.evaluate(() => window.__ide.editors.editor.getScrollTop());
  const cursors: Snapshot['cursors'] = {};
  for (const t of tabs.filter((id) => !id.startsWith('view:'))) {
    await page.locator(`.tabs .tab[data-path="${t}"]`).click();
    cursors[t] = await page.evaluate(() => { const p = window.__ide.editors.editor.getPosition()!; return { lineNumber: p.lineNumber, column: p.column }; });
  }
  if (active) await page.locator(`.tabs .tab[data-path="${active}"]`).click();
  const box = async (sel: string, dim: 'width' | 'height') => Math.round((await page.locator(sel).boundingBox())![dim]);
  return {
    tabs, active, cursors, scrollTop,
    sidebar: await box('.sidebar', 'width'), panel: await box('.bottom-panel', 'height'),
    shownPanel: await page.locator('.panel-tab.active').getAttribute('data-panel'),
  };
}

async function reload(): Promise<void> {
  await s.page.reload();
  await s.page.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
}

async function drag(selector: string, dx: number, dy: number): Promise<void> {
  const b = (await s.page.locator(selector).boundingBox())!;
  const x = b.x + b.width / 2;
  const y = b.y + b.height / 2;
  await s.page.mouse.move(x, y);
  await s.page.mouse.down();
  await s.page.mouse.move(x + dx / 2, y + dy / 2);
  await s.page.mouse.move(x + dx, y + dy);
  await s.page.mouse.up();
}

describe('reload keeps the workspace', () => {
  s = ideSession({ buildService: false });

  it('tabs, active tab, cursors, scroll, panel sizes, the bottom panel and the architecture view come back', async () => {
    const { page } = s;
    for (const f of FILES) {
      await openFile(page, f);
      await placeCursor(page, CURSOR_AT[f]!, 2);
    }
    await page.locator('#btn-arch').click();
    await page.locator('.tab[data-path="view:architecture"]').waitFor({ timeout: 20_000 });
    await page.locator('#btn-timeline').click();
    await page.locator('.tab[data-path="view:timeline"]').waitFor({ timeout: 20_000 });
    const sidebar0 = (await page.locator('.sidebar').boundingBox())!.width;
    const panel0 = (await page.locator('.bottom-panel').boundingBox())!.height;
    await drag('.resizer.vertical', 110, 0);
    await drag('.resizer.horizontal', 0, -90);
    expect((await page.locator('.sidebar').boundingBox())!.width).toBeGreaterThan(sidebar0 + 50);
    expect((await page.locator('.bottom-panel').boundingBox())!.height).toBeGreaterThan(panel0 + 50);
    await page.locator('.panel-tab[data-panel=generate]').click();
    await page.locator('.tabs .tab[data-path="supervisor.contract"]').click();
    await placeCursor(page, 'RECEPTION', 3);
    await page.evaluate(() => window.__ide.editors.editor.setScrollTop(200));
    const before = await snapshot();
    expect(before.tabs.length).toBe(FILES.length + 3); // + supervisor.contract opened at start, + the architecture and timeline views
    expect(before.tabs).toContain('view:architecture');
    expect(before.tabs).toContain('view:timeline');
    expect(before.active).toBe('supervisor.contract');
    expect(before.scrollTop).toBeGreaterThan(100);
    expect(before.shownPanel).toBe('generate');
    await page.waitForTimeout(400); // the debounced save
    await reload();
    await shot(page, '30-layout-restored');
    const after = await snapshot();
    expect(after.tabs).toEqual(before.tabs);
    expect(after.active).toBe(before.active);
    expect(after.cursors).toEqual(before.cursors);
    expect(Math.abs(after.scrollTop - before.scrollTop)).toBeLessThanOrEqual(1);
    expect(Math.abs(after.sidebar - before.sidebar)).toBeLessThanOrEqual(1);
    expect(Math.abs(after.panel - before.panel)).toBeLessThanOrEqual(1);
    expect(after.shownPanel).toBe('generate');
    await page.locator('.tabs .tab[data-path="view:architecture"]').click();
    await page.locator('.view-host:not(.hidden) .arch-svg').first().waitFor({ timeout: 20_000 });
    expect(await page.locator('.tab.active').getAttribute('data-path')).toBe('view:architecture');
  });

  it('the architecture diagram docked beside the editor comes back docked', async () => {
    const { page } = s;
    await page.locator('.tabs .tab[data-path="view:architecture"]').click();
    await page.locator('#arch-dock').click();
    await page.locator('.side-pane:not(.hidden) .arch-svg').first().waitFor({ timeout: 20_000 });
    await page.locator('.tabs .tab[data-path="sched.contract"]').click();
    await page.waitForTimeout(400);
    await reload();
    await page.locator('.side-pane:not(.hidden) .arch-svg').first().waitFor({ timeout: 20_000 });
    expect(await page.locator('.tab[data-path="view:architecture"]').count()).toBe(0);
    expect(await page.locator('.tab.active').getAttribute('data-path')).toBe('sched.contract');
    // back in a tab for the next test
    await page.locator('.side-pane #arch-dock').click();
    await page.locator('.tab[data-path="view:architecture"]').waitFor();
    await page.waitForTimeout(400);
  });

  it('a file deleted since is skipped, and corrupt stored JSON is ignored, with no error', async () => {
    const { page } = s;
    const key = await page.evaluate(() => `contract-studio:layout:${window.__ide.workspace.root}`);
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.evaluate((k) => {
      const l = JSON.parse(localStorage.getItem(k)!);
      l.tabs.splice(1, 0, 'deleted-since.contract');
      l.active = 'deleted-since.contract';
      localStorage.setItem(k, JSON.stringify(l));
    }, key);
    // the page saves its layout when it unloads: the edited one is put back before the next page's scripts run
    await page.addInitScript(({ k, v }) => { if (!sessionStorage.getItem('seeded')) { sessionStorage.setItem('seeded', '1'); localStorage.setItem(k, v); } },
      { k: key, v: await page.evaluate((k) => localStorage.getItem(k)!, key) });
    await reload();
    const tabs = await page.locator('.tabs .tab').evaluateAll((els) => els.map((e) => e.getAttribute('data-path')));
    expect(tabs).not.toContain('deleted-since.contract');
    expect(tabs.length).toBe(FILES.length + 3);
    expect(await page.locator('.toast.error').count()).toBe(0);

    await page.addInitScript((k) => localStorage.setItem(k, '{"v":1,"tabs":[bad json'), key);
    await reload();
    expect(await page.locator('.tabs .tab').evaluateAll((els) => els.map((e) => e.getAttribute('data-path')))).toEqual(['supervisor.contract']);
    expect(await page.locator('.toast.error').count()).toBe(0);
    expect(errors).toEqual([]);
  });
});
