/**
 * The assembler's errors read as the build reads them: real gcc output for an `__asm__` statement
 * of a protected region (with -g: at the C line; without: gcc's temporary file, told without a
 * place), each once; lines that are not the assembler's stay null.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { findProtectedRegions } from './protected-regions.js';
import { BuildOutputRouter } from './output-router.js';
import { parseAssemblerLine } from './as-text.js';

const dir = mkdtempSync(join(tmpdir(), 'as-text-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

const MODULE = [
  'void _exec_module(void) {', // 1
  '  /*PROTECTED REGION ID(protect_exec_CTL) ENABLED START*/', // 2
  '  __asm__("gripper_open");', // 3
  '  /*PROTECTED REGION END*/', // 4
  '}', // 5
  '',
].join('\n');

function compile(debug: boolean): string {
  mkdirSync(join(dir, 'CTL_mod'), { recursive: true });
  writeFileSync(join(dir, 'CTL_mod', 'module.c'), MODULE);
  const r = spawnSync('gcc', ['-std=c11', ...(debug ? ['-g'] : []), '-c', 'module.c', '-o', '/dev/null'], { cwd: join(dir, 'CTL_mod'), encoding: 'utf8' });
  expect(r.status).not.toBe(0);
  return r.stderr;
}

function routed(output: string) {
  const router = new BuildOutputRouter({ startDir: join(dir, 'CTL_mod'), root: dir, regions: new Map([['CTL_mod/module.c', findProtectedRegions(MODULE)]]) });
  return output.split('\n').filter(Boolean).flatMap((l) => router.route(l, 'stderr').diagnostics);
}

describe('the assembler\'s errors', () => {
  test('with debug information: the C file and line, the region', () => {
    const diags = routed(compile(true));
    expect(diags).toHaveLength(1);
    expect(diags[0]).toMatchObject({
      severity: 'error', file: 'CTL_mod/module.c', line: 3, column: null, message: "no such instruction: `gripper_open'", protectedRegion: { id: 'protect_exec_CTL' },
    });
  });

  test('without debug information gcc still names the C line; a line of gcc\'s temporary assembly file is told without a place', () => {
    expect(routed(compile(false))[0]).toMatchObject({ file: 'CTL_mod/module.c', line: 3, protectedRegion: { id: 'protect_exec_CTL' } });
    const diags = routed("/tmp/ccQ2.s:25: Error: no such instruction: `gripper_open'");
    expect(diags).toEqual([{ severity: 'error', file: null, line: null, column: null, protectedRegion: null, children: [], message: "no such instruction: `gripper_open' (in the assembly gcc made, line 25)" }]);
  });

  test('not the assembler\'s: null; hostile lines never throw', () => {
    const ctx = { cwd: '/work/x', root: '/work', regions: new Map() };
    for (const line of ['module.c: Assembler messages:', 'make: *** [Makefile:3: x] Error 2', 'x: Error: no line', ': Error: x', 'a:1x: Error: y']) {
      expect(parseAssemblerLine(line, ctx), line).toBeNull();
    }
    expect(parseAssemblerLine('m.c:7: Warning: ignoring', ctx)).toMatchObject({ severity: 'warning', file: 'x/m.c', line: 7 });
    expect(() => parseAssemblerLine(':'.repeat(100_000) + ': Error: ' + 'e'.repeat(100_000), ctx)).not.toThrow();
  });
});
