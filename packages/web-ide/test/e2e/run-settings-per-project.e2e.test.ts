/**
 * End-to-end: the run settings of a workspace of two projects (a/ and b/, docs/ide.md, Build & Run):
 * the start request and the stdin files are kept per project, the project of the file being edited.
 * Before, the browser kept one start request and one stdin text, each with the one project it was
 * for: saving b's settings replaced a's, and a ran its default with every module on /dev/null.
 * The stdin rows are driven with the keyboard: a row added with *+ Add a module*, one removed with
 * its ✕.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { startSession, openIde, openFile, shot, type Session } from './harness.js';
import { axeScan, seriousOf } from './axe.js';

const SETTINGS = 'contract-studio:run-settings';
let s: Session;

describe("a workspace of two projects: each project's run settings", () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false, empty: true, port: 7841 });
    for (const p of ['a', 'b']) {
      mkdirSync(join(s.workspace, p));
      writeFileSync(join(s.workspace, p, 'types.contract'), `datatype T${p} {float i = 0.0};\n`);
    }
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  const field = (label: string) => s.page.getByLabel(label, { exact: true });
  const focused = (label: string) => field(label).evaluate((el) => el === document.activeElement);
  /** The dialog's start request and stdin rows, then closed (Escape). */
  async function shown(): Promise<{ start: string; rows: string[][] }> {
    const { page } = s;
    await page.locator('#btn-run-settings').click();
    await field('Stdin module 1').waitFor({ timeout: 5000 });
    const start = await page.locator('.dialog-input[data-key=start]').inputValue();
    const rows: string[][] = [];
    for (let n = 1; (await field(`Stdin module ${n}`).count()) > 0; n++) rows.push([await field(`Stdin module ${n}`).inputValue(), await field(`Stdin file ${n}`).inputValue()]);
    await page.keyboard.press('Escape');
    await expect.poll(() => page.locator('.dialog-overlay').count()).toBe(0);
    return { start, rows };
  }

  it("saving b's settings keeps a's start request and stdin files; each project shows its own", async () => {
    const { page } = s;
    await openFile(page, 'a/types.contract');
    expect(await shown()).toEqual({ start: '', rows: [['', '']] });

    // a: a start request, and two stdin rows by keyboard (a first row removed with its ✕)
    await page.locator('#btn-run-settings').click();
    await page.locator('.dialog-input[data-key=start]').fill('SUPA.go()');
    await field('Stdin module 1').focus();
    await page.keyboard.type('MAX');
    await page.keyboard.press('Tab');
    await page.keyboard.type('x.txt');
    await page.keyboard.press('Tab');
    expect(await field('Remove stdin row 1').evaluate((el) => el === document.activeElement)).toBe(true);
    await page.keyboard.press('Tab');
    await page.keyboard.press('Enter'); // + Add a module
    expect(await focused('Stdin module 2')).toBe(true);
    await page.keyboard.type('MAA');
    await page.keyboard.press('Tab');
    await page.keyboard.type('in, a é.txt');
    // back to row 1's ✕: Enter removes the row, the next one becomes row 1 and takes the focus
    await field('Remove stdin row 1').focus();
    await page.keyboard.press('Enter');
    expect(await focused('Stdin module 1')).toBe(true);
    expect(await field('Stdin file 1').inputValue()).toBe('in, a é.txt');
    await field('Stdin file 1').press('Tab');
    await page.keyboard.press('Tab');
    await page.keyboard.press('Enter'); // + Add a module
    await page.keyboard.type('MSD');
    await page.keyboard.press('Tab');
    await page.keyboard.type('in/d.txt');
    await shot(page, 'run-settings-stdin-rows');
    // every row's inputs and ✕ named: no serious or critical accessibility violation in the dialog
    expect(seriousOf(await axeScan(page, 'run settings with stdin rows'))).toEqual([]);
    await page.keyboard.press('Enter'); // Save
    await expect.poll(() => page.locator('.dialog-overlay').count()).toBe(0);
    expect(await shown()).toEqual({ start: 'SUPA.go()', rows: [['MAA', 'in, a é.txt'], ['MSD', 'in/d.txt']] });

    // b: none of a's; its own saved
    await openFile(page, 'b/types.contract');
    expect(await shown()).toEqual({ start: '', rows: [['', '']] });
    await page.locator('#btn-run-settings').click();
    await page.locator('.dialog-input[data-key=start]').fill('SUPB.go()');
    await field('Stdin module 1').fill('MSC');
    await field('Stdin file 1').fill('b.txt');
    await page.locator('.dialog .btn.primary').click();
    await expect.poll(() => page.locator('.dialog-overlay').count()).toBe(0);
    expect(await shown()).toEqual({ start: 'SUPB.go()', rows: [['MSC', 'b.txt']] });

    // a's settings are still a's
    await openFile(page, 'a/types.contract');
    expect(await shown()).toEqual({ start: 'SUPA.go()', rows: [['MAA', 'in, a é.txt'], ['MSD', 'in/d.txt']] });
    const saved = await page.evaluate((k) => JSON.parse(localStorage.getItem(k)!), SETTINGS);
    expect(saved.projects).toEqual({
      [`${s.workspace}/a`]: { start: 'SUPA.go()', stdin: { MAA: 'in, a é.txt', MSD: 'in/d.txt' } },
      [`${s.workspace}/b`]: { start: 'SUPB.go()', stdin: { MSC: 'b.txt' } },
    });

    // an earlier version's record (one start request, one stdin text, for a) is read for a, and kept for a when b saves
    await page.evaluate(([k, a]) => localStorage.setItem(k!, JSON.stringify({ duration: 3, start: 'OLD.go()', startFor: a, stdin: 'MAA=old.txt', stdinFor: a })), [SETTINGS, `${s.workspace}/a`]);
    expect(await shown()).toEqual({ start: 'OLD.go()', rows: [['MAA', 'old.txt']] });
    await openFile(page, 'b/types.contract');
    await page.locator('#btn-run-settings').click();
    await field('Stdin module 1').fill('MSC');
    await field('Stdin file 1').fill('b2.txt');
    await page.locator('.dialog .btn.primary').click();
    await expect.poll(() => page.locator('.dialog-overlay').count()).toBe(0);
    await openFile(page, 'a/types.contract');
    expect(await shown()).toEqual({ start: 'OLD.go()', rows: [['MAA', 'old.txt']] });
  }, 90_000);
});
