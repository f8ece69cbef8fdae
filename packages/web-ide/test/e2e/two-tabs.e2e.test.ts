/**
 * End-to-end: two IDE tabs (two browsers, each with its own storage) and other programs editing
 * one file. Nothing typed may be lost: disjoint edits are merged and written, overlapping ones
 * open the side-by-side view and nothing is written before the user chose (docs/ide.md, "Saves,
 * versions and merges"). Real server, real Chromium.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { readFileSync, writeFileSync, renameSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { join } from 'node:path';
import type { Page, Request } from 'playwright-core';
import { shot, placeCursor, activeValue, openFile, waitSaved, openAnotherTab, type Session, startTwoBrowsersOn } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

let s: Session;
let other: { page: Page; close(): Promise<void> };
const SCHED = 'sched.contract';
const disk = () => readFileSync(join(s.workspace, SCHED), 'utf8');
/** Another program writing the file the usual careful way (temp file + rename). */
const writeByScript = (text: string) => {
  writeFileSync(join(s.workspace, '.script.tmp'), text);
  renameSync(join(s.workspace, '.script.tmp'), join(s.workspace, SCHED));
};
/** The browser's copies of the file (browser-copies.ts: one entry per tab, key prefix + JSON [root, path, tab]), and any entry of the older form (one per file). */
const backups = (page: Page) => page.evaluate((p) => Object.keys(localStorage)
  .filter((k) => (k.startsWith('contract-studio:unsaved-copy:') && JSON.parse(k.slice('contract-studio:unsaved-copy:'.length))[1] === p) || (k.startsWith('contract-studio:unsaved:') && k.endsWith(`:${p}`)))
  .map((k) => localStorage.getItem(k) ?? ''), SCHED);

describe('one file edited in two IDE tabs and by a script', () => {
  beforeAll(async () => {
    ({ s, other } = await startTwoBrowsersOn(SCHED, 'second'));
  }, 90_000);
  afterAll(async () => {
    await other?.close();
    await s?.close();
  });

  it('two tabs typing on neighbouring lines at once: disk and both tabs end with both edits', async () => {
    const a = s.page;
    const b = other.page;
    const before = disk();
    await placeCursor(a, 'MSD;', 4);
    await placeCursor(b, 'MSC;', 4);
    await Promise.all([a.keyboard.type(' // A'), b.keyboard.type(' // B')]);
    const expected = before.replace('MSD;', 'MSD; // A').replace('MSC;', 'MSC; // B');
    await expect.poll(disk, { timeout: 10_000 }).toBe(expected);
    await expect.poll(() => activeValue(a), { timeout: 10_000 }).toBe(expected);
    await expect.poll(() => activeValue(b), { timeout: 10_000 }).toBe(expected);
    await waitSaved(a);
    await waitSaved(b);
    expect(await backups(a)).toEqual([]);
    expect(await backups(b)).toEqual([]);
    await shot(b, '20-two-tabs-merged');
  });

  it('a tab whose save was refused as stale merges and tells the user ("merged with a change made elsewhere")', async () => {
    const a = s.page;
    const b = other.page;
    const before = disk();
    await b.context().setOffline(true); // b keeps its base while a saves a newer text
    try {
      await placeCursor(b, 'MSB;', 4);
      await b.keyboard.type(' // offline edit');
      await b.locator('#status-save.error').waitFor({ timeout: 10_000 });
      await placeCursor(a, 'MSA;', 4);
      await a.keyboard.type(' // online edit');
      await expect.poll(disk, { timeout: 10_000 }).toContain('// online edit');
    } finally {
      await b.context().setOffline(false);
    }
    await b.keyboard.press('Control+s');
    const expected = before.replace('MSB;', 'MSB; // offline edit').replace('MSA;', 'MSA; // online edit');
    await expect.poll(disk, { timeout: 15_000 }).toBe(expected);
    await expect.poll(() => activeValue(b), { timeout: 10_000 }).toBe(expected);
    await expect.poll(() => activeValue(a), { timeout: 10_000 }).toBe(expected);
    await b.locator('.toast.info', { hasText: 'merged with a change made elsewhere' }).first().waitFor({ timeout: 5000 });
    // the cursor stayed where b was typing
    const line = await b.evaluate(() => window.__ide.editors.editor.getPosition()!.lineNumber);
    expect(expected.split('\n')[line - 1]).toContain('offline edit');
    await waitSaved(b);
  });

  it('overlapping edits: nothing is written blindly, the side-by-side view appears, the chosen merge keeps both', async () => {
    const a = s.page;
    const b = other.page;
    const before = disk();
    const puts: string[] = [];
    b.on('request', (r) => r.method() === 'PUT' && puts.push(r.url()));
    await b.context().setOffline(true);
    try {
      await placeCursor(b, 'schemaCommande1;', 'schemaCommande1;'.length);
      await b.keyboard.type(' // from tab B');
      await b.locator('#status-save.error').waitFor({ timeout: 10_000 });
      await placeCursor(a, 'schemaCommande1;', 'schemaCommande1;'.length);
      await a.keyboard.type(' // from tab A');
      await expect.poll(disk, { timeout: 10_000 }).toContain('// from tab A');
    } finally {
      await b.context().setOffline(false);
    }
    await b.keyboard.press('Control+s');
    const view = b.locator('.conflict-overlay');
    await view.waitFor({ timeout: 15_000 });
    await b.locator('.conflict-overlay .monaco-diff-editor').waitFor({ timeout: 5000 });
    await shot(b, '21-overlapping-edits-side-by-side');
    // nothing written over A's edit; B's text is in B's tab and in its browser copy
    const withA = before.replace('schemaCommande1;', 'schemaCommande1; // from tab A');
    expect(disk()).toBe(withA);
    expect(await activeValue(b)).toContain('// from tab B');
    const copy = await backups(b);
    expect(copy).toHaveLength(1);
    // this tab's copy (browser-copies.ts: one per tab; B is the only tab of its browser)
    expect((JSON.parse(copy[0]!) as { text: string }).text).toContain('// from tab B');
    expect(await b.locator('#status-save').textContent()).toMatch(/Overlapping edits/);
    // no save is retried while the user has not chosen
    const sent = puts.length;
    await b.waitForTimeout(1500);
    expect(puts.length).toBe(sent);
    expect(disk()).toBe(withA);
    // edit the merge: both versions between markers on the right; saving them as they are is refused
    await b.locator('#conflict-edit-merge').click();
    await b.locator('#conflict-save-right').click();
    await b.locator('.conflict-overlay .conflict-error', { hasText: 'conflict marker' }).waitFor({ timeout: 5000 });
    expect(disk()).toBe(withA);
    // resolved on the right side (both comments kept), then saved
    await b.evaluate(() => {
      const m = (window.__ide.monaco.editor.getModels() as Array<{ uri: { scheme: string }; getValue(): string; setValue(t: string): void; isDisposed(): boolean }>)
        .find((x) => !x.isDisposed() && x.uri.scheme === 'conflict' && x.getValue().includes('<<<<<<< yours'))!;
      m.setValue(m.getValue().replace(/<<<<<<< yours\n[^]*?>>>>>>> on disk\n/, '        schemaCommande1; // from tab A // from tab B\n'));
    });
    await b.locator('#conflict-save-right').click();
    await expect.poll(() => view.count()).toBe(0);
    await expect.poll(disk, { timeout: 10_000 }).toContain('// from tab B');
    const merged = disk();
    expect(merged).toContain('schemaCommande1; // from tab A // from tab B\n');
    expect(merged).not.toContain('<<<<<<<');
    await expect.poll(() => activeValue(b), { timeout: 5000 }).toBe(merged);
    await expect.poll(() => activeValue(a), { timeout: 10_000 }).toBe(merged);
    await waitSaved(b);
    expect(await backups(b)).toEqual([]);
  });

  it('keep my version after overlapping edits (buttons named by what they keep, long lines wrapped) writes the tab text on the disk version it was shown', async () => {
    const a = s.page;
    const b = other.page;
    await b.context().setOffline(true);
    try {
      await placeCursor(b, 'MSD; // A', 'MSD; // A'.length);
      // a long line: it wraps in the view rather than being cut on the right
      await b.keyboard.type(' mine, with a long explanation of the gain: add derivative action to damp the oscillation seen when the line curves sharply at speed');
      await b.locator('#status-save.error').waitFor({ timeout: 10_000 });
      await placeCursor(a, 'MSD; // A', 'MSD; // A'.length);
      await a.keyboard.type(' theirs');
      await expect.poll(disk, { timeout: 10_000 }).toContain('// A theirs');
    } finally {
      await b.context().setOffline(false);
    }
    await b.keyboard.press('Control+s');
    await b.locator('.conflict-overlay').waitFor({ timeout: 15_000 });
    await b.locator('.conflict-overlay .monaco-diff-editor').waitFor({ timeout: 5000 });
    // each button says what it keeps, and a line under the title says it for a beginner
    expect(await b.locator('.conflict-overlay .dialog-buttons button').allTextContents())
      .toEqual(['Edit the merge', 'Keep the version on disk (saved elsewhere)', 'Keep my version (this tab)', 'Save the right side as edited here']);
    expect(await b.locator('.conflict-overlay .conflict-choices').textContent()).toMatch(/^Keep my version \(this tab\): your text wins, the other change is lost\. Keep the version on disk/);
    // the long line wraps: the right side never scrolls sideways (its text fits its width)
    const fits = () => b.evaluate(() => {
      const e = window.__ide.monaco.editor.getEditors()
        .find((x) => x.getModel()?.uri.scheme === 'conflict' && x.getModel()!.uri.path.includes('/yours/'))!;
      return e.getScrollWidth() <= e.getLayoutInfo().width;
    });
    await expect.poll(fits, { timeout: 5000 }).toBe(true);
    await shot(b, '22-overlapping-edits-long-line-wrapped');
    const mine = await activeValue(b);
    await b.locator('#conflict-keep-mine').click();
    await expect.poll(disk, { timeout: 10_000 }).toBe(mine);
    await expect.poll(() => activeValue(a), { timeout: 10_000 }).toBe(mine);
    await waitSaved(b);
  });

  it('take theirs after overlapping edits: the tab shows the disk text, nothing of it overwritten', async () => {
    const a = s.page;
    const b = other.page;
    await b.context().setOffline(true);
    try {
      await placeCursor(b, 'MSC; // B', 'MSC; // B'.length);
      await b.keyboard.type(' dropped by choice');
      await b.locator('#status-save.error').waitFor({ timeout: 10_000 });
      await placeCursor(a, 'MSC; // B', 'MSC; // B'.length);
      await a.keyboard.type(' kept on disk');
      await expect.poll(disk, { timeout: 10_000 }).toContain('// B kept on disk');
    } finally {
      await b.context().setOffline(false);
    }
    const onDisk = disk();
    await b.keyboard.press('Control+s');
    await b.locator('.conflict-overlay').waitFor({ timeout: 15_000 });
    await b.locator('#conflict-take-theirs').click();
    await expect.poll(() => activeValue(b), { timeout: 5000 }).toBe(onDisk);
    await waitSaved(b);
    expect(disk()).toBe(onDisk);
    expect(await backups(b)).toEqual([]);
  });

    it('a browser copy made on an older base is merged with the disk after a reload, not written over it', async () => {
    const b = other.page;
    await waitSaved(b);
    const base = disk();
    const root = await b.evaluate(() => window.__ide.workspace.root);
    // the copy a tab kept before a reload: its text and the base it was edited from, as an earlier
    // version kept it (one entry per file): moved to this tab's own entry at the load, none lost
    const copy = { v: 1, text: base.replace('MSB;', 'MSB; // kept in the browser'), baseText: base, baseVersion: createHash('sha256').update(base).digest('hex') };
    // meanwhile another program changed another line
    writeByScript(base.replace('MSD;', 'MSD; // changed on disk'));
    await b.addInitScript(({ key, value }) => {
      if (!sessionStorage.getItem('copy-seeded')) {
        sessionStorage.setItem('copy-seeded', '1');
        localStorage.setItem(key, value);
      }
    }, { key: `contract-studio:unsaved:${root}:${SCHED}`, value: JSON.stringify(copy) });
    await b.reload();
    await b.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    const expected = base.replace('MSB;', 'MSB; // kept in the browser').replace('MSD;', 'MSD; // changed on disk');
    await expect.poll(disk, { timeout: 10_000 }).toBe(expected);
    await waitSaved(b);
    await openFile(b, SCHED);
    expect(await activeValue(b)).toBe(expected);
    await expect.poll(() => activeValue(s.page), { timeout: 10_000 }).toBe(expected);
    // the old entry is gone with the copy it held (moved, taken up, saved): nothing left to restore again
    expect(await backups(b)).toEqual([]);
  });

  it('a script writing the file while the user types: both changes kept', async () => {
    const a = s.page;
    await b_idle();
    const before = disk();
    await placeCursor(a, 'schemaCommande2;', 'schemaCommande2;'.length);
    const typing = a.keyboard.type(' // typed slowly while a script writes', { delay: 40 });
    await a.waitForTimeout(500);
    writeByScript(before.replace('scheduler configuration {', '// header added by a script\nscheduler configuration {'));
    await typing;
    const expected = before.replace('scheduler configuration {', '// header added by a script\nscheduler configuration {')
      .replace('schemaCommande2;', 'schemaCommande2; // typed slowly while a script writes');
    await expect.poll(disk, { timeout: 15_000 }).toBe(expected);
    await expect.poll(() => activeValue(a), { timeout: 10_000 }).toBe(expected);
    await expect.poll(() => activeValue(other.page), { timeout: 10_000 }).toBe(expected);
    await waitSaved(a);
  });

  it('a file moved away by a script while the user types in it: its tab closes, said, and the keys typed after go into no other file', async () => {
    const a = s.page;
    const moved = 'sschema2.contract';
    const shownBefore = readFileSync(join(s.workspace, SCHED), 'utf8');
    await openFile(a, SCHED);
    await openFile(a, moved);
    await placeCursor(a, 'schema', 0);
    await a.keyboard.type('/* typed */ ');
    await expect.poll(() => readFileSync(join(s.workspace, moved), 'utf8'), { timeout: 10_000 }).toContain('/* typed */ ');
    await waitSaved(a);
    renameSync(join(s.workspace, moved), join(s.workspace, 'elsewhere.contract'));
    try {
      await a.locator('.toast', { hasText: `${moved} is no longer in the workspace` }).waitFor({ timeout: 15_000 });
      // the keyboard is out of the editor of the file shown now (on no element): words typed on go nowhere
      expect(await a.evaluate(() => document.activeElement === document.body)).toBe(true);
      await a.keyboard.type('LOST words typed on');
      await new Promise((r) => setTimeout(r, 1500));
      expect(readFileSync(join(s.workspace, SCHED), 'utf8')).toBe(shownBefore);
      expect(await activeValue(a)).toBe(shownBefore);
    } finally {
      renameSync(join(s.workspace, 'elsewhere.contract'), join(s.workspace, moved));
    }
  }, 60_000);

  it('seven tabs in one browser: every tab gets file changes and saves (no tab holds one of the six HTTP connections the browser allows a server)', async () => {
    const streams: string[] = [];
    // every request of that browser's tabs, those to come included, from their first
    const seeStreams = (r: Request) => void (r.resourceType() === 'eventsource' && streams.push(r.url()));
    other.page.context().on('request', seeStreams);
    const tabs: Page[] = [other.page];
    try {
      while (tabs.length < 7) tabs.push(await openAnotherTab(s, other.page));
      const last = tabs.at(-1)!;
      await openFile(last, SCHED);
      await placeCursor(last, 'MSA;', 4);
      await last.keyboard.type(' // from the seventh tab');
      await expect.poll(disk, { timeout: 10_000 }).toContain('MSA; // from the seventh tab');
      await waitSaved(last);
      // and the first tab of that browser heard of it (its file events)
      await expect.poll(() => activeValue(other.page), { timeout: 10_000 }).toContain('MSA; // from the seventh tab');
      expect(streams).toEqual([]);
    } finally {
      other.page.context().off('request', seeStreams);
      for (const tab of tabs.slice(1)) await tab.close();
    }
  }, 120_000);
});

/** The second tab has nothing unsaved. */
async function b_idle(): Promise<void> {
  await waitSaved(other.page);
}
