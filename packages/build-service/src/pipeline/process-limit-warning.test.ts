import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import { prepareWorkspace } from './prepare.js';
import { holdsUnderProcessLimit } from './process-limit-warning.js';

describe("contract check's process limit warning in a job", () => {
  const warning = {
    file: 'sup/power.contract', line: 7, column: 12, severity: 'warning' as const, code: 'architecture-over-process-limit',
    message: "This architecture runs 136 processes (128 modules, 7 supervisors and ORD), 2 threads each: with make and the launcher, 276 processes and threads, more than the build service's default process limit of 256 ...",
    data: { processes: 136, threads: 276, limit: 256, suggested: 320 },
  };
  test('kept under the default limit, dropped under a job limit that fits (276 processes and threads); other problems kept', () => {
    expect(holdsUnderProcessLimit(warning, 256)).toBe(true);
    expect(holdsUnderProcessLimit(warning, 275)).toBe(true);
    expect(holdsUnderProcessLimit(warning, 276)).toBe(false);
    expect(holdsUnderProcessLimit(warning, 512)).toBe(false);
    expect(holdsUnderProcessLimit({ ...warning, code: 'import-unused' }, 512)).toBe(true);
  });
  test('read from its code and data, not its words: another wording is read the same; without its count it is kept', () => {
    const reworded = { ...warning, message: 'Too many processes for the default limit: raise it with --limit processes=320.' };
    expect(holdsUnderProcessLimit(reworded, 275)).toBe(true);
    expect(holdsUnderProcessLimit(reworded, 276)).toBe(false);
    // the data, not the message's first words, says the count
    expect(holdsUnderProcessLimit({ ...warning, data: { ...warning.data, threads: 600 } }, 512)).toBe(true);
    for (const data of [undefined, null, {}, { threads: '276' }, { threads: -1 }]) expect(holdsUnderProcessLimit({ ...warning, data }, 512)).toBe(true);
  });
});

describe("the warning as a job's prepare gets it", () => {
  test("it carries the check's code and data (threads), from which the job keeps or drops it", async () => {
    const root = mkdtempSync(join(tmpdir(), 'process-limit-warning-'));
    try {
      for (const d of ['stage', 'work']) mkdirSync(join(root, d));
      const ws = { root, stageDir: join(root, 'stage'), workDir: join(root, 'work'), owner: { uid: process.getuid!(), gid: process.getgid!() }, reused: false, acceptedOutputs: null, reset: async () => {}, release: async () => {} };
      // 120 modules, 7 supervisors and ORD: 128 processes, 260 with their threads (contract check's case)
      const name = (n: number) => `M${String.fromCharCode(97 + Math.floor(n / 26) % 26)}${String.fromCharCode(97 + (n % 26))}`;
      const files: Record<string, string> = {};
      for (let m = 0; m < 120; m++) files[`m${Math.floor(m / 20)}.contract`] = `${files[`m${Math.floor(m / 20)}.contract`] ?? ''}synchronous module ${name(m)} { scheduling { C=1ms; } }\n`;
      for (let s = 0; s < 7; s++) files[`s${s}.contract`] = `supervisor S${name(s)} { f() { rules { R: [elapsed=1ms] [elapsed=2ms] } } }\n`;
      const out = await prepareWorkspace(ws, { files }, 'cactal', { ...DEFAULT_LIMITS }, () => {});
      const found = out.problems.filter((p) => p.code === 'architecture-over-process-limit');
      expect(found).toEqual([expect.objectContaining({ severity: 'warning', data: expect.objectContaining({ processes: 128, threads: 260, limit: 256, suggested: 320 }) })]);
      expect(holdsUnderProcessLimit(found[0]!, 256)).toBe(true);
      expect(holdsUnderProcessLimit(found[0]!, 260)).toBe(false);
    } finally {
      rmSync(root, { recursive: true, force: true });
    }
  }, 120_000);
});
