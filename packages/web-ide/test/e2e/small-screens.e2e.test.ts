/**
 * End-to-end: the IDE on a laptop screen, zoomed. A 1366x768 laptop at 150 % is a window of
 * 911x512 CSS pixels at a device scale of 1.5 (at 125 %: 1093x614 at 1.25), with "reduce motion"
 * on. What a field test found there: the Run settings dialog taller than the window (its Save
 * off-screen, no scrolling), the Monitor beside the editor 135 px tall, the pane resizers mouse-only,
 * the editor's line numbers and keywords under the contrast minimum, the Generate panel's paths cut
 * at their file name, the Monitor's readout before a run's first record, its slider changing width,
 * a spinner spinning regardless of "reduce motion", a white native list in the Timeline, and the
 * Monitor's cursor buttons enabled with no run.
 */
import { afterAll, afterEach, beforeAll, describe, expect, it } from 'vitest';
import { cpSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { Page } from 'playwright-core';
import { ideSession, openFile, openIde, placeCursor, shot, startSession, waitSaved, type Session } from './harness.js';
import { axeScan, seriousOf } from './axe.js';
import type {} from '../../src/app/ide-hook.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/tutorial-run', import.meta.url));

interface Box { top: number; bottom: number; left: number; right: number; height: number; width: number }
const box = (page: Page, sel: string): Promise<Box> => page.locator(sel).first().evaluate((e) => {
  const r = e.getBoundingClientRect();
  return { top: r.top, bottom: r.bottom, left: r.left, right: r.right, height: r.height, width: r.width };
});

/**
 * The open dialog fits the window: the dialog, its title and its buttons on screen; each control
 * Tab reaches is scrolled into view (inside the dialog's scrolling body, or one of the buttons).
 */
async function checkDialogFits(page: Page, name: string, dialogSel = '[role=dialog]'): Promise<{ scrolls: boolean; stops: number }> {
  const vp = page.viewportSize()!;
  const d = await box(page, dialogSel);
  expect(d.top, `${name}: dialog top`).toBeGreaterThanOrEqual(0);
  expect(d.bottom, `${name}: dialog bottom`).toBeLessThanOrEqual(vp.height);
  for (const b of await page.locator(`${dialogSel} .dialog-buttons button`).all()) {
    const r = await b.evaluate((e) => { const x = e.getBoundingClientRect(); return { top: x.top, bottom: x.bottom, text: e.textContent }; });
    expect(r.bottom, `${name}: button ${r.text} on screen`).toBeLessThanOrEqual(vp.height);
    expect(r.top, `${name}: button ${r.text} on screen`).toBeGreaterThanOrEqual(0);
  }
  const scrolls = await page.locator(dialogSel).first().evaluate((dlg) => {
    const body = dlg.querySelector('.dialog-body');
    return !!body && body.scrollHeight > body.clientHeight;
  });
  // Tab round the dialog: the focused control is always visible in the window and in its scrolling body
  const seen = new Set<string>();
  for (let i = 0; i < 30; i++) {
    await page.keyboard.press('Tab');
    const f = await page.evaluate(() => {
      const e = document.activeElement as HTMLElement;
      const r = e.getBoundingClientRect();
      const body = e.closest('.dialog-body');
      const b = body?.getBoundingClientRect();
      const id = `${e.tagName}:${e.getAttribute('aria-label') ?? e.textContent}:${[...(e.closest('[role=dialog]')?.querySelectorAll('*') ?? [])].indexOf(e)}`;
      return { id, top: r.top, bottom: r.bottom, inBody: !b || (r.top >= b.top - 1 && r.bottom <= b.bottom + 1), inDialog: !!e.closest('[role=dialog]') };
    });
    expect(f.inDialog, `${name}: the focus stays in the dialog`).toBe(true);
    expect(f.bottom, `${name}: ${f.id} focused on screen`).toBeLessThanOrEqual(vp.height);
    expect(f.top, `${name}: ${f.id} focused on screen`).toBeGreaterThanOrEqual(0);
    expect(f.inBody, `${name}: ${f.id} scrolled into view in the dialog's body`).toBe(true);
    if (seen.has(f.id)) break;
    seen.add(f.id);
  }
  return { scrolls, stops: seen.size };
}

/** The cursor on the file's first `import`: its other places are highlighted (the keywords on the highlight are scanned too). */
async function highlightWordAtCursor(page: Page): Promise<void> {
  await placeCursor(page, 'import', 2);
  await expect.poll(() => page.locator('.monaco-editor .view-overlays [class*="wordHighlight"], .monaco-editor .view-overlays .selectionHighlight').count(), { timeout: 10_000 }).toBeGreaterThan(1);
}

describe('a 1366x768 laptop at 150 % (911x512 at scale 1.5, reduce motion)', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession({ port: 7900, viewport: { width: 911, height: 512 }, deviceScaleFactor: 1.5, reducedMotion: 'reduce' });
    cpSync(FIXTURE, join(s.workspace, 'recorded'), { recursive: true });
    await openIde(s);
  }, 90_000);
  afterAll(async () => {
    await s?.close();
  });
  afterEach(async () => {
    // a test that failed with a dialog open leaves it to no other
    for (let i = 0; i < 3 && (await s.page.locator('[role=dialog], .dialog-overlay').count()); i++) await s.page.keyboard.press('Escape');
  });

  it('Run settings with stdin rows fits the window: its body scrolls (the wheel too), Cancel and Save stay on screen, Tab scrolls each control into view', async () => {
    const { page } = s;
    await page.locator('#btn-run-settings').click();
    await page.locator('[role=dialog] .dialog-rows-add').waitFor();
    for (let i = 0; i < 3; i++) await page.locator('[role=dialog] .dialog-rows-add').click({ timeout: 5000 }); // scrolled to, in the dialog's body
    await page.locator('[role=dialog] .dialog-input').first().focus();
    const { scrolls, stops } = await checkDialogFits(page, 'Run settings');
    expect(scrolls).toBe(true);
    expect(stops).toBeGreaterThan(10);
    // the wheel over the dialog scrolls its body
    expect(await page.locator('[role=dialog] .dialog-body').count(), 'a scrolling body').toBe(1);
    const before = await page.locator('[role=dialog] .dialog-body').evaluate((b) => { b.scrollTop = 0; return b.scrollTop; });
    const d = await box(page, '[role=dialog]');
    await page.mouse.move(d.left + d.width / 2, d.top + d.height / 2);
    await page.mouse.wheel(0, 300);
    await expect.poll(() => page.locator('[role=dialog] .dialog-body').evaluate((b) => b.scrollTop)).toBeGreaterThan(before);
    // Save, reached by Shift+Tab from the first field, is on screen
    await page.locator('[role=dialog] .dialog-input').first().focus();
    await page.keyboard.press('Shift+Tab');
    expect(await page.evaluate(() => document.activeElement?.textContent)).toBe('Save');
    const save = await box(page, '[role=dialog] .dialog-buttons .primary');
    expect(save.bottom).toBeLessThanOrEqual(512);
    await shot(page, 'small-screens-150-run-settings');
    await page.keyboard.press('Escape');
    await expect.poll(() => page.locator('[role=dialog]').count()).toBe(0);
  });

  it('New File, New Project and a confirmation fit the window', async () => {
    const { page } = s;
    for (const [button, name] of [['#btn-new-file', 'New file'], ['#btn-new-project', 'New project']] as const) {
      await page.locator(button).click();
      await page.locator('[role=dialog] .dialog-input').waitFor();
      await checkDialogFits(page, name);
      await shot(page, `small-screens-150-${name.replace(' ', '-').toLowerCase()}`);
      await page.keyboard.press('Escape');
      await expect.poll(() => page.locator('[role=dialog]').count()).toBe(0);
    }
    // a confirmation: Delete on a file of the explorer (Cancel: nothing deleted)
    const row = page.locator('.tree-row[data-path="sched.contract"]');
    await row.click();
    await row.press('Delete');
    await page.locator('[role=dialog] .btn.danger').waitFor();
    await checkDialogFits(page, 'Delete');
    await page.keyboard.press('Escape');
    await expect.poll(() => page.locator('[role=dialog]').count()).toBe(0);
  });

  it('the overlapping-edits view fits the window: both sides and its four buttons on screen', async () => {
    const { page } = s;
    await openFile(page, 'sched.contract');
    await waitSaved(page);
    const file = join(s.workspace, 'sched.contract');
    const text = readFileSync(file, 'utf8');
    const anchor = text.split('\n').find((l) => l.trim().length > 8)!.trim();
    await page.context().setOffline(true);
    try {
      await placeCursor(page, anchor, anchor.length);
      await page.keyboard.type(' // mine');
      await page.locator('#status-save.error').waitFor({ timeout: 10_000 });
      writeFileSync(file, text.replace(anchor, `${anchor} // theirs`));
    } finally {
      await page.context().setOffline(false);
    }
    await page.keyboard.press('Control+s');
    await page.locator('.conflict-overlay .monaco-diff-editor').waitFor({ timeout: 20_000 });
    const vp = page.viewportSize()!;
    const view = await box(page, '.conflict-overlay');
    expect(view.bottom).toBeLessThanOrEqual(vp.height);
    for (const b of await page.locator('.conflict-overlay .dialog-buttons button').all()) {
      const r = await b.evaluate((e) => e.getBoundingClientRect().bottom);
      expect(r).toBeLessThanOrEqual(vp.height);
    }
    expect((await box(page, '.conflict-overlay .conflict-diff')).height).toBeGreaterThan(100);
    await shot(page, 'small-screens-150-overlapping-edits');
    await page.locator('#conflict-keep-mine').click();
    await expect.poll(() => page.locator('.conflict-overlay').count()).toBe(0);
  });

  it('the Monitor beside the editor keeps a usable height, the bottom panel gives way; with no run its cursor buttons are disabled; a focused rule is scrolled into view', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await page.keyboard.press('Alt+Shift+M');
    await page.locator('.side-pane .monitor-view').waitFor();
    const pane = await box(page, '.side-pane');
    console.log(`at 911x512: the Monitor's pane ${Math.round(pane.height)} px, its body ${Math.round((await box(page, '.monitor-body')).height)} px, the bottom panel ${Math.round((await box(page, '.bottom-panel')).height)} px`);
    expect(pane.height).toBeGreaterThanOrEqual(220); // 135 before
    expect((await box(page, '.bottom-panel')).height).toBeGreaterThanOrEqual(80);
    for (const id of ['monitor-prev', 'monitor-follow', 'monitor-play', 'monitor-next']) expect(await page.locator(`#${id}`).isDisabled(), id).toBe(true);
    await page.evaluate(() => window.__ide.monitor.openFolder('recorded'));
    await expect.poll(() => page.locator('.monitor-rule').count(), { timeout: 15_000 }).toBeGreaterThan(3);
    for (const id of ['monitor-prev', 'monitor-follow', 'monitor-play', 'monitor-next']) expect(await page.locator(`#${id}`).isDisabled(), id).toBe(false);
    expect((await box(page, '.monitor-body')).height).toBeGreaterThanOrEqual(40); // 8 before
    // a rule focused far down the Monitor is scrolled into view, inside the pane and above the bottom panel
    // the replay may still be adding rows on a loaded machine: wait until their number holds for half a second,
    // then focus and measure one and the same element (a locator's .last() would resolve again)
    let rows = -1;
    await expect.poll(async () => { const n = await page.locator('.monitor-rule').count(); const same = n === rows; rows = n; return same; }, { timeout: 15_000, interval: 500 }).toBe(true);
    const last = await page.locator('.monitor-rule').last().elementHandle();
    await last!.focus();
    const r = await last!.evaluate((e) => e.getBoundingClientRect().toJSON() as DOMRect);
    expect(await last!.evaluate((e) => e === document.activeElement)).toBe(true);
    const body = await box(page, '.monitor-body');
    expect(r.top).toBeGreaterThanOrEqual(body.top - 1);
    expect(r.bottom).toBeLessThanOrEqual(body.bottom + 1);
    expect(r.bottom).toBeLessThanOrEqual((await box(page, '.bottom-panel')).top);
    await shot(page, 'small-screens-150-monitor-docked');
  });

  it('the pane resizers are focusable separators moved by the arrow keys; a drag selects no text', async () => {
    const { page } = s;
    const h = page.locator('.resizer.horizontal');
    const v = page.locator('.resizer.vertical');
    expect(await h.getAttribute('role')).toBe('separator');
    expect(await h.getAttribute('aria-orientation')).toBe('horizontal');
    expect(await v.getAttribute('aria-orientation')).toBe('vertical');
    expect(await h.getAttribute('tabindex')).toBe('0');
    expect(await h.getAttribute('aria-label')).toBe('Resize the bottom panel');
    const panelH = async () => Math.round((await box(page, '.bottom-panel')).height);
    await h.focus();
    const start = await panelH();
    expect(Number(await h.getAttribute('aria-valuenow'))).toBe(start);
    await page.keyboard.press('ArrowDown'); // the line down: the panel smaller
    await expect.poll(panelH).toBe(Math.max(80, start - 10));
    expect(Number(await h.getAttribute('aria-valuenow'))).toBe(await panelH());
    await page.keyboard.press('Home');
    await expect.poll(panelH).toBe(80);
    await page.keyboard.press('ArrowUp');
    await expect.poll(panelH).toBe(90);
    await page.keyboard.press('End'); // the largest the editor's minimum leaves
    const max = Number(await h.getAttribute('aria-valuemax'));
    await expect.poll(panelH).toBe(max);
    expect(max).toBeGreaterThanOrEqual(80);
    expect((await box(page, '.editor-area')).height).toBeGreaterThanOrEqual(250);
    const sideW = async () => Math.round((await box(page, '.sidebar')).width);
    await v.focus();
    const w0 = await sideW();
    await page.keyboard.press('Shift+ArrowRight');
    await expect.poll(sideW).toBe(Math.min(600, w0 + 50));
    await page.keyboard.press('ArrowLeft');
    await expect.poll(sideW).toBe(Math.min(600, w0 + 50) - 10);
    expect(Number(await v.getAttribute('aria-valuenow'))).toBe(await sideW());
    // a drag of the resizer from over the text: nothing selected
    const hb = await box(page, '.resizer.horizontal');
    await page.mouse.move(hb.left + 200, hb.top + 2);
    await page.mouse.down();
    await page.mouse.move(hb.left + 100, hb.top + 60, { steps: 5 });
    await page.mouse.move(hb.left + 20, hb.top + 90, { steps: 5 });
    await page.mouse.up();
    expect(await page.evaluate(() => String(window.getSelection()))).toBe('');
    expect(await panelH()).toBeLessThan(max);
  });

  it('the editor with a file open, axe-core: no serious or critical violation (its line numbers and keywords readable)', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await highlightWordAtCursor(page);
    const scan = await axeScan(page, 'editor at 150 %', { editor: true });
    expect(seriousOf(scan)).toEqual([]);
  });

  it('the Generate panel cuts a long path in its folders: the file name stays visible, the whole path in the tooltip', async () => {
    const { page } = s;
    await page.locator('#btn-generate').click();
    await page.locator('#panel-tab-generate').click();
    const row = page.locator('.gen-file[data-path$="SharedFunctiontestit.h"] .gen-name').first();
    await row.waitFor({ timeout: 30_000 });
    expect(await row.getAttribute('title')).toBe('generated/architecture/common/SharedFunctiontestit.h');
    expect(await row.textContent()).toBe('generated/architecture/common/SharedFunctiontestit.h');
    // the column is narrower than the path, and the file name is whole in it
    const shown = await row.evaluate((e) => {
      const base = e.querySelector('.gen-base') as HTMLElement | null;
      const r = e.getBoundingClientRect();
      const b = (base ?? e).getBoundingClientRect();
      return { cut: e.scrollWidth > e.clientWidth || !!e.querySelector('.gen-dir') && (e.querySelector('.gen-dir') as HTMLElement).scrollWidth > (e.querySelector('.gen-dir') as HTMLElement).clientWidth, baseWhole: !!base && base.scrollWidth <= base.clientWidth && b.right <= r.right + 1 };
    });
    expect(shown.cut).toBe(true);
    expect(shown.baseWhole).toBe(true);
    await shot(page, 'small-screens-150-generate');
  });

  it('reduce motion: the spinner stands still', async () => {
    const { page } = s;
    const state = await page.evaluate(async () => {
      const el = document.createElement('span');
      el.className = 'spinner';
      document.body.append(el);
      await new Promise((r) => setTimeout(r, 100));
      const running = el.getAnimations().filter((a) => a.playState === 'running').length;
      el.remove();
      return running;
    });
    expect(state).toBe(0);
  });

  it('the Timeline\'s run list is drawn in the dark theme, not a white native list', async () => {
    const { page } = s;
    await page.locator('#btn-timeline').click();
    const select = page.locator('.timeline-source');
    await select.waitFor();
    const bg = await select.evaluate((e) => getComputedStyle(e).backgroundColor);
    expect(bg).not.toBe('rgb(255, 255, 255)');
    const [r, g, b] = bg.match(/\d+/g)!.map(Number);
    expect(r! + g! + b!).toBeLessThan(200);
  });
});

describe('the Monitor\'s readout and slider (1366x768 at 100 %)', () => {
  const s = ideSession({ port: 7901, viewport: { width: 1366, height: 768 }, deviceScaleFactor: 1, timeout: 90_000 });

  it('the editor with a file open, axe-core: no serious or critical violation', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await highlightWordAtCursor(page);
    const scan = await axeScan(page, 'editor at 100 %', { editor: true });
    expect(seriousOf(scan)).toEqual([]);
  });

  it('before a live run\'s first record it says it waits for it; the slider keeps its width live, paused and ended', async () => {
    const { page } = s;
    await page.keyboard.press('Alt+Shift+M');
    await page.locator('.monitor-view').waitFor();
    await page.evaluate(() => window.__ide.monitor.followLive('fed', null));
    await expect.poll(() => page.locator('.monitor-time').textContent()).toBe('waiting for the run\'s first record · live');
    const width = async () => Math.round((await box(page, '.monitor-slider')).width);
    const widths = [await width()];
    // the recorded tutorial run's records, all at once
    const lines = readdirSync(FIXTURE).filter((f) => f.endsWith('.csv'))
      .flatMap((file) => readFileSync(join(FIXTURE, file), 'utf8').split('\n').map((text, i) => ({ file, line: i + 1, text })))
      .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
    await page.evaluate((records) => window.__ide.monitor.feed('fed', records), lines);
    await expect.poll(() => page.locator('.monitor-time').textContent()).toContain('live (last record');
    widths.push(await width());
    await page.locator('#monitor-follow').click(); // Pause
    await expect.poll(() => page.locator('#monitor-follow').getAttribute('data-following')).toBe('false');
    expect(await page.locator('.monitor-time').textContent()).toMatch(/^\+\d+\.\d{6} s \/ \+\d+\.\d{6} s$/);
    widths.push(await width());
    await page.locator('#monitor-follow').click(); // Follow again
    widths.push(await width());
    expect(new Set(widths).size, widths.join(' ')).toBe(1);
    await shot(page, 'small-screens-100-monitor-slider');
  });
});

describe('a 1366x768 laptop at 125 % (1093x614 at scale 1.25)', () => {
  const s = ideSession({ port: 7902, viewport: { width: 1093, height: 614 }, deviceScaleFactor: 1.25, timeout: 90_000 });

  it('Run settings with stdin rows fits the window: Cancel and Save on screen, Tab scrolls each control into view', async () => {
    const { page } = s;
    await page.locator('#btn-run-settings').click();
    await page.locator('[role=dialog] .dialog-rows-add').waitFor();
    for (let i = 0; i < 2; i++) await page.locator('[role=dialog] .dialog-rows-add').click({ timeout: 5000 });
    await page.locator('[role=dialog] .dialog-input').first().focus();
    const { scrolls } = await checkDialogFits(page, 'Run settings at 125 %');
    expect(scrolls).toBe(true);
    await shot(page, 'small-screens-125-run-settings');
    await page.keyboard.press('Escape');
  });
});
