/**
 * End-to-end: a module's stdin from a file of the project, given in the IDE's run settings (the ⚙
 * beside Build & Run, its *Stdin* rows: a module and a file of the project each), sent as the run request's `stdin`
 * (docs/ide.md, Build & Run). The old tutorial's MAA read its commands with scanf: with no way to
 * give it a file in the IDE, its stdin was /dev/null. Here the tutorial's MSC reads a line with
 * scanf in its init and prints it; a real Build & Run in the bwrap sandbox. The dialog driven with
 * the keyboard only, the inputs found by their names. The file's path holds a comma, spaces and
 * unicode (the old field, `MODULE=path` entries with commas between, could not take it). A bad
 * entry is said before anything runs; the build service's refusal of a file the project does not
 * have is shown as it says it.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { chmodSync, cpSync, mkdirSync, mkdtempSync, readFileSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { spawnSync } from 'node:child_process';
import { startSession, openIde, shot, TUTORIAL, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const canBuild =
  (await import('@contract-studio/build-service').then((m) => typeof (m as Record<string, unknown>).createBuildServer === 'function').catch(() => false)) &&
  spawnSync('bwrap', ['--version']).status === 0;

const MSC_C = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
const SETTINGS = 'contract-studio:run-settings';
/** The file MSC reads: a comma, spaces and unicode in its path. */
const COMMANDS = 'inputs/hello, world é 1.txt';

let s: Session;
let base: string;

describe.skipIf(!canBuild)("a module's stdin from a file of the project, from the run settings", () => {
  beforeAll(async () => {
    base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-stdin-')));
    chmodSync(base, 0o755);
    const project = join(base, 'tutorial');
    cpSync(TUTORIAL, project, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
    // MSC's init reads one line of its stdin with scanf and says what it read
    const c = readFileSync(join(project, MSC_C), 'utf8');
    const init = '    printf("initialization of MSC\\n");\n';
    expect(c).toContain(init);
    writeFileSync(join(project, MSC_C), c.replace(init, `${init}    { char line[80]; if (scanf("%79[^\\n]", line) == 1) printf("MSC read: %s\\n", line); else printf("MSC read nothing\\n"); }\n`));
    mkdirSync(join(project, 'inputs'));
    writeFileSync(join(project, COMMANDS), 'hello from stdin\n');
    s = await startSession({ example: project, port: 7840 });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
    if (base) rmSync(base, { recursive: true, force: true });
  });

  /** The Build & Run log's lines as `SOURCE: line`. */
  const lines = () => s.page.evaluate(() => {
    const store = window.__ide.build.store;
    const out: string[] = [];
    for (let i = 0; i < store.visibleCount; i++) out.push(`${store.visibleAt(i)!.source}: ${store.visibleAt(i)!.line}`);
    return out;
  });
  const jobStatus = () => s.page.locator('#status-job').getAttribute('data-status');

  /**
   * Opens the run settings from the ⚙ with the keyboard, sets the duration, Tabs to the first stdin
   * row's module input, types `module`, Tab, `file`, Enter; `refused`: the dialog stays open, saying it,
   * the focus on the input `refusedAt` names.
   */
  async function setWithKeyboard(module: string, file: string, refused?: { message: string; at: 'module' | 'file' }): Promise<void> {
    const { page } = s;
    await page.locator('#btn-run-settings').focus();
    await page.keyboard.press('Enter');
    const moduleInput = page.getByLabel('Stdin module 1', { exact: true });
    const fileInput = page.getByLabel('Stdin file 1', { exact: true });
    await moduleInput.waitFor({ timeout: 5000 });
    const focused = (l: typeof moduleInput) => l.evaluate((el) => el === document.activeElement);
    // the duration first (the dialog's focus), then Tab along the fields to the first stdin row
    await page.keyboard.press('Control+A');
    await page.keyboard.type('2');
    for (let i = 0; i < 10 && !(await focused(moduleInput)); i++) await page.keyboard.press('Tab');
    expect(await focused(moduleInput)).toBe(true);
    await page.keyboard.press('Control+A');
    await page.keyboard.type(module);
    await page.keyboard.press('Tab');
    expect(await focused(fileInput)).toBe(true);
    await page.keyboard.press('Control+A');
    await page.keyboard.type(file);
    await page.keyboard.press('Enter');
    if (refused === undefined) {
      await expect.poll(() => page.locator('.dialog-overlay').count()).toBe(0);
      return;
    }
    // said in the dialog, which stays open with what was typed, the focus on the input to mend
    await page.locator('.dialog-problem[role="alert"]', { hasText: refused.message }).waitFor({ timeout: 5000 });
    expect(await page.locator('.dialog-overlay').count()).toBe(1);
    expect([await moduleInput.inputValue(), await fileInput.inputValue()]).toEqual([module, file]);
    const at = refused.at === 'module' ? moduleInput : fileInput;
    expect(await at.evaluate((el) => el === document.activeElement && el.hasAttribute('aria-invalid'))).toBe(true);
    await page.keyboard.press('Escape');
    await expect.poll(() => page.locator('.dialog-overlay').count()).toBe(0);
  }

  it('MSC reads a file whose path holds a comma, spaces and unicode: the row kept for this project, sent as the run request\'s stdin, the line scanf read printed by the module', async () => {
    const { page } = s;
    // a bad entry is said at once, nothing kept
    await setWithKeyboard('MSC', '../commands.txt', { message: 'stdin row 1: path "../commands.txt" has an empty, "." or ".." component (a path inside the project, relative to it)', at: 'file' });
    expect(await page.evaluate((k) => localStorage.getItem(k), SETTINGS)).toBeNull();
    await setWithKeyboard('M-C', 'x.txt', { message: 'stdin row 1: "M-C" is no module name', at: 'module' });

    await setWithKeyboard(' MSC ', COMMANDS);
    await page.locator('.toast.info', { hasText: `Runs last 2 s, MSC reads ${COMMANDS}` }).waitFor({ timeout: 5000 });
    const saved = await page.evaluate((k) => JSON.parse(localStorage.getItem(k)!), SETTINGS);
    expect(saved).toEqual({ duration: 2, projects: { [`${s.workspace}/`]: { stdin: { MSC: COMMANDS } } } });
    // shown again as saved, one row
    await page.locator('#btn-run-settings').click();
    expect(await page.getByLabel('Stdin module 1', { exact: true }).inputValue()).toBe('MSC');
    expect(await page.getByLabel('Stdin file 1', { exact: true }).inputValue()).toBe(COMMANDS);
    expect(await page.getByLabel('Stdin module 2', { exact: true }).count()).toBe(0);
    await page.keyboard.press('Escape');

    const submitted = page.waitForRequest((r) => r.method() === 'POST' && new URL(r.url()).pathname === '/api/jobs');
    await page.locator('#btn-run').click();
    expect((await submitted).postDataJSON()).toMatchObject({ action: 'run', duration: 2, stdin: { MSC: COMMANDS } });
    await expect.poll(jobStatus, { timeout: 180_000, interval: 1000 }).toMatch(/^(succeeded|failed)$/);
    await shot(page, 'run-stdin');
    const log = await lines();
    expect(log, log.slice(-30).join('\n')).toContain('MSC: MSC read: hello from stdin');
    // the launcher's news: MSC given the file (the others keep /dev/null)
    expect(log.filter((l) => l.startsWith('launcher: module ') && l.includes(' reads its stdin from '))).toEqual([expect.stringMatching(/^launcher: module MSC reads its stdin from \S+$/)]);
    expect(await jobStatus()).toBe('succeeded');
  }, 240_000);

  it("a file the project does not have: the build service's refusal shown as it says it, nothing run", async () => {
    const { page } = s;
    await page.evaluate(([k, where]) => localStorage.setItem(k!, JSON.stringify({ duration: 2, projects: { [where!]: { stdin: { MSC: 'nothing.txt' } } } })), [SETTINGS, `${s.workspace}/`]);
    await page.locator('#btn-run').click();
    await expect.poll(jobStatus, { timeout: 180_000, interval: 1000 }).toBe('failed');
    const log = await lines();
    expect(log.some((l) => l.includes('stdin of MSC: nothing.txt is not a regular file of the project (not there, a folder, or reached through a symbolic link); nothing was run')), log.slice(-20).join('\n')).toBe(true);
    expect(log.some((l) => l.startsWith('MSC: '))).toBe(false);
  }, 240_000);

  it('an entry an older page kept (`MODULE=path` text) that is no MODULE=path is said before anything is submitted', async () => {
    const { page } = s;
    await page.evaluate(([k, where]) => localStorage.setItem(k!, JSON.stringify({ duration: 2, stdin: 'MSC', stdinFor: where })), [SETTINGS, `${s.workspace}/`]);
    let posted = 0;
    const count = (r: { method(): string; url(): string }) => void (r.method() === 'POST' && new URL(r.url()).pathname === '/api/jobs' && posted++);
    page.on('request', count);
    await page.locator('#btn-run').click();
    await expect.poll(async () => (await lines()).some((l) => l.includes('could not start: stdin: bad entry "MSC": expected MODULE=FILE')), { timeout: 10_000 }).toBe(true);
    page.off('request', count);
    expect(posted).toBe(0);
  });
});
