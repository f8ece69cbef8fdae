/**
 * End-to-end: the server guards generated C against a stale tab. A tab of MAA_mod/module.c edits a
 * protected region while the browser is offline (its save fails), the model changes and the tree
 * is regenerated meanwhile (by another client: the HTTP API, like the CLI or a second tab); when
 * the browser is back, the stale save must not bring the old skeleton back. The save names its
 * base version, so the server answers 409 with the regenerated file; the tab merges three-way
 * (its region edit + the new skeleton) and saves that, which the region guard then accepts
 * (docs/ide.md, "Saves, versions and merges": which mechanism applies where).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { startSession, openIde, shot, placeCursor, activeValue, waitSaved, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const canGenerate = await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).generateArchitecture === 'function').catch(() => false);
const MAA = 'src-gen/generated/architecture/modules/MAA_mod/module.c';

let s: Session;
/** The browser's copies of unsaved edits of file `p` (browser-copy-store.ts: one entry a file and tab, key prefix + JSON [root, path, tab]), run in the page. */
const copiesOf = (p: string) => {
  const prefix = 'contract-studio:unsaved-copy:';
  return Object.keys(localStorage).filter((k) => k.startsWith(prefix) && (JSON.parse(k.slice(prefix.length)) as string[])[1] === p).map((k) => localStorage.getItem(k));
};
const disk = (p: string) => readFileSync(join(s.workspace, p), 'utf8');
const editModel = (from: string, to: string) => {
  const text = disk('amodule1.contract');
  expect(text).toContain(from);
  writeFileSync(join(s.workspace, 'amodule1.contract'), text.replace(from, to));
};
/** Generate All by another client (not this browser, which is offline). */
const generateElsewhere = async () => {
  const res = await fetch(`${s.server.url}/api/generate`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': s.server.token }, body: '{"project":""}' });
  expect(res.status).toBe(200);
  return (await res.json()) as { updated: string[]; orphaned: string[] };
};
/** Types `text` on a new line at the start of protected region `id` of the active editor. */
const typeInRegion = async (id: string, text: string) => {
  const marker = `/*PROTECTED REGION ID(${id}) ENABLED START*/`;
  await placeCursor(s.page, marker, marker.length);
  await s.page.keyboard.press('Enter');
  await s.page.keyboard.type(text);
};

describe.skipIf(!canGenerate)('the server guards generated C against stale tabs', () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false });
    await openIde(s);
    await s.page.locator('#btn-generate').click();
    await s.page.locator('.gen-summary').waitFor({ timeout: 30_000 });
    // open it from the Generate panel (the explorer is still expanding the new tree at this point)
    await s.page.locator(`.gen-file[data-path="${MAA}"]`).click();
    await s.page.waitForFunction((p) => document.querySelector('.tab.active')?.getAttribute('data-path') === p, MAA);
    await waitSaved(s.page);
  }, 90_000);
  afterAll(async () => {
    await s?.close();
  });

  it('a stale save after Generate All keeps the new skeleton and the edited region; the tab shows the merged file', async () => {
    const { page } = s;
    await page.context().setOffline(true);
    try {
      await typeInRegion('protect_exec_MAA', '/* typed in a stale tab */');
      await page.locator('#status-save.error').waitFor({ timeout: 10_000 });
      editModel('out :2 string connection_status;', 'out :2 string connection_status;\n        out :3 string added_status;');
      expect((await generateElsewhere()).updated).toContain('generated/architecture/modules/MAA_mod/module.c');
      expect(disk(MAA)).toContain('added_status');
      expect(disk(MAA)).not.toContain('typed in a stale tab');
      expect(await activeValue(page)).not.toContain('added_status'); // the tab is stale
    } finally {
      await page.context().setOffline(false);
    }
    await page.keyboard.press('Control+s');
    await expect.poll(() => disk(MAA), { timeout: 20_000 }).toContain('/* typed in a stale tab */');
    const merged = disk(MAA);
    expect(merged).toContain('added_status'); // the new skeleton stayed
    expect(merged.match(/added_status/g)!.length).toBeGreaterThan(1); // variable + interface table
    await expect.poll(() => activeValue(page), { timeout: 10_000 }).toBe(merged);
    await page.locator('.toast.info', { hasText: 'merged with a change made elsewhere' }).first().waitFor({ timeout: 5000 });
    await waitSaved(page);
    await expect.poll(() => page.locator('.toast.error', { hasText: `Could not save ${MAA}` }).count()).toBe(0); // out of date once saved
    // the cursor stayed in the region it was typing in
    const line = await page.evaluate(() => window.__ide.editors.editor.getPosition()!.lineNumber);
    expect(merged.split('\n')[line - 1]).toContain('typed in a stale tab');
    await shot(page, '10-stale-tab-merged');
  });

  it('a stale edit of a region the regenerated file no longer has: side-by-side view; "keep mine" is refused by the guard, told, kept in the browser and not retried', async () => {
    const { page } = s;
    await page.context().setOffline(true);
    try {
      await typeInRegion('protect_event_MAA', '/* reacts to controlevent */');
      await page.locator('#status-save.error').waitFor({ timeout: 10_000 });
      editModel('in :0 string controlevent;\n', '');
      expect((await generateElsewhere()).orphaned.length).toBeGreaterThan(0); // the region's former content went to src-gen/orphans
      expect(disk(MAA)).not.toContain('protect_event_MAA');
    } finally {
      await page.context().setOffline(false);
    }
    const onDisk = disk(MAA);
    const puts: string[] = [];
    page.on('request', (r) => r.method() === 'PUT' && puts.push(r.url()));
    await page.keyboard.press('Control+s');
    // the edit sits in a block the regeneration removed: an overlap, nothing written yet
    await page.locator('.conflict-overlay').waitFor({ timeout: 10_000 });
    expect(disk(MAA)).toBe(onDisk);
    await page.locator('#conflict-keep-mine').click();
    const refused = page.locator('.toast.error', { hasText: 'Not saved:' }).first();
    await refused.waitFor({ timeout: 10_000 });
    expect(await refused.textContent()).toMatch(/'protect_event_MAA' no longer exists/);
    await page.locator('#status-save.error').waitFor();
    await shot(page, '11-stale-tab-refused');
    expect(disk(MAA)).toBe(onDisk);
    expect(await activeValue(page)).toContain('/* reacts to controlevent */');
    const backup = await page.evaluate(copiesOf, MAA);
    expect(backup).toHaveLength(1);
    expect(backup[0]).toContain('/* reacts to controlevent */');
    // no retry loop: a failed network write would be retried after 2 s
    const sent = puts.length;
    await page.waitForTimeout(4500);
    expect(puts.length).toBe(sent);
    // "Reload from disk" drops the refused text and shows the file on disk
    await page.evaluate(() => void window.__ide.editors.editor.getAction('contract.reloadFromDisk')!.run()); // resolves after the dialog
    await page.locator('.dialog .btn.danger', { hasText: 'Reload' }).click();
    await expect.poll(() => activeValue(page)).toBe(onDisk);
    await waitSaved(page);
    expect(await page.evaluate(copiesOf, MAA)).toHaveLength(0);
  });

  it('a generated file holding Latin-1 bytes (written by another editor) turns read-only when they arrive: typing in a region writes nothing over them, and the tab says why', async () => {
    const { page } = s;
    const file = join(s.workspace, MAA);
    const marker = '/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/';
    const latin1 = Buffer.from(readFileSync(file, 'latin1').replace(marker, `${marker}\n/* caf\xe9 */`), 'latin1');
    writeFileSync(file, latin1);
    await expect.poll(() => activeValue(page), { timeout: 15_000 }).toContain('/* caf\uFFFD */');
    await typeInRegion('protect_exec_MAA', '/* typed over Latin-1 */');
    await page.waitForTimeout(1500); // past the autosave delay
    expect(readFileSync(file).equals(latin1)).toBe(true);
    expect(await activeValue(page)).not.toContain('/* typed over Latin-1 */');
    await page.locator('.monaco-editor .monaco-editor-overlaymessage', { hasText: 'holds bytes that are not UTF-8' }).waitFor({ timeout: 5000 });
    await shot(page, '12-latin1-read-only');
    // converted to UTF-8 by the user: the tab is editable again
    writeFileSync(file, readFileSync(file, 'latin1'));
    await expect.poll(() => activeValue(page), { timeout: 15_000 }).toContain('/* café */');
    await typeInRegion('protect_exec_MAA', '/* typed after conversion */');
    await expect.poll(() => readFileSync(file, 'utf8'), { timeout: 10_000 }).toContain('/* typed after conversion */');
    await waitSaved(page);
  });
});
