/**
 * The Timeline's trace-file source (a `contract run --trace` file of the workspace) reads the file's
 * `launcher_line` items as its logs-folder source reads the folder's contract-launch.log: a module
 * the launcher says was killed (its pid its own) is marked in its lane at the line's time, and the
 * header says it (`gone: MAB at … ms (contract-launch: module MAB (pid 65) died by signal 9
 * (Killed))`). The file: a real bwrap run of the tutorial with MAB SIGKILLed
 * (src/views/fixtures/killed-trace-run). Before, the Timeline read no launcher line from either
 * source. Real IDE server, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { copyFileSync, mkdirSync, readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { ideSession, shot } from './harness.js';

/** One of the ports this test may use (E2E_TIMELINE_GONE_PORT to choose another). */
const PORT = Number(process.env.E2E_TIMELINE_GONE_PORT ?? 8113);
const FIXTURE = join(dirname(fileURLToPath(import.meta.url)), '..', '..', 'src', 'views', 'fixtures', 'killed-trace-run');
const HEADER_GONE = /· gone: MAB at \d+\.\d{3} ms \(contract-launch: module MAB \(pid 65\) died by signal 9 \(Killed\)\) ·/;

describe("the Timeline: a module killed, told by the launcher's line", () => {
  const s = ideSession({ port: PORT, buildService: false });

  it("marks it in its lane from the trace file's launcher_line, as from the folder's contract-launch.log", async () => {
    const { page } = s;
    copyFileSync(join(FIXTURE, 'run.jsonl'), join(s.workspace, 'killed.jsonl'));
    // the same run's logs folder, where `contract run` writes it
    mkdirSync(join(s.workspace, 'logs'), { recursive: true });
    for (const f of readdirSync(FIXTURE)) if (f.endsWith('.csv') || f === 'contract-launch.log') copyFileSync(join(FIXTURE, f), join(s.workspace, 'logs', f));
    await page.locator('#btn-timeline').click();
    await page.locator('.timeline-view').waitFor();
    const info = () => page.locator('.timeline-view .muted').first().textContent();
    await expect.poll(() => page.locator('.timeline-source option[value="file:killed.jsonl"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.timeline-source').selectOption('file:killed.jsonl');
    await expect.poll(info, { timeout: 10_000 }).toMatch(HEADER_GONE);
    const fromFile = await info();
    const mark = page.locator('.timeline-view .gone-mark[data-module="MAB"]');
    expect(await mark.count()).toBe(1);
    expect(await mark.locator('title').textContent()).toMatch(/^MAB gone at \d+\.\d{3} ms: contract-launch: module MAB \(pid 65\) died by signal 9 \(Killed\)$/);
    // the other modules' end lines (exited with status 0 at the run's end) mark nothing
    expect(await page.locator('.timeline-view .gone-mark').count()).toBe(1);
    await shot(page, 'timeline-trace-file-gone');
    // the folder the file was written from says the same
    await expect.poll(() => page.locator('.timeline-source option[value="local"]').textContent(), { timeout: 10_000 }).toBe('Local logs: logs/');
    await page.locator('.timeline-source').selectOption('local');
    await expect.poll(info, { timeout: 10_000 }).toMatch(HEADER_GONE);
    expect(HEADER_GONE.exec((await info())!)![0]).toBe(HEADER_GONE.exec(fromFile!)![0]);
    expect(await page.locator('.timeline-view .gone-mark[data-module="MAB"]').count()).toBe(1);
  }, 120_000);
});
