/**
 * End-to-end: the real IDE server on a temp copy of examples/tutorial, driven in headless
 * Chromium (playwright-core + /usr/bin/chromium). One browser session, scenarios in order.
 * Screenshots of the main states go to test-output/.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { readFileSync, writeFileSync, existsSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { startSession, openIde, shot, placeCursor, activeValue, activeTab, openFile, waitSaved, type Session } from './harness.js';

let s: Session;
const canGenerate = await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).generateArchitecture === 'function').catch(() => false);
const canBuild = await import('@contract-studio/build-service').then((m) => typeof (m as Record<string, unknown>).createBuildServer === 'function').catch(() => false);


const disk = (p: string) => readFileSync(join(s.workspace, p), 'utf8');

describe('IDE in headless Chromium', () => {
  beforeAll(async () => {
    s = await startSession();
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('shows the outline of supervisor.contract, click reveals the symbol', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    const outline = page.locator('.outline-row');
    await expect.poll(() => outline.count(), { timeout: 10_000 }).toBeGreaterThan(5);
    const names = await outline.locator('.sym-name').allTextContents();
    expect(names).toContain('SUP');
    expect(names).toContain('action');
    expect(names).toContain('FIRST');
    await page.locator('.outline-row[data-name="RECEPTION"]').click();
    const line = await page.evaluate(() => (window as any).__ide.editors.editor.getPosition().lineNumber);
    expect((await activeValue(page)).split('\n')[line - 1]).toContain('RECEPTION');
    await shot(page, '01-outline-supervisor');
  });

  it('shows a typed error in the problems panel within 1 s, and removes it when fixed', async () => {
    const { page } = s;
    await openFile(page, 'smodule3.contract');
    await page.locator('.panel-tab[data-panel=problems]').click();
    await placeCursor(page, 'C=1ms', 3);
    await page.keyboard.type('x');
    const t0 = Date.now();
    const row = page.locator('.problem-row[data-path="smodule3.contract"]');
    await row.first().waitFor({ timeout: 1000 });
    const latency = Date.now() - t0;
    expect(latency).toBeLessThan(1000);
    expect(Number(await page.locator('#status-problems').getAttribute('data-errors'))).toBeGreaterThan(0);
    await shot(page, '02-problem-typed');
    await page.keyboard.press('Backspace');
    await expect.poll(() => row.count(), { timeout: 2000 }).toBe(0);
    await waitSaved(page);
    expect(disk('smodule3.contract')).toContain('C=1ms;');
  });

  it('goes to a definition in another file (opens its tab)', async () => {
    const { page } = s;
    await openFile(page, 'sschema1.contract');
    await placeCursor(page, 'MSC (consigne', 1);
    await page.keyboard.press('F12');
    await expect.poll(() => activeTab(page), { timeout: 5000 }).toBe('smodule3.contract');
    const pos = await page.evaluate(() => (window as any).__ide.editors.editor.getPosition());
    expect((await activeValue(page)).split('\n')[pos.lineNumber - 1]).toContain('MSC');
  });

  it('reflects a change made on disk by another program', async () => {
    const { page } = s;
    await openFile(page, 'amodule2.contract');
    const text = disk('amodule2.contract').replace('asynchronous module MAB', '// edited outside\nasynchronous module MAB');
    writeFileSync(join(s.workspace, 'amodule2.contract'), text);
    await expect.poll(() => activeValue(page), { timeout: 5000 }).toContain('// edited outside');
  });

  it('refuses file API paths outside the workspace with clear 4xx errors', async () => {
    const { page } = s;
    const results = await page.evaluate(async () => {
      const get = async (p: string) => {
        const r = await fetch(`/api/file?path=${encodeURIComponent(p)}`);
        return [r.status, (await r.json()).error as string] as const;
      };
      return [await get('../../etc/passwd'), await get('/etc/passwd'), await get('nothing-here.contract')];
    });
    expect(results[0][0]).toBe(403);
    expect(results[0][1]).toMatch(/\.\./);
    expect(results[1][0]).toBe(403);
    expect(results[1][1]).toMatch(/absolute/);
    expect(results[2][0]).toBe(404);
  });

  it.skipIf(!canGenerate)('Generate All shows the tree; module.c opens as C with only protected regions editable; saving keeps them', async () => {
    const { page } = s;
    await page.locator('#btn-generate').click();
    await page.locator('.gen-summary').waitFor({ timeout: 30_000 });
    expect(await page.locator('.gen-summary .pill').first().textContent()).toContain('generated');
    const path = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
    await page.locator(`.gen-file[data-path="${path}"]`).click();
    await expect.poll(() => activeTab(page)).toBe(path);
    expect(await page.evaluate(() => (window as any).__ide.editors.editor.getModel().getLanguageId())).toBe('c');
    expect(await page.locator('.gen-readonly').count()).toBeGreaterThan(0);
    await shot(page, '03-generated-module-c');

    const before = await activeValue(page);
    // outside any region: refused
    await placeCursor(page, 'MODULE_NAME');
    await page.keyboard.type('zzz');
    await page.waitForTimeout(200);
    const after = await activeValue(page);
    const at = [...after].findIndex((c, i) => c !== before[i]);
    expect(at < 0 ? '' : after.slice(Math.max(0, at - 40), at + 40)).toBe('');
    // inside the exec region: accepted and saved
    const marker = /\/\*PROTECTED REGION ID\((protect_exec_MSC)\) ENABLED START\*\//.exec(before);
    expect(marker).not.toBeNull();
    await placeCursor(page, marker![0], marker![0].length);
    await page.keyboard.press('Enter');
    await page.keyboard.type('/* user code kept */');
    await page.keyboard.press('Control+s');
    await waitSaved(page);
    const saved = disk(path);
    expect(saved).toContain('/* user code kept */');
    expect(saved.replace(/\n[ \t]*\/\* user code kept \*\//, '')).toBe(before);
    // regeneration keeps it
    await page.locator('#btn-generate').click();
    await page.locator('.gen-summary').waitFor();
    await page.waitForTimeout(300);
    expect(disk(path)).toContain('/* user code kept */');
  });

  it.skipIf(!canGenerate)('renames a module across files and carries its generated files and regions over', async () => {
    const { page } = s;
    const oldFile = 'src-gen/generated/architecture/modules/MSA_mod/module.c';
    const userCode = disk(oldFile).replace(/(PROTECTED REGION ID\(protect_init_MSA\) ENABLED START\*\/)/, '$1\n/* MSA init by hand */');
    writeFileSync(join(s.workspace, oldFile), userCode);
    await openFile(page, 'smodule1.contract');
    await placeCursor(page, 'module MSA', 'module '.length);
    await page.keyboard.press('F2');
    await page.waitForFunction(() => document.activeElement?.classList.contains('rename-input'));
    await page.keyboard.press('Control+a');
    await page.keyboard.type('MSX');
    await page.keyboard.press('Enter');
    await expect.poll(() => disk('sschema1.contract'), { timeout: 5000 }).toContain('MSX');
    expect(disk('smodule1.contract')).toContain('module MSX');
    expect(disk('sched.contract')).toContain('MSX;');
    expect(disk('sschema1.contract')).not.toMatch(/\bMSA\b/);
    const newFile = 'src-gen/generated/architecture/modules/MSX_mod/module.c';
    await expect.poll(() => existsSync(join(s.workspace, newFile)), { timeout: 10_000 }).toBe(true);
    await expect.poll(() => disk(newFile), { timeout: 10_000 }).toContain('/* MSA init by hand */');
    expect(disk(newFile)).toContain('protect_init_MSX');
    expect(existsSync(join(s.workspace, oldFile))).toBe(false);
    const orphans = join(s.workspace, 'src-gen/orphans');
    expect(existsSync(orphans) ? readdirSync(orphans, { recursive: true }).filter((f) => String(f).includes('MSA')) : []).toEqual([]);
    await shot(page, '04-renamed-module');
  });

  it('draws the architecture of a schema with elkjs', async () => {
    const { page } = s;
    await page.locator('#btn-arch').click();
    await page.locator('.arch-svg').waitFor({ timeout: 15_000 });
    await page.locator('.arch-select').selectOption('schemaCommande1');
    await expect.poll(() => page.locator('.arch-svg').getAttribute('data-schema')).toBe('schemaCommande1');
    expect(await page.locator('.arch-node').count()).toBe(3);
    expect(await page.locator('.edge.data').count()).toBeGreaterThanOrEqual(2);
    expect(await page.locator('.edge.precedence').count()).toBe(2);
    await shot(page, '05-architecture');
  });

  it.skipIf(!canBuild || !canGenerate)('Build & Run streams MSC lines into the log panel; Stop cancels', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await page.locator('#btn-run').click();
    await page.locator('.log-row[data-source="MSC"]').first().waitFor({ timeout: 90_000 });
    await shot(page, '06-build-and-run');
    await page.locator('#btn-stop').click();
    await expect.poll(() => page.locator('#status-job').getAttribute('data-status'), { timeout: 10_000 }).toMatch(/cancelled|failed|succeeded/);
    await expect.poll(() => page.locator('#btn-run').isEnabled()).toBe(true);
  });

  it('keeps an edit made just before a reload (localStorage backup, then saved)', async () => {
    const { page } = s;
    await openFile(page, 'datatype.contract');
    await placeCursor(page, 'datatype TypeF');
    await page.keyboard.type('// typed right before reload\n');
    await page.reload();
    await page.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    await openFile(page, 'datatype.contract');
    expect(await activeValue(page)).toContain('// typed right before reload');
    await waitSaved(page);
    await expect.poll(() => disk('datatype.contract'), { timeout: 5000 }).toContain('// typed right before reload');
  });

  it('creates, renames and deletes files and folders from the explorer', async () => {
    const { page } = s;
    await page.locator('#btn-new-folder').click();
    await page.locator('.dialog-input').fill('robot2');
    await page.keyboard.press('Enter');
    await expect.poll(() => existsSync(join(s.workspace, 'robot2'))).toBe(true);
    await page.locator('.tree-row[data-path="robot2"]').click();
    await page.locator('#btn-new-file').click();
    await page.locator('.dialog-input').fill('extra.contract');
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page)).toBe('robot2/extra.contract');
    expect(existsSync(join(s.workspace, 'robot2/extra.contract'))).toBe(true);

    await page.locator('.tree-row[data-path="robot2/extra.contract"]').hover();
    await page.locator('.tree-row[data-path="robot2/extra.contract"] [data-action=rename]').click();
    await page.locator('.dialog-input').fill('renamed.contract');
    await page.keyboard.press('Enter');
    await expect.poll(() => existsSync(join(s.workspace, 'robot2/renamed.contract'))).toBe(true);
    expect(existsSync(join(s.workspace, 'robot2/extra.contract'))).toBe(false);

    await page.locator('.tree-row[data-path="robot2/renamed.contract"]').hover();
    await page.locator('.tree-row[data-path="robot2/renamed.contract"] [data-action=delete]').click();
    await page.locator('.dialog .btn.danger').click();
    await expect.poll(() => existsSync(join(s.workspace, 'robot2/renamed.contract'))).toBe(false);
    await expect.poll(() => page.locator('.tree-row[data-path="robot2/renamed.contract"]').count()).toBe(0);
  });
});

describe('New Project in an empty workspace', () => {
  let e: Session;
  beforeAll(async () => {
    e = await startSession({ empty: true, buildService: false });
    await openIde(e);
  }, 60_000);
  afterAll(async () => {
    await e?.close();
  });

  it('creates the six report templates, valid Cactal with no problem', async () => {
    const { page } = e;
    await page.locator('#btn-new-project').click();
    await page.locator('.dialog-input').waitFor();
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page), { timeout: 5000 }).toBe('supervisor.contract');
    for (const f of ['datatype', 'module1', 'module2', 'sched', 'schema', 'supervisor']) expect(existsSync(join(e.workspace, `${f}.contract`))).toBe(true);
    await page.waitForFunction(() => (window as any).__ide.lsp.workspaceBuilt().then(() => true));
    await page.waitForTimeout(500);
    expect(await page.locator('.problem-row').allTextContents()).toEqual([]);
    expect(await page.locator('.outline-row .sym-name').allTextContents()).toContain('MIS');
    await shot(page, '07-new-project');
  });
});
