/**
 * Keyboard-first (docs/ide.md "Keyboard"): a walkthrough without the mouse — quick open, go to a
 * problem, Generate All and Build & Run from the command palette — then the lists and tabs by
 * keyboard (WAI-ARIA tree, listbox, tablist), a tab click focusing its editor, and an axe-core
 * scan of the main screens (report printed; no serious or critical violation).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { startSession, openIde, shot, placeCursor, activeTab, openFile, waitSaved, cursorLine, type Session } from './harness.js';
import { axeScan, seriousOf, type AxeSummary } from './axe.js';
import type {} from '../../src/app/ide-hook.js';

let s: Session;
const canBuild = spawnSync('bwrap', ['--version']).status === 0;
const scans: AxeSummary[] = [];

/** What has the keyboard focus: 'editor' (Monaco), or the focused element's role and label. */
const focusOf = (page: Session['page']) => page.evaluate(() => {
  const el = document.activeElement as HTMLElement | null;
  if (!el) return 'none';
  if (el.closest('.monaco-editor')) return 'editor';
  return `${el.getAttribute('role') ?? el.tagName.toLowerCase()}:${el.dataset.path ?? el.dataset.panel ?? el.dataset.name ?? el.getAttribute('aria-label') ?? ''}`;
});

/** Opens `file` by quick open (Ctrl+P, its name typed, Enter) and waits for its tab (`typed`: what is typed, when not the name). */
async function quickOpen(page: Session['page'], file: string, typed = file): Promise<void> {
  await page.keyboard.press('Control+p');
  await page.keyboard.type(typed);
  await page.keyboard.press('Enter');
  await expect.poll(() => activeTab(page)).toBe(file);
}

describe('keyboard-first IDE', () => {
  beforeAll(async () => {
    s = await startSession();
    await openIde(s);
    // runs of this walkthrough last 2 s
    await s.page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 2 })));
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('Ctrl+P opens quick open (not the print dialog): fuzzy match, arrows, Enter opens the file in the editor', async () => {
    const { page } = s;
    await page.keyboard.press('Control+p');
    const input = page.locator('#quick-open input[role=combobox]');
    await input.waitFor({ timeout: 5000 });
    expect(await focusOf(page)).toBe('combobox:Go to file');
    await page.keyboard.type('smod3');
    await expect.poll(() => page.locator('#quick-open [role=option]').first().textContent()).toBe('smodule3.contract');
    await shot(page, 'kb-01-quick-open');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page)).toBe('smodule3.contract');
    expect(await page.locator('#quick-open').count()).toBe(0);
    expect(await focusOf(page)).toBe('editor');
    // arrows move the selection; Escape closes and gives the focus back
    await page.keyboard.press('Control+p');
    await page.keyboard.type('contract');
    await page.keyboard.press('ArrowDown');
    expect(await page.locator('#quick-open [role=option][aria-selected=true]').count()).toBe(1);
    expect(await page.locator('#quick-open [role=option]').nth(1).getAttribute('aria-selected')).toBe('true');
    await page.keyboard.press('Escape');
    expect(await page.locator('#quick-open').count()).toBe(0);
    expect(await focusOf(page)).toBe('editor');
    expect(await activeTab(page)).toBe('smodule3.contract');
  });

  it('goes to a problem by keyboard (Ctrl+Shift+M, arrows, Enter), undoes the error there, Escape leaves the list', async () => {
    const { page } = s;
    await placeCursor(page, 'C=1ms', 3);
    await page.keyboard.type('x'); // C=1xms: an error the user typed
    await quickOpen(page, 'supervisor.contract');
    await page.locator('.problem-row[data-path="smodule3.contract"]').first().waitFor({ timeout: 5000 });
    await page.keyboard.press('Control+Shift+M');
    await expect.poll(() => focusOf(page)).toMatch(/^option:smodule3.contract/);
    expect(await page.locator('.panel-tab[data-panel=problems]').getAttribute('aria-selected')).toBe('true');
    const line = Number(await page.locator('.problem-row:focus').getAttribute('data-line'));
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page)).toBe('smodule3.contract');
    expect(await focusOf(page)).toBe('editor');
    expect(await cursorLine(page)).toBe(line);
    expect(await page.locator('#status-cursor').textContent()).toMatch(new RegExp(`^Ln ${line}, Col \\d+$`));
    await shot(page, 'kb-02-went-to-problem');
    await page.keyboard.press('Control+z');
    await expect.poll(() => page.locator('.problem-row[data-path="smodule3.contract"]').count(), { timeout: 5000 }).toBe(0);
    await waitSaved(page);
    // Escape in a list goes back to the editor
    await page.keyboard.press('Control+Shift+M');
    await page.keyboard.press('Escape');
    expect(await focusOf(page)).toBe('editor');
  });

  it('the command palette (F1 and Ctrl+Shift+P) lists the IDE commands with their shortcuts and the editor actions; Generate All from it', async () => {
    const { page } = s;
    await page.keyboard.press('F1');
    const palette = page.locator('#command-palette');
    await palette.waitFor({ timeout: 5000 });
    const rows = await palette.locator('[role=option]').evaluateAll((els) => els.map((e) => `${e.querySelector('.qp-label')?.textContent}|${e.querySelector('.qp-key')?.textContent ?? ''}`));
    for (const [label, key] of [['Generate All', 'Ctrl+Shift+G'], ['Build & Run', 'Ctrl+Shift+B'], ['Stop the running job', 'Alt+Shift+S'], ['Go to File…', 'Ctrl+P'],
      ['Open Architecture diagram', 'Alt+Shift+D'], ['Open Timeline', 'Alt+Shift+T'], ['Open Monitor', 'Alt+Shift+M'], ['Open Simulate panel', 'Alt+Shift+U'], ['Show Problems', 'Ctrl+Shift+M'],
      ['Focus Outline', 'Alt+Shift+O'], ['New File…', 'Alt+Shift+N'], ['Rename File…', 'Alt+Shift+R'], ['Reload from disk (discard unsaved edits)', 'Alt+Shift+L'],
      ['New Folder…', ''], ["New Project… (the report's six templates)", '']]) {
      expect(rows, label).toContain(`${label}|${key}`);
    }
    // the editor's own actions are there too (one palette inside and outside the editor)
    expect(rows.find((r) => r.startsWith('Go to Definition|'))).toMatch(/\|(Ctrl\+)?F12$/); // Monaco's own binding, as its keybinding service names it
    expect(rows).toContain('Format Document|Ctrl+Shift+I');
    expect(rows).toContain('Rename Symbol|F2');
    await shot(page, 'kb-03-command-palette');
    scans.push(await axeScan(page, 'command palette'));
    await page.keyboard.press('Escape');
    // an editor action from the palette: Go to Definition on MSB in sschema2.contract
    await quickOpen(page, 'sschema2.contract', 'sschema2');
    await placeCursor(page, 'MSB ();', 1);
    await page.keyboard.press('F1');
    await page.keyboard.type('go to definition');
    expect(await palette.locator('[role=option][aria-selected=true] .qp-label').textContent()).toBe('Go to Definition');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page), { timeout: 5000 }).toBe('smodule2.contract');
    await page.keyboard.press('Control+Shift+P');
    await palette.waitFor({ timeout: 5000 });
    await page.keyboard.type('generate all');
    expect(await palette.locator('[role=option][aria-selected=true] .qp-label').textContent()).toBe('Generate All');
    await page.keyboard.press('Enter');
    await page.locator('.gen-summary').waitFor({ timeout: 60_000 });
    expect(await page.locator('.gen-summary .pill').first().textContent()).toContain('generated');
    expect(await page.locator('.panel-tab[data-panel=generate]').getAttribute('aria-selected')).toBe('true');
    // the generated files are tab stops: Enter on one opens it (the panel had no focusable entry)
    const entry = page.locator('.gen-file[data-path$="MSA_mod/module.c"]');
    await entry.focus();
    expect(await focusOf(page)).toMatch(/^button:.*MSA_mod\/module\.c$/);
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page), { timeout: 5000 }).toMatch(/MSA_mod\/module\.c$/);
    expect(await focusOf(page)).toBe('editor');
    scans.push(await axeScan(page, 'Generate panel'));
    // Run settings has no shortcut: the palette opens its dialog, Escape closes it
    await page.keyboard.press('F1');
    await palette.waitFor({ timeout: 5000 });
    await page.keyboard.type('run settings');
    expect(await palette.locator('[role=option][aria-selected=true] .qp-label').textContent()).toBe('Run settings: duration, start request, init time, CPUs, stdin, real-time');
    await page.keyboard.press('Enter');
    const dialog = page.locator('.dialog-overlay .dialog');
    await dialog.waitFor({ timeout: 5000 });
    expect(await dialog.textContent()).toContain('Duration of a run');
    await page.keyboard.press('Escape');
    await expect.poll(() => dialog.count()).toBe(0);
    // the focus is back where it was before the palette (the editor), not on the page's body
    expect(await focusOf(page)).toBe('editor');
  }, 150_000);

  it.skipIf(!canBuild)('Build & Run from the palette, to the end of the run, without the mouse', async () => {
    const { page } = s;
    await page.keyboard.press('F1');
    await page.keyboard.type('build run');
    expect(await page.locator('#command-palette [role=option][aria-selected=true] .qp-label').textContent()).toBe('Build & Run');
    await page.keyboard.press('Enter');
    await expect.poll(() => page.locator('#status-job').getAttribute('data-status'), { timeout: 150_000 }).toMatch(/succeeded|failed/);
    expect(await page.locator('#status-job').getAttribute('data-status')).toBe('succeeded');
    expect(await page.locator('.panel-tab[data-panel=output]').getAttribute('aria-selected')).toBe('true');
    // the launcher's news is not in the error colour of stderr (it was: "exited with status 0" in red)
    const last = page.locator('.log-row[data-source=launcher]', { hasText: 'all modules stopped cleanly' });
    await last.waitFor({ timeout: 10_000 });
    expect(await last.getAttribute('class')).toBe('log-row stderr news');
    const colour = (row: typeof last) => row.locator('.log-text').evaluate((e) => getComputedStyle(e).color);
    expect(await colour(last)).toBe(await page.evaluate(() => getComputedStyle(document.body).color));
    await shot(page, 'kb-04-build-and-run');
  }, 180_000);

  it('in the editor Tab indents; Ctrl+M makes Tab leave the editor (and Ctrl+M again gives Tab back to the text)', async () => {
    const { page } = s;
    await openFile(page, 'sched.contract');
    await page.locator('.monaco-editor textarea').first().focus();
    expect(await focusOf(page)).toBe('editor');
    await page.keyboard.press('Control+m');
    await page.keyboard.press('Tab');
    await expect.poll(() => focusOf(page)).not.toBe('editor');
    await page.keyboard.press('Shift+Tab');
    await expect.poll(() => focusOf(page)).toBe('editor');
    await page.keyboard.press('Control+m'); // back to Tab indenting: the text gets it
    const text = () => page.evaluate(() => window.__ide.editors.editor.getModel()!.getValue());
    const before = await text();
    await page.keyboard.press('Tab');
    await expect.poll(text).not.toBe(before);
    expect(await focusOf(page)).toBe('editor');
    await page.keyboard.press('Control+z');
    await expect.poll(text).toBe(before);
  });

  it('explorer, tabs and panel tabs work by keyboard (tree, tablist, roving tabindex, Escape back to the editor)', async () => {
    const { page } = s;
    await page.keyboard.press('Control+Shift+E');
    await expect.poll(() => focusOf(page)).toMatch(/^treeitem:/);
    expect(await page.locator('.tree [tabindex="0"]').count()).toBe(1); // one Tab stop in the tree
    // Home: the first row (src-gen, a folder); → expands it, ← collapses it
    await page.keyboard.press('Home');
    expect(await focusOf(page)).toBe('treeitem:scenarios');
    const expanded = () => page.locator('.tree-row[data-path="scenarios"]').getAttribute('aria-expanded');
    const before = await expanded();
    if (before === 'true') await page.keyboard.press('ArrowLeft');
    await page.keyboard.press('ArrowRight');
    expect(await expanded()).toBe('true');
    expect(await focusOf(page)).toBe('treeitem:scenarios');
    await page.keyboard.press('ArrowRight'); // into the folder
    expect(await focusOf(page)).toMatch(/^treeitem:scenarios\//);
    await page.keyboard.press('ArrowLeft'); // back to the folder
    expect(await focusOf(page)).toBe('treeitem:scenarios');
    await page.keyboard.press('ArrowLeft');
    expect(await expanded()).toBe('false');
    // down to sschema2.contract and open it
    for (let i = 0; i < 40 && (await focusOf(page)) !== 'treeitem:sschema2.contract'; i++) await page.keyboard.press('ArrowDown');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page)).toBe('sschema2.contract');
    expect(await focusOf(page)).toBe('editor');
    // the explorer again, then Escape: back to the editor
    await page.keyboard.press('Control+Shift+E');
    expect(await focusOf(page)).toBe('treeitem:sschema2.contract');
    await page.keyboard.press('Escape');
    expect(await focusOf(page)).toBe('editor');

    // editor tabs: ←/→ move, Enter shows the tab and focuses its editor
    await page.keyboard.press('Alt+Shift+W');
    expect(await focusOf(page)).toBe('tab:sschema2.contract');
    await page.keyboard.press('Home');
    const first = await page.locator('.tabs .tab').first().getAttribute('data-path');
    expect(await focusOf(page)).toBe(`tab:${first}`);
    await page.keyboard.press('Enter');
    expect(await activeTab(page)).toBe(first);
    expect(await focusOf(page)).toBe('editor');

    // panel tabs: → shows the next panel, Escape back to the editor
    await page.keyboard.press('Control+Shift+M'); // the first problem, or the Problems tab when there is none
    if ((await focusOf(page)).startsWith('option:')) await page.keyboard.press('Shift+Tab'); // from the list back to its tab
    expect(await focusOf(page)).toBe('tab:problems');
    await page.keyboard.press('ArrowRight');
    expect(await focusOf(page)).toBe('tab:output');
    expect(await page.locator('.panel-tab[data-panel=output]').getAttribute('aria-selected')).toBe('true');
    expect(await page.locator('#panel-output').isVisible()).toBe(true);
    await page.keyboard.press('Escape');
    expect(await focusOf(page)).toBe('editor');
    await shot(page, 'kb-05-keyboard-lists');

    // Delete closes tab after tab; after the last, the focus is on the empty editor's hint, not the page's body
    await page.keyboard.press('Alt+Shift+W');
    for (let i = 0; i < 30 && (await page.locator('.tabs .tab').count()) > 0; i++) await page.keyboard.press('Delete');
    expect(await page.locator('.tabs .tab').count()).toBe(0);
    expect(await page.evaluate(() => document.activeElement?.className)).toBe('editor-empty');
    await page.keyboard.press('Control+p'); // and on from there
    await page.keyboard.type('sched.contract');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page)).toBe('sched.contract');
  });

  it('New File… and Rename File… from their shortcuts, in the keyboard-driven dialog', async () => {
    const { page } = s;
    await page.keyboard.press('Alt+Shift+N');
    const input = page.locator('.dialog-input');
    await input.waitFor({ timeout: 5000 });
    expect(await focusOf(page)).toMatch(/^input:/);
    await page.keyboard.press('Control+a');
    await page.keyboard.type('kb_new.contract');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page), { timeout: 5000 }).toBe('kb_new.contract');
    expect(await focusOf(page)).toBe('editor');
    // the rename's last step (loading the file under its new name) is held back 1 s: Ctrl+P
    // pressed meanwhile keeps its focus when that step ends
    let released!: () => void;
    const lateStepDone = new Promise<void>((r) => (released = r));
    await page.route('**/api/file?path=kb_renamed.contract', async (route) => {
      await new Promise((r) => setTimeout(r, 1000));
      await route.continue();
      setTimeout(released, 300);
    });
    await page.keyboard.press('Alt+Shift+R');
    await input.waitFor({ timeout: 5000 });
    await page.keyboard.press('Control+a');
    await page.keyboard.type('kb_renamed.contract');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page), { timeout: 5000 }).toBe('kb_renamed.contract');
    await page.locator('.tree-row[data-path="kb_renamed.contract"]').waitFor({ timeout: 5000 });
    expect(await page.locator('.tree-row[data-path="kb_new.contract"]').count()).toBe(0);
    await page.keyboard.press('Control+p');
    await page.locator('#quick-open input[role=combobox]').waitFor({ timeout: 5000 });
    await lateStepDone;
    await page.unroute('**/api/file?path=kb_renamed.contract');
    expect(await focusOf(page)).toBe('combobox:Go to file');
    await page.keyboard.press('Escape');
    expect(await focusOf(page)).toBe('editor');
  });

  it('outline by keyboard: Enter reveals the symbol in the editor', async () => {
    const { page } = s;
    await quickOpen(page, 'smodule3.contract');
    await page.locator('.outline-row[data-name="in_coordinates"]').waitFor({ timeout: 5000 });
    await page.keyboard.press('Alt+Shift+O');
    await expect.poll(() => focusOf(page)).toMatch(/^treeitem:/);
    for (let i = 0; i < 30 && (await focusOf(page)) !== 'treeitem:in_coordinates'; i++) await page.keyboard.press('ArrowDown');
    await page.keyboard.press('Enter');
    expect(await focusOf(page)).toBe('editor');
    expect(await cursorLine(page)).toBe(10);
  });

  it('Alt+Shift+U opens the Simulate panel on its supervisor function: arrows choose one, Tab reaches Start, Enter starts; Escape goes back to the editor', async () => {
    const { page } = s;
    await quickOpen(page, 'supervisor.contract');
    await expect.poll(() => focusOf(page)).toBe('editor');
    await page.keyboard.press('Alt+Shift+U');
    await expect.poll(() => focusOf(page)).toBe('select:supervisor function');
    await page.waitForSelector('.sim-fn option[value="SUP.action"]', { state: 'attached', timeout: 30_000 });
    await page.selectOption('.sim-fn', 'SUP.action'); // (what the arrow keys do in a headless select)
    const onStart = () => page.evaluate(() => document.activeElement?.classList.contains('sim-start') === true);
    for (let i = 0; i < 5 && !(await onStart()); i++) await page.keyboard.press('Tab');
    expect(await onStart()).toBe(true);
    await page.keyboard.press('Enter');
    await expect.poll(() => page.locator('.sim-message').textContent(), { timeout: 30_000 }).toMatch(/^simulated to 0 in \d+ ms/);
    await page.keyboard.press('Escape');
    await expect.poll(() => focusOf(page)).toBe('editor');
  });

  it('a tab click focuses its editor (Ctrl+Z undoes there), the status bar cursor follows the active editor, the active tab is scrolled into view', async () => {
    const { page } = s;
    await openFile(page, 'amodule1.contract');
    await placeCursor(page, 'module');
    await page.keyboard.type('/*kb*/');
    await openFile(page, 'sched.contract');
    await placeCursor(page, 'MSD', 0);
    const schedCursor = await page.locator('#status-cursor').textContent();
    await page.locator('.tabs .tab[data-path="amodule1.contract"]').click();
    expect(await focusOf(page)).toBe('editor');
    const amoduleCursor = await page.locator('#status-cursor').textContent();
    expect(amoduleCursor).not.toBe(schedCursor);
    expect(amoduleCursor).toBe(`Ln ${await cursorLine(page)}, Col ${await page.evaluate(() => window.__ide.editors.editor.getPosition()!.column)}`);
    await page.keyboard.press('Control+z');
    await expect.poll(() => page.evaluate(() => window.__ide.editors.editor.getModel()!.getValue().includes('/*kb*/'))).toBe(false);
    await waitSaved(page);
    // many tabs: the active one is always visible in the strip
    for (const f of ['amodule2.contract', 'aschema1.contract', 'datatype.contract', 'smodule1.contract', 'smodule2.contract', 'smodule4.contract', 'sschema1.contract', 'supervisor2.contract']) {
      await quickOpen(page, f);
    }
    await page.setViewportSize({ width: 900, height: 800 });
    for (const id of ['supervisor2.contract', await page.locator('.tabs .tab').first().getAttribute('data-path')]) {
      await page.locator(`.tabs .tab[data-path="${id}"]`).evaluate((el) => (el as HTMLElement).click());
      const [tab, strip] = await Promise.all([page.locator('.tab.active').boundingBox(), page.locator('.tabs').boundingBox()]);
      expect(tab!.x).toBeGreaterThanOrEqual(strip!.x - 1);
      expect(tab!.x + tab!.width).toBeLessThanOrEqual(strip!.x + strip!.width + 1);
    }
    await page.setViewportSize({ width: 1440, height: 900 });
  });

  it('axe-core: no serious or critical violation on the main screens (report in the output)', async () => {
    const { page } = s;
    await page.keyboard.press('Control+Shift+M');
    scans.push(await axeScan(page, 'editor, explorer, outline, problems'));
    await page.keyboard.press('Alt+Shift+B');
    scans.push(await axeScan(page, 'Build & Run output'));
    await page.keyboard.press('Alt+Shift+D');
    await page.locator('.view-host .arch-svg').waitFor({ timeout: 20_000 });
    scans.push(await axeScan(page, 'architecture diagram'));
    await page.keyboard.press('Alt+Shift+T');
    await page.locator('.timeline-view').first().waitFor({ timeout: 20_000 });
    scans.push(await axeScan(page, 'timeline'));
    await page.keyboard.press('Control+p');
    scans.push(await axeScan(page, 'quick open'));
    await page.keyboard.press('Escape');
    const serious = scans.flatMap((sc) => seriousOf(sc).map((v) => `${sc.screen}: ${v}`));
    expect(serious).toEqual([]);
  }, 240_000);
});
