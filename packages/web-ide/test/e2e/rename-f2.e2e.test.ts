/**
 * End-to-end: F2 renames on the mobile robot (docs/ide.md, "Rename carry-over"). A name the rename
 * rules refuse says why on the page (a toast) and changes nothing; an enumeration's rename moves
 * its generated `common/Shared<Enum>.h` and rewrites its C names (the type, `print_<Enum>`, the
 * constants `<Enum>_<MEMBER>`) in the protected regions' code; a member's rename its constant.
 * Every step waits on what it needs, never for a time: the language server answering a rename at
 * the cursor (waitRenameLocation: before, F2 found nothing to rename and no rename box opened, the
 * flaky part of the refused-rename test that ide.e2e.test had), the rename box focused, the toast
 * (its 5 s on the page are enough: it is waited for from the moment Enter is pressed), the files.
 * A rename the server cannot carry over (a target path taken) is taken back in the editor and
 * saves nothing: it said so in a notice, yet kept the renamed text in every tab and saved it, so
 * the next Generate All orphaned the module's code and generated into the user's folder. What the
 * user typed while the refusal was on its way is kept and saved; a server that does not answer
 * (the connection refused, page.route) gets the rename taken back too.
 */
import { describe, it, expect } from 'vitest';
import { existsSync, mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ideSession, renameWithF2, activeValue, waitSaved, shot, MOBILE_ROBOT, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const canGenerate = await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).generateArchitecture === 'function').catch(() => false);

let s: Session;
const disk = (p: string) => readFileSync(join(s.workspace, p), 'utf8');
const VEL = 'src-gen/generated/architecture/modules/VEL_mod/module.c';
const COMMON = 'src-gen/generated/architecture/common';
const MODULES = 'src-gen/generated/architecture/modules';

describe('F2 renames in the IDE', () => {
  s = ideSession({ example: MOBILE_ROBOT, buildService: false });

  it('a rename the rules refuse (a supervisor named abc) says why in a toast, and changes nothing', async () => {
    const { page } = s;
    const before = disk('mission.contract');
    await renameWithF2(page, 'mission.contract', 'supervisor MIS', 'supervisor '.length, 'abc');
    await page.locator('.toast.warning', { hasText: "Rename refused: 'abc' is not a valid supervisor name" }).first().waitFor({ timeout: 15_000 });
    expect(await activeValue(page)).toBe(before);
    expect(disk('mission.contract')).toBe(before);
  }, 60_000);

  it.skipIf(!canGenerate)('a rename whose generated tree cannot be carried over (QQQ_mod/ taken) is taken back: nothing saved, the module\'s code not orphaned', async () => {
    const { page } = s;
    const renamed = ['odometry.contract', 'control-loop.contract', 'scheduler.contract'];
    const before = new Map(renamed.map((f) => [f, disk(f)]));
    const userCode = 'double dl = (double)ticks.count[0] / ODO_TICKS_PER_RAD * wheel_radius;';
    expect(disk(`${MODULES}/ODO_mod/module.c`)).toContain(userCode);
    // the user's own folder where the renamed module's generated files would go
    mkdirSync(join(s.workspace, MODULES, 'QQQ_mod'));
    writeFileSync(join(s.workspace, MODULES, 'QQQ_mod/notes.txt'), 'notes\n');

    await renameWithF2(page, 'odometry.contract', 'module ODO', 'module '.length, 'QQQ');
    const notice = page.locator('.toast.error', { hasText: 'QQQ_mod already exists' }).first();
    await notice.waitFor({ timeout: 15_000 });
    // every model the rename edited shows its text again, the open tab as the others
    await expect.poll(() => activeValue(page), { timeout: 10_000 }).toBe(before.get('odometry.contract'));
    for (const f of renamed) {
      expect(await page.evaluate((p) => window.__ide.workspace.files.get(p)!.model.getValue(), f)).toBe(before.get(f));
    }
    await waitSaved(page);
    await page.waitForTimeout(1000); // past autosave's delay: a held save let go would have been written by now
    await shot(page, 'rename-f2-not-carried-over');
    for (const f of renamed) expect(disk(f), f).toBe(before.get(f));
    expect(existsSync(join(s.workspace, 'src-gen/.contract-rename.json'))).toBe(false);
    expect(await page.locator('#status-save').textContent()).toContain('All saved');
    expect(await page.locator('.toast', { hasText: 'Renamed ODO → QQQ' }).count()).toBe(0);
    expect(await notice.textContent()).toContain('Rename ODO → QQQ not made: cannot carry generated/architecture/modules/ODO_mod over: QQQ_mod already exists');
    expect(await notice.textContent()).toContain('No file was changed; the editor\'s rename was taken back, nothing renamed was saved');

    // the next Generate All: ODO's code stays ODO's, nothing generated into the user's folder
    await page.locator('#btn-generate').click();
    await page.locator('.gen-summary').waitFor({ timeout: 30_000 });
    expect(disk(`${MODULES}/ODO_mod/module.c`)).toContain(userCode);
    expect(readdirSync(join(s.workspace, MODULES, 'QQQ_mod'))).toEqual(['notes.txt']);
    expect(existsSync(join(s.workspace, 'src-gen/orphans'))).toBe(false);
  }, 90_000);

  it('a rename the server refuses while the user types on: the rename is taken back, the typing kept and saved; no answer at all: taken back too', async () => {
    const { page } = s;
    const renamed = ['navigation.contract', 'drive.contract', 'localisation-loop.contract', 'scheduler.contract'];
    const before = new Map(renamed.map((f) => [f, disk(f)]));
    const model = (p: string) => page.evaluate((path) => window.__ide.workspace.files.get(path)!.model.getValue() as string, p);
    // the server's answer held until the user typed in the renamed file, then a refusal
    let answer!: () => void;
    const typed = new Promise<void>((r) => (answer = r));
    await page.route('**/api/rename-entity', async (route) => {
      await typed;
      await route.fulfill({ status: 409, contentType: 'application/json', body: JSON.stringify({ error: 'refused by the test' }) });
    });
    try {
      await renameWithF2(page, 'navigation.contract', 'module NAV', 'module '.length, 'PLN');
      await expect.poll(() => activeValue(page), { timeout: 10_000 }).toContain('module PLN {');
      await page.keyboard.press('Control+End');
      await page.keyboard.type('// typed while the rename was on its way\n');
      answer();
      const notice = page.locator('.toast.error', { hasText: 'refused by the test' }).first();
      await notice.waitFor({ timeout: 15_000 });
      await expect.poll(() => activeValue(page), { timeout: 10_000 }).toBe(`${before.get('navigation.contract')}// typed while the rename was on its way\n`);
      expect(await notice.textContent()).toContain('Rename NAV → PLN not made: refused by the test');
      await waitSaved(page);
      expect(disk('navigation.contract')).toBe(await activeValue(page)); // the typing saved, as any edit
      for (const f of renamed.slice(1)) {
        expect(await model(f)).toBe(before.get(f));
        expect(disk(f), f).toBe(before.get(f));
      }
    } finally {
      await page.unroute('**/api/rename-entity');
    }
    const typedText = disk('navigation.contract');

    // no answer (the connection refused): the failure may come before the editor applied the rename
    await page.route('**/api/rename-entity', (route) => route.abort('connectionrefused'));
    try {
      await renameWithF2(page, 'navigation.contract', 'module NAV', 'module '.length, 'PLN');
      const notice = page.locator('.toast.error', { hasText: 'server unreachable' }).first();
      await notice.waitFor({ timeout: 15_000 });
      await expect.poll(() => activeValue(page), { timeout: 10_000 }).toBe(typedText);
      expect(await notice.textContent()).toContain('Rename NAV → PLN not made: server unreachable. The IDE server did not answer');
      await waitSaved(page);
      await page.waitForTimeout(1000); // past autosave's delay
      expect(disk('navigation.contract')).toBe(typedText);
      for (const f of renamed.slice(1)) {
        expect(await model(f)).toBe(before.get(f));
        expect(disk(f), f).toBe(before.get(f));
      }
    } finally {
      await page.unroute('**/api/rename-entity');
    }
  }, 90_000);

  it.skipIf(!canGenerate)('an enumeration: the .contract files, common/Shared<Enum>.h and its C names in the regions\' code follow; then a member', async () => {
    const { page } = s;
    expect(disk(VEL)).toContain('if (mode == DriveMode_SAFESTOP) { v = 0.0; w = 0.0; }');
    await renameWithF2(page, 'types.contract', 'enum DriveMode', 'enum '.length, 'Mode');
    await expect.poll(() => disk('types.contract'), { timeout: 10_000 }).toContain('enum Mode { TELEOP, AUTO, SAFESTOP }');
    await expect.poll(() => disk('velocity.contract'), { timeout: 10_000 }).toContain('Mode mode = Mode.TELEOP :1;');
    await expect.poll(() => existsSync(join(s.workspace, COMMON, 'SharedMode.h')), { timeout: 15_000 }).toBe(true);
    await expect.poll(() => disk(VEL), { timeout: 15_000 }).toContain('if (mode == Mode_SAFESTOP) { v = 0.0; w = 0.0; }');
    expect(disk(VEL)).toContain('print_Mode(&mode);');
    await page.locator('.toast', { hasText: 'Renamed DriveMode → Mode: 1 generated path(s)' }).first().waitFor({ timeout: 15_000 });
    // Generate All ran after the carry-over: the old header is not made again, nothing was orphaned
    await expect.poll(() => disk(VEL), { timeout: 15_000 }).toContain('Mode mode = Mode_TELEOP;');
    expect(existsSync(join(s.workspace, COMMON, 'SharedDriveMode.h'))).toBe(false);
    expect(existsSync(join(s.workspace, 'src-gen/orphans'))).toBe(false);

    await renameWithF2(page, 'types.contract', 'SAFESTOP', 0, 'HALT');
    await expect.poll(() => disk('types.contract'), { timeout: 10_000 }).toContain('enum Mode { TELEOP, AUTO, HALT }');
    await expect.poll(() => disk(VEL), { timeout: 15_000 }).toContain('if (mode == Mode_HALT) { v = 0.0; w = 0.0; }');
    await expect.poll(() => disk('drive.contract'), { timeout: 10_000 }).toContain('Mode.HALT');
    expect(disk('drive.contract')).not.toMatch(/\bSAFESTOP\b/);
  }, 120_000);
});
