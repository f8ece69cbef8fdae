/**
 * End-to-end, in headless Chromium on the real IDE server and its build service (bwrap): a Build &
 * Run whose MAA crashes in an always-inline function of its own, called from its exec region. The
 * replay of the job's CSV logs (GET /api/jobs/:id/artifacts) names the crash sites the service mapped
 * in the sandbox right after the run — the executable that crashed, so no build-id to check and no
 * addr2line run again — in `contract trace`'s words, the inlined place joined to its frame; a
 * replay of a logs folder tells its crash files unmapped (log-api.ts: the IDE runs no addr2line).
 * The crash's row in the Problems panel is labelled `run` (no compiler said it) and says what the signal means.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { spawnSync } from 'node:child_process';
import { chmodSync, cpSync, mkdtempSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { startSession, openIde, shot, TUTORIAL, type Session } from './harness.js';

const canBuild =
  (await import('@contract-studio/build-service').then((m) => typeof (m as Record<string, unknown>).createBuildServer === 'function').catch(() => false)) &&
  spawnSync('bwrap', ['--version']).status === 0;

const MAA_C = 'src-gen/generated/architecture/modules/MAA_mod/module.c';
const DECL = '/*PROTECTED REGION ID(protect_internal_functions_decl_MAA) ENABLED START*/';
const EXEC = '/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/';
const IDE_PORT = 7822;

let s: Session;
let base: string;

describe.skipIf(!canBuild)('Monitor: the replay of a job whose module crashed', () => {
  beforeAll(async () => {
    base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-crash-sites-')));
    chmodSync(base, 0o755);
    const project = join(base, 'tutorial');
    cpSync(TUTORIAL, project, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
    const c = readFileSync(join(project, MAA_C), 'utf8');
    writeFileSync(join(project, MAA_C), c
      .replace(DECL, `${DECL}\nstatic double *volatile bad_target;\nstatic inline __attribute__((always_inline)) void store_bad(double v)\n{\n    *bad_target = v; /* the crash */\n}`)
      .replace(EXEC, `${EXEC}\n    { static int calls = 0; if (++calls == 3) store_bad(1.0); /* the call */ }`));
    s = await startSession({ example: project, port: IDE_PORT });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
    rmSync(base, { recursive: true, force: true });
  });

  it("names the crash sites the build service mapped, in contract trace's words, the inlined place joined to its frame", async () => {
    const { page } = s;
    const lines = readFileSync(join(s.workspace, MAA_C), 'utf8').split('\n');
    const crashLine = lines.findIndex((l) => l.includes('/* the crash */')) + 1;
    const callLine = lines.findIndex((l) => l.includes('/* the call */')) + 1;
    await page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 3 })));
    await page.locator('#btn-run').click();
    await expect.poll(() => page.locator('#status-job').getAttribute('data-status'), { timeout: 150_000, interval: 1000 }).toBe('failed');
    // the crash's row in Problems is the run's, not gcc's, and says what SIGSEGV means
    const crashRow = page.locator(`.problem-row[data-path$="${MAA_C}"]`, { hasText: 'crashed here' });
    await expect.poll(() => crashRow.locator('.src').allTextContents(), { timeout: 20_000 }).toEqual(['run']);
    expect(await crashRow.locator('.msg').textContent()).toMatch(/^MAA crashed here: signal 11 \(SIGSEGV\) at address 0x0, in \w+: a bad pointer: NULL, freed, or past the end of an array/);
    await shot(page, 'problems-crash-row-run');
    if (!(await page.locator('.side-pane .monitor-view').isVisible())) await page.locator('#btn-monitor').click();
    const option = page.locator('.monitor-sources option[value^="job:"]');
    await expect.poll(() => option.count(), { timeout: 20_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption((await option.getAttribute('value'))!);
    const label = () => page.locator('.monitor-source').textContent();
    await expect.poll(label, { timeout: 20_000 }).toContain(' — crash sites (mapped by the build service): MAA crashed: signal 11 (SIGSEGV) at address 0x0 (a bad pointer: NULL, freed, or past the end of an array), executable build-id ');
    const said = (await label())!;
    expect(said).toContain(`; #0 store_bad at ${MAA_C}:${crashLine} (inlined into _exec_module_state at ${MAA_C}:${callLine}); `);
    expect(said).toMatch(/; #\d+ main at runtime\/src\/module_main\.c:\d+;/);
    expect(said).not.toContain('the executable+0x');
    await shot(page, 'monitor-job-crash-sites');
  }, 240_000);
});
