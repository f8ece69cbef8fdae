/**
 * A trace file of the workspace (`contract run --trace`) holding the launcher's end line of a module
 * killed from outside (`{"kind":"launcher_line",...}`): its replay in the Monitor shows that module
 * gone at the line's time (alert line, strip mark), as the replay of the logs folder does; a line
 * forged into the file for another module, whose pid is not that module's own, is not believed.
 * Before, the trace file's replay read no launcher line: the module was never shown gone. Real IDE
 * server, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { ideSession, shot, showMonitor } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

/** One of the ports this test may use (E2E_TRACE_FILE_GONE_PORT to choose another). */
const PORT = Number(process.env.E2E_TRACE_FILE_GONE_PORT ?? 8011);
const W = '2026-12-07T12:00:00.000000Z';
const rec = (mono: string, module: string, kind: string, detail: string) => ({ kind, monoNs: mono, wallTime: W, module, peer: '', port: null, size: 0, detail, ...(kind === 'user' ? { fields: { event: detail } } : {}) });

describe('a trace file with the launcher\'s end lines, replayed', () => {
  const s = ideSession({ port: PORT, buildService: false });

  it('shows the module gone at the line\'s time; a line with another pid is not believed', async () => {
    const { page } = s;
    const lines = [
      rec('1000000000', 'ORD', 'module_started', 'pid=40 priority=90'),
      rec('1000100000', 'SRT', 'module_started', 'pid=41 priority=40'),
      rec('1200000000', 'SRT', 'user', 'sorting'),
      { kind: 'launcher_line', monoNs: '1300000000', line: 'module SRT (pid 41) died by signal 9 (Killed)' },
      { kind: 'launcher_line', monoNs: '1300000000', line: 'module ORD (pid 99) died by signal 9 (Killed)' },
      rec('1500000000', 'ORD', 'user', 'tick'),
      rec('2500000000', 'ORD', 'user', 'tick'),
    ];
    writeFileSync(join(s.workspace, 'killed.jsonl'), lines.map((l) => JSON.stringify(l)).join('\n') + '\n');
    await showMonitor(page);
    await expect.poll(() => page.locator('.monitor-sources option[value="file:killed.jsonl"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('file:killed.jsonl');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 10_000 }).toBe('Trace file killed.jsonl · 5 record(s)');
    const state = () => page.evaluate(() => {
      const run = window.__ide.monitor.current;
      const end = run?.stateAt(run.end)?.modules;
      return { srt: end?.get('SRT')?.gone, ord: end?.get('ORD')?.gone ?? null, marks: (run?.marks ?? []).filter((k: { kind: string }) => k.kind === 'crash').map((k: { t: number; where: string }) => ({ t: k.t, where: k.where })) };
    });
    await expect.poll(async () => (await state()).srt, { timeout: 10_000 }).toBe('gone: contract-launch: module SRT (pid 41) died by signal 9 (Killed)');
    const { ord, marks } = await state();
    expect(ord).toBeNull();
    expect(marks).toEqual([{ t: 300_000_000, where: 'SRT' }]);
    await expect.poll(() => page.locator('.monitor-crashed').textContent(), { timeout: 5000 }).toBe('⚠ SRT gone at +0.300000 s: contract-launch: module SRT (pid 41) died by signal 9 (Killed)');
    await shot(page, 'monitor-trace-file-launcher-gone');
  }, 120_000);
});
