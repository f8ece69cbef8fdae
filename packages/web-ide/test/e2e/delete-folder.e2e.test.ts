/**
 * End-to-end: deleting a folder in the Explorer (docs/ide.md, "Deleting a folder"). Its
 * confirmation said only "The folder and everything in it will be deleted from disk." whatever it
 * held; now it says how many files, and names the generated files in it whose protected regions
 * hold code with those regions, as the delete of one generated file does (GET /api/folder-contents,
 * the tree's user code recorded first): restored by the next generation when the folder leaves the
 * tree's copy of that code (src-gen/.contract-regions.json), lost when it takes it along.
 */
import { afterAll, beforeAll, afterEach, describe, expect, it } from 'vitest';
import { existsSync, mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { RENAME_JOURNAL_NAME, TREE_LOCK_NAME } from '@contract-studio/conventions';
import { openIde, shot, startSession, type Session } from './harness.js';

const canGenerate = await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).userCodeOfFiles === 'function').catch(() => false);
/** This file's own port (each browser test file has its own server on its own port). */
const PORT = 7921;
const MAA_DIR = 'src-gen/generated/architecture/modules/MAA_mod';
const LAB = '/* lab code written after the last generation */';

/** The files under `dir` as the Explorer lists them (links and the tree's lock left out), counted on disk. */
function filesIn(dir: string): number {
  return readdirSync(dir, { withFileTypes: true }).filter((e) => e.name !== TREE_LOCK_NAME && e.name !== RENAME_JOURNAL_NAME)
    .reduce((n, e) => n + (e.isFile() ? 1 : e.isDirectory() ? filesIn(join(dir, e.name)) : 0), 0);
}

/** Focuses the Explorer's row of `path`, its folders expanded by keyboard, and presses Delete: the confirmation's text. */
async function askDelete(page: Page, path: string): Promise<string> {
  const parts = path.split('/');
  for (let i = 1; i <= parts.length; i++) {
    const row = page.locator(`.tree-row[data-path="${parts.slice(0, i).join('/')}"]`);
    await row.waitFor({ timeout: 10_000 });
    await row.focus();
    if (i < parts.length && (await row.getAttribute('aria-expanded')) !== 'true') await page.keyboard.press('ArrowRight');
  }
  await page.keyboard.press('Delete');
  const dialog = page.locator('.dialog');
  await dialog.waitFor({ timeout: 10_000 });
  expect(await dialog.locator('.dialog-title').innerText()).toBe(`Delete ${path}?`);
  return dialog.locator('.dialog-hint').innerText();
}

let s: Session;

describe.skipIf(!canGenerate)('the explorer\'s delete of a folder says what it holds', () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false, port: PORT });
    // code written in a region after the last generation (on disk, as an editor or a terminal would)
    const file = join(s.workspace, MAA_DIR, 'module.c');
    writeFileSync(file, readFileSync(file, 'utf8').replace('/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/', `/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/\n    ${LAB}`));
    mkdirSync(join(s.workspace, 'notes/old'), { recursive: true });
    for (const f of ['a.txt', 'b.txt', 'old/c.txt']) writeFileSync(join(s.workspace, 'notes', f), 'x\n');
    mkdirSync(join(s.workspace, 'empty'));
    await openIde(s);
  }, 90_000);
  afterAll(async () => {
    await s?.close();
  });
  afterEach(async () => {
    if (await s.page.locator('.dialog').count()) await s.page.keyboard.press('Escape');
  });

  it('a module\'s generated folder: its files counted, module.c named with the region holding code, restored by the next generation; Escape keeps it', async () => {
    const { page } = s;
    const said = await askDelete(page, MAA_DIR);
    const n = filesIn(join(s.workspace, MAA_DIR));
    expect(said).toMatch(new RegExp(`^The folder and everything in it will be deleted from disk: ${n} files\\. One of them is a generated file holding your code in protected regions: module\\.c \\((protect_\\w+_MAA, )*protect_exec_MAA(, protect_\\w+_MAA)*\\)\\. The next generation \\(Generate All, a build, contract generate\\) generates it again with that code restored from the last generation's copy \\(src-gen/\\.contract-regions\\.json\\)\\. There is no other undo\\.$`));
    await shot(page, 'delete-folder-confirmation');
    await page.keyboard.press('Escape');
    await page.locator('.dialog').waitFor({ state: 'detached', timeout: 5000 });
    expect(existsSync(join(s.workspace, MAA_DIR, 'module.c'))).toBe(true);
  });

  it('the whole src-gen folder: its files holding code, the first five named, the rest counted; the copy of the code goes with it, so the code is said lost', async () => {
    const said = await askDelete(s.page, 'src-gen');
    const n = filesIn(join(s.workspace, 'src-gen'));
    // the tutorial's generated files holding code, as the tree's record has them (the request recorded them first)
    const held = Object.entries((JSON.parse(readFileSync(join(s.workspace, 'src-gen/.contract-manifest.json'), 'utf8')) as { userCode: Record<string, string[]> }).userCode).sort(([a], [b]) => (a < b ? -1 : 1));
    expect(held.length).toBeGreaterThan(5);
    const named = held.slice(0, 5).map(([path, regions]) => `${path} (${regions.join(', ')})`).join('; ');
    expect(said).toContain(`The folder and everything in it will be deleted from disk: ${n} files. ${held.length} of them are generated files holding your code in protected regions: ${named}; and ${held.length - 5} others.`);
    expect(held.find(([path]) => path.endsWith('MAA_mod/module.c'))?.[1]).toContain('protect_exec_MAA');
    expect(said).toMatch(/That code is lost unless you restore the files from git: the last generation's copy of it \(src-gen\/\.contract-regions\.json\) is deleted with the folder\. There is no other undo\.$/);
    expect(said).not.toContain('restored');
  });

  it('a folder of notes and an empty folder: how many files, nothing about generated code; Enter deletes', async () => {
    const { page } = s;
    expect(await askDelete(page, 'notes')).toBe('The folder and everything in it will be deleted from disk: 3 files.');
    await page.keyboard.press('Escape');
    await page.locator('.dialog').waitFor({ state: 'detached', timeout: 5000 });
    expect(await askDelete(page, 'empty')).toBe('The folder and everything in it will be deleted from disk: it holds no file.');
    await page.keyboard.press('Enter');
    await expect.poll(() => existsSync(join(s.workspace, 'empty')), { timeout: 10_000 }).toBe(false);
    // the route: a file is no folder, a path leaving the workspace is refused
    const ask = (path: string) => fetch(`${s.server.url}/api/folder-contents?path=${encodeURIComponent(path)}`, { headers: { 'x-contract-token': s.server.token } });
    expect((await ask('supervisor.contract')).status).toBe(400);
    expect((await ask('../../etc')).status).toBeGreaterThanOrEqual(400);
    expect(await (await ask('notes')).json()).toEqual({ files: 3, cut: false, userCode: [] });
    // and, like every /api route, answers no one without the session
    expect((await fetch(`${s.server.url}/api/folder-contents?path=notes`)).status).toBe(401);
  });
});
