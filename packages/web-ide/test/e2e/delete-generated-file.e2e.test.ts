/**
 * End-to-end: deleting a generated file whose protected regions hold code (docs/ide.md, "Deleting
 * a generated file"). The code was written after the last generation (on disk, as an editor or a
 * terminal would): the explorer's delete, by keyboard, says how many regions hold code, which, and
 * that the next generation restores them; Escape keeps the file; Enter deletes it; Generate All
 * brings the code back (GET /api/user-code: nothing for another file, a path leaving the workspace
 * refused). The confirmation said only "The file will be deleted from disk." before.
 */
import { describe, expect, it } from 'vitest';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ideSession, shot, type Session } from './harness.js';

const canGenerate = await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).generateArchitecture === 'function').catch(() => false);
const MAA = 'src-gen/generated/architecture/modules/MAA_mod/module.c';
const LAB = '/* lab code written after the last generation */';

let s: Session;

describe.skipIf(!canGenerate)('the explorer\'s delete of a generated file holding code', () => {
  s = ideSession({ buildService: false, timeout: 90_000 });

  it('says which regions hold code and that the next generation restores them; keyboard only; Generate All brings the code back', async () => {
    const { page } = s;
    const file = join(s.workspace, MAA);
    const text = readFileSync(file, 'utf8');
    writeFileSync(file, text.replace('/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/', `/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/\n    ${LAB}`));
    // down the tree by keyboard to MAA's module.c
    const parts = MAA.split('/');
    for (let i = 1; i <= parts.length; i++) {
      const path = parts.slice(0, i).join('/');
      const row = page.locator(`.tree-row[data-path="${path}"]`);
      await row.waitFor({ timeout: 10_000 });
      await row.focus();
      if (i < parts.length && (await row.getAttribute('aria-expanded')) !== 'true') await page.keyboard.press('ArrowRight');
    }
    await page.keyboard.press('Delete');
    const dialog = page.locator('.dialog');
    await dialog.waitFor({ timeout: 10_000 });
    const said = await dialog.locator('.dialog-hint').innerText();
    expect(said).toMatch(/^The file will be deleted from disk\. It is a generated file holding your code in \d+ protected regions \((protect_\w+_MAA, )*protect_exec_MAA(, protect_\w+_MAA)*\): the next generation \(Generate All, a build, contract generate\) generates it again with that code restored from the last generation's copy \(src-gen\/\.contract-regions\.json\)\. There is no other undo\.$/);
    await shot(page, 'delete-generated-file-confirmation');
    // Escape: nothing deleted
    await page.keyboard.press('Escape');
    await dialog.waitFor({ state: 'detached', timeout: 5000 });
    expect(existsSync(file)).toBe(true);
    // again, Enter on the focused Delete button: deleted
    await page.locator(`.tree-row[data-path="${MAA}"]`).focus();
    await page.keyboard.press('Delete');
    await dialog.waitFor({ timeout: 10_000 });
    await page.keyboard.press('Enter');
    await expect.poll(() => existsSync(file), { timeout: 10_000 }).toBe(false);
    // Generate All: the file is back with the code written after the last generation
    const res = await fetch(`${s.server.url}/api/generate`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': s.server.token }, body: '{"project":""}' });
    expect(res.status).toBe(200);
    const report = (await res.json()) as { created: string[]; warnings: { file: string; message: string }[] };
    expect(report.created).toContain('generated/architecture/modules/MAA_mod/module.c');
    expect(report.warnings.map((w) => w.message).join('\n')).toMatch(/restored \d+ protected region\(s\) of src-gen\/generated\/architecture\/modules\/MAA_mod\/module\.c/);
    expect(readFileSync(file, 'utf8')).toContain(LAB);
    // the route answers nothing for a file that is not generated, and refuses a path leaving the workspace
    const ask = (path: string) => fetch(`${s.server.url}/api/user-code?path=${encodeURIComponent(path)}`, { headers: { 'x-contract-token': s.server.token } });
    expect(await (await ask('amodule1.contract')).json()).toEqual({ regions: [], restorable: false });
    expect((await ask('../../etc/passwd')).status).toBeGreaterThanOrEqual(400);
  }, 120_000);
});
