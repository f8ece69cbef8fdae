/**
 * Two tabs of one browser (one localStorage) editing the same file while the IDE server is down
 * (docs/ide.md "Saving"): the browser keeps each tab's unsaved text (one copy per tab), the second
 * tab's never over the first's. The first tab closed before the server is back: its edits were
 * only in that shared copy, which the second tab's typing had replaced — lost, without a word.
 * Now the tab left saves its own, then takes up the closed tab's copy, merges it with the disk and
 * says so. Real server stopped and started again on its port (the same session), real Chromium.
 */
import { describe, it, expect } from 'vitest';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { startIdeServer } from '../../server/ide-server.js';
import { ideSession, openAnotherTab, openFile, placeCursor, waitSaved, activeValue, shot, type Session } from './harness.js';

const SCHED = 'sched.contract';
let s: Session;
const disk = () => readFileSync(join(s.workspace, SCHED), 'utf8');
/**
 * The browser's copies of the file's unsaved text, one per tab (browser-copies.ts: each tab's under its
 * own key; the shared entry of earlier versions, by tab inside, read too).
 */
const copies = (page: Page) => page.evaluate((p) => {
  const out: string[] = [];
  for (const key of Object.keys(localStorage)) {
    const raw = localStorage.getItem(key)!;
    if (key.startsWith('contract-studio:unsaved-copy:')) {
      const [, path] = JSON.parse(key.slice('contract-studio:unsaved-copy:'.length)) as [string, string, string];
      if (path === p) out.push((JSON.parse(raw) as { text: string }).text);
    } else if (key.startsWith('contract-studio:unsaved:') && key.endsWith(`:${p}`)) {
      const v = JSON.parse(raw) as { copies?: Record<string, { text: string }>; text?: string };
      out.push(...(v.copies ? Object.values(v.copies).map((c) => c.text) : [v.text ?? '']));
    }
  }
  return out;
}, SCHED);
/** Every notice shown (toasts), kept by the page. */
const noticesOf = (page: Page) => page.evaluate(() => [...document.querySelectorAll('.toast')].map((t) => t.textContent ?? ''));

describe('two tabs of one browser edit a file while the server is down', () => {
  s = ideSession({ buildService: false });

  it("one tab's edit never replaces the other's in the browser; the first tab closed before the server is back, both edits reach the disk, said", async () => {
    const a = s.page;
    await openFile(a, SCHED);
    const b = await openAnotherTab(s, a);
    await openFile(b, SCHED);
    await waitSaved(a);
    const base = disk();
    const port = Number(new URL(s.server.url).port);
    const token = s.server.token; // restarted with the same session: the tabs keep theirs
    await s.server.close();
    try {
      await placeCursor(a, 'MSB;', 4);
      await a.keyboard.insertText(' // from tab A');
      await a.locator('#status-save.error').waitFor({ timeout: 10_000 });
      await b.bringToFront();
      await placeCursor(b, 'MSD;', 4);
      await b.keyboard.insertText(' // from tab B');
      await b.locator('#status-save.error').waitFor({ timeout: 10_000 });
      // both texts in the browser, each its tab's
      const kept = await copies(b);
      expect(kept.length, JSON.stringify(kept)).toBe(2);
      expect(kept.some((t) => t.includes('// from tab A') && !t.includes('// from tab B'))).toBe(true);
      expect(kept.some((t) => t.includes('// from tab B') && !t.includes('// from tab A'))).toBe(true);
      // tab A goes before the server is back: its text is only in the browser now
      await a.close();
      expect(disk()).toBe(base);
    } finally {
      s.server = await startIdeServer({ workspace: s.workspace, port, buildService: false, token });
    }
    const both = base.replace('MSB;', 'MSB; // from tab A').replace('MSD;', 'MSD; // from tab B');
    await expect.poll(disk, { timeout: 30_000 }).toBe(both);
    await waitSaved(b);
    expect(await activeValue(b)).toBe(both);
    expect(await copies(b)).toEqual([]);
    // said: the closed tab's edits came back, merged with this tab's
    const notices = await noticesOf(b);
    expect(notices.some((n) => n.includes(`Restored unsaved edits of ${SCHED} kept in this browser`)), notices.join('\n')).toBe(true);
    await shot(b, 'offline-two-tabs-01-merged');
    s.page = b; // the session's page for close()
  }, 90_000);

  it("both tabs still open, their offline edits overlapping: the tab whose save lost is asked, the other does not take up its copy (nor ask it again)", async () => {
    const a = s.page;
    await openFile(a, SCHED);
    const b = await openAnotherTab(s, a);
    await openFile(b, SCHED);
    await waitSaved(a);
    await waitSaved(b);
    const base = disk();
    const port = Number(new URL(s.server.url).port);
    const token = s.server.token;
    await s.server.close();
    try {
      await a.bringToFront();
      await placeCursor(a, 'MSC;', 4);
      await a.keyboard.insertText(' // A says this');
      await a.locator('#status-save.error').waitFor({ timeout: 10_000 });
      await b.bringToFront();
      await placeCursor(b, 'MSC;', 4);
      await b.keyboard.insertText(' // B says that');
      await b.locator('#status-save.error').waitFor({ timeout: 10_000 });
    } finally {
      s.server = await startIdeServer({ workspace: s.workspace, port, buildService: false, token });
    }
    // one of them saves first; the other's save is refused as stale and, overlapping, asks its user
    await expect.poll(disk, { timeout: 30_000 }).not.toBe(base);
    const winner = disk().includes('// A says this') ? a : b;
    const loser = winner === a ? b : a;
    await loser.locator('.conflict-overlay').waitFor({ timeout: 30_000 });
    // the loser's copy stays in the browser while it is asked; the winner, saved, leaves it to it
    await winner.waitForTimeout(4000);
    expect(await winner.locator('.conflict-overlay').count()).toBe(0);
    // the loser's copy is kept, not taken up by the winner (its editor has none of it), and it is the only
    // one: the winner's, dropped once saved, is not put back by the loser's writes (each tab has its own key)
    const left = await copies(winner);
    const loserText = loser === a ? '// A says this' : '// B says that';
    expect(left, JSON.stringify(left)).toHaveLength(1);
    expect(left[0], JSON.stringify(left)).toContain(loserText);
    expect(await activeValue(winner)).not.toContain(loserText);
    await shot(loser, 'offline-two-tabs-02-overlap-asked');
    await loser.locator('#conflict-take-theirs').click().catch(() => undefined);
    await loser.close();
  }, 90_000);
});
