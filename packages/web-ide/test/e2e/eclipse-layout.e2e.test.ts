/**
 * End-to-end: a project in the Eclipse layout (its `.contract` files in `src/`, its generated tree
 * with the user's code in `src-gen/` at the project's root) opened with `contract serve P`. The IDE
 * follows the rule the CLI does (docs/codegen.md "Where a project is"): Generate All updates
 * `P/src-gen` (it made a second tree `P/src/src-gen` of generated defaults), Build & Run runs the
 * user's code (it ran that second tree: not one line of theirs), and a second tree is said.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, realpathSync, renameSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { spawnSync } from 'node:child_process';
import { startSession, openIde, shot, openFile, TUTORIAL, type Session } from './harness.js';

const canGenerate = await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).generateArchitecture === 'function').catch(() => false);
const canBuild =
  (await import('@contract-studio/build-service').then((m) => typeof (m as Record<string, unknown>).createBuildServer === 'function').catch(() => false)) &&
  spawnSync('bwrap', ['--version']).status === 0;

let s: Session;
let source: string;

/** The tutorial laid out as an Eclipse project: `P/src/*.contract`, `P/src-gen/` (its code) at the root. */
function eclipseProject(): string {
  const base = realpathSync(mkdtempSync(join(tmpdir(), 'eclipse-layout-')));
  const p = join(base, 'oldproj');
  cpSync(TUTORIAL, p, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
  mkdirSync(join(p, 'src'));
  for (const f of readdirSync(p)) if (f.endsWith('.contract')) renameSync(join(p, f), join(p, 'src', f));
  return p;
}

describe.skipIf(!canGenerate)('the Eclipse layout in the IDE: one project, its src-gen/ at the root', () => {
  beforeAll(async () => {
    source = eclipseProject();
    s = await startSession({ example: source, buildService: canBuild });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
    rmSync(join(source, '..'), { recursive: true, force: true });
  });

  it('Generate All from src/supervisor.contract updates the root src-gen/, and makes no src/src-gen', async () => {
    const { page } = s;
    await openFile(page, 'src/supervisor.contract');
    await page.locator('#btn-generate').click();
    await page.locator('.gen-summary').waitFor({ timeout: 60_000 });
    await shot(page, 'eclipse-layout-generate');
    expect(existsSync(join(s.workspace, 'src', 'src-gen'))).toBe(false);
    expect(await page.locator('.gen-summary .pill').first().textContent()).toBe('✓ generated');
    // the tree shown is the root's, the tutorial's own (nothing created: its code kept)
    expect(await page.locator('.gen-summary .pill', { hasText: 'created' }).textContent()).toBe('0 created');
    expect(await page.locator('.gen-file[data-path="src-gen/generated/architecture/modules/MSC_mod/module.c"]').count()).toBe(1);
    expect(await page.locator('.layout-warnings').count()).toBe(0);
  }, 90_000);

  it('Generate All asked for src/ (a folder inside the project) is refused, naming the project', async () => {
    const res = await fetch(`${s.server.url}/api/generate`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': s.server.token }, body: '{"project":"src"}' });
    expect(res.status).toBe(409);
    expect(((await res.json()) as { error: string }).error).toContain('src is not a project: it is inside project the workspace root, which holds the generated tree src-gen/');
    expect(existsSync(join(s.workspace, 'src', 'src-gen'))).toBe(false);
  });

  it.skipIf(!canBuild)('Build & Run runs the user\'s code of the root src-gen/', async () => {
    const { page } = s;
    await openFile(page, 'src/supervisor.contract');
    await page.locator('#btn-run').click();
    // a line of MSC's protected region (the tutorial's code), not of the generated defaults
    await page.locator('.log-row[data-source="MSC"]', { hasText: 'MSC : state 0 => getting coordinates' }).first().waitFor({ timeout: 140_000 }).catch(async (e) => {
      await shot(page, 'eclipse-layout-run-FAILED');
      throw e;
    });
    await expect.poll(() => page.locator('#status-job').getAttribute('data-status'), { timeout: 60_000 }).toBe('succeeded');
    expect(existsSync(join(s.workspace, 'src', 'src-gen'))).toBe(false);
  }, 240_000);

  it('a second tree (src/src-gen, what the IDE used to make) is said in the Generate panel and a toast, and not used', async () => {
    const { page } = s;
    cpSync(join(s.workspace, 'src-gen'), join(s.workspace, 'src', 'src-gen'), { recursive: true });
    await page.reload();
    await page.waitForSelector('body[data-ready=true]', { timeout: 30_000 });
    await openFile(page, 'src/supervisor.contract');
    await page.locator('#btn-generate').click();
    const said = page.locator('.layout-warnings');
    await said.waitFor({ timeout: 60_000 });
    await shot(page, 'eclipse-layout-two-trees');
    expect(await said.textContent()).toContain('src/src-gen/ is a second generated tree of this project, not used: the project is the workspace root and its tree src-gen/');
    await page.locator('.toast.warning', { hasText: 'src/src-gen/ is a second generated tree' }).first().waitFor({ timeout: 10_000 });
    expect(await page.locator('.gen-file[data-path^="src/src-gen/"]').count()).toBe(0);
  }, 90_000);
});
