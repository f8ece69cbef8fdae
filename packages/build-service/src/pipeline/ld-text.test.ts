/**
 * ld's errors of a failed link, read as the build reads them: real gcc and ld output (a region
 * calling a function nobody defines, a function defined in two units) placed at the user's file,
 * line and protected region, each once (LinkErrorReader); hostile lines never throw and stay bounded.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { findProtectedRegions } from './protected-regions.js';
import { BuildOutputRouter } from './output-router.js';
import { renderDiagnostic } from './gcc-diagnostics.js';
import { LinkErrorReader, parseLinkerLine } from './ld-text.js';

const dir = mkdtempSync(join(tmpdir(), 'ld-text-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

const MODULE = [
  '#include "../common/shared.h"', // 1
  'int _init_module(void) {', // 2
  '  /*PROTECTED REGION ID(protect_init_MAA) ENABLED START*/', // 3
  '  extern int calibrate_arm(int);', // 4
  '  return calibrate_arm(3) + shared();', // 5
  '  /*PROTECTED REGION END*/', // 6
  '}', // 7
  'int main(void) { return _init_module(); }', // 8
  '',
].join('\n');
const SHARED = [
  'int shared(void);', // 1
  '/*PROTECTED REGION ID(protect_additional_impl_T) ENABLED START*/', // 2
  'int shared(void) { return 1; }', // 3
  '/*PROTECTED REGION END*/', // 4
  '',
].join('\n');

/** Compiles each unit with debug information (as the generated Makefile's -g) and links them: ld's output. */
function link(units: Record<string, string>): string {
  mkdirSync(join(dir, 'MAA_mod'), { recursive: true });
  mkdirSync(join(dir, 'common'), { recursive: true });
  writeFileSync(join(dir, 'common', 'shared.h'), SHARED);
  const objects: string[] = [];
  for (const [name, text] of Object.entries(units)) {
    writeFileSync(join(dir, 'MAA_mod', name), text);
    const o = join(dir, 'MAA_mod', `${name}.o`);
    const c = spawnSync('gcc', ['-std=c11', '-g', '-gdwarf-4', '-c', join(dir, 'MAA_mod', name), '-o', o], { encoding: 'utf8' });
    expect(c.status, c.stderr).toBe(0);
    objects.push(o);
  }
  const l = spawnSync('gcc', ['-o', join(dir, 'MAA_mod', 'MAA'), ...objects], { cwd: join(dir, 'MAA_mod'), encoding: 'utf8' });
  expect(l.status).not.toBe(0);
  return l.stderr;
}

function routed(output: string) {
  const router = new BuildOutputRouter({
    startDir: join(dir, 'MAA_mod'), root: dir,
    regions: new Map([['MAA_mod/main.c', findProtectedRegions(MODULE)], ['common/shared.h', findProtectedRegions(SHARED)]]),
  });
  return output.split('\n').filter(Boolean).flatMap((l) => router.route(l, 'stderr').diagnostics);
}

describe('ld\'s errors of a failed link', () => {
  test('an undefined reference: the user\'s file and line, its region, the function it is in; once', () => {
    const output = link({ 'main.c': MODULE });
    expect(output).toContain("undefined reference to `calibrate_arm'");
    const diags = routed(output);
    expect(diags).toHaveLength(1);
    expect(diags[0]).toMatchObject({
      severity: 'error', file: 'MAA_mod/main.c', line: 5, column: null,
      message: "undefined reference to `calibrate_arm' (in function _init_module)",
      protectedRegion: { id: 'protect_init_MAA' },
    });
  });

  test('a multiple definition: the second at its header line and region, the first as a note', () => {
    const output = link({ 'main.c': MODULE.replace('extern int calibrate_arm(int);', '').replace('calibrate_arm(3) + ', ''), 'other.c': '#include "../common/shared.h"\n' });
    const diags = routed(output);
    expect(diags).toHaveLength(1);
    expect(diags[0]).toMatchObject({
      severity: 'error', file: 'common/shared.h', line: 3, message: "multiple definition of `shared'",
      protectedRegion: { id: 'protect_additional_impl_T' },
      children: [{ severity: 'note', file: 'common/shared.h', line: 3, message: 'first defined here' }],
    });
  });

  test('ld\'s lines without a line number: told without a place, never as a file of the tree', () => {
    const ctx = { cwd: '/work/x', root: '/work', regions: new Map() };
    expect(parseLinkerLine("/usr/bin/ld: m.o:module.c:(.text+0x16): undefined reference to `x'", ctx)).toEqual({
      kind: 'diagnostic', diagnostic: { severity: 'error', message: "undefined reference to `x' (in module.c)", file: null, line: null, column: null, protectedRegion: null, children: [] },
    });
    expect(parseLinkerLine('/usr/bin/ld: cannot find -lgripper: No such file or directory', ctx)).toMatchObject({ kind: 'diagnostic', diagnostic: { severity: 'error', file: null, message: 'cannot find -lgripper: No such file or directory' } });
    expect(parseLinkerLine('/usr/bin/x86_64-linux-gnu-ld.bfd: warning: creating DT_TEXTREL', ctx)).toMatchObject({ kind: 'diagnostic', diagnostic: { severity: 'warning', message: 'creating DT_TEXTREL' } });
    expect(parseLinkerLine("/usr/bin/ld: /tmp/cc1.o: in function `main':", ctx)).toEqual({ kind: 'function', name: 'main' });
    // not ld's: gcc's collect2, make, a program's own words
    for (const line of ['collect2: error: ld returned 1 exit status', 'make[1]: *** [Makefile:23: MAA] Error 1', 'hold: ready', 'world: undefined reference']) {
      expect(parseLinkerLine(line, ctx), line).toBeNull();
    }
  });

  test('hostile lines: no throw, bounded messages, linear time', () => {
    const ctx = { cwd: '/work/x', root: '/work', regions: new Map() };
    const huge = 'ld: ' + ':'.repeat(200_000) + ': undefined reference to ' + 'a'.repeat(200_000);
    const t0 = performance.now();
    const d = parseLinkerLine(huge, ctx);
    expect(performance.now() - t0).toBeLessThan(1000);
    if (d?.kind === 'diagnostic') expect(d.diagnostic.message.length).toBeLessThan(SERVICE_BOUNDS.diagnosticTextChars + 100);
    for (const line of ['ld: ', 'ld: :1: undefined reference to ', ': undefined reference to x', 'ld: a:99999999999: undefined reference to `y\'', 'ld: x: multiple definition of `g\'; : first defined here', "ld: : in function `':"]) {
      expect(() => parseLinkerLine(line, ctx), line).not.toThrow();
    }
    // a line number too long to be ld's is no line
    expect(parseLinkerLine("ld: /work/a.c:99999999999: undefined reference to `y'", ctx)).toMatchObject({ kind: 'diagnostic', diagnostic: { line: null, file: null } });
  });
});

/** A function calling `calibrate_arm` twice on one line, another calling it once. */
const CALLS = [
  'extern int calibrate_arm(int);', // 1
  'int f(void) {', // 2
  '  return calibrate_arm(3) + calibrate_arm(4);', // 3
  '}', // 4
  'int g(void) { return calibrate_arm(1); }', // 5
  'int main(void) { return f() + g(); }', // 6
  '',
].join('\n');

describe('LinkErrorReader', () => {
  const ctx = { cwd: join(dir, 'MAA_mod'), root: dir, regions: new Map() };
  /** The errors told of `lines`, each as `line: message`. */
  function told(reader: LinkErrorReader, lines: string[]): string[] {
    return lines.flatMap((l) => {
      const d = reader.read(parseLinkerLine(l, ctx));
      return d && reader.first(renderDiagnostic(d)) ? [`${d.line}: ${d.message}`] : [];
    });
  }

  test('each error in the function of the `in function` line before it; a reference ld repeats for every use, told once', () => {
    const output = link({ 'main.c': CALLS });
    // ld: `in function f`, the reference at line 3 twice, `in function g`, the one at line 5
    expect(output.match(/undefined reference to `calibrate_arm'/g)).toHaveLength(3);
    expect(told(new LinkErrorReader(), output.split('\n').filter(Boolean))).toEqual([
      "3: undefined reference to `calibrate_arm' (in function f)",
      "5: undefined reference to `calibrate_arm' (in function g)",
    ]);
  });

  test('a line that is not ld\'s forgets the function', () => {
    const [fn, ref] = link({ 'main.c': CALLS }).split('\n');
    expect(told(new LinkErrorReader(), [fn!, ref!])).toEqual(["3: undefined reference to `calibrate_arm' (in function f)"]);
    expect(told(new LinkErrorReader(), [fn!, 'make[1]: *** [Makefile:23: MAA] Error 1', ref!])).toEqual(["3: undefined reference to `calibrate_arm'"]);
  });

  test('no more errors remembered than its bound: the ones after it are told every time', () => {
    const reader = new LinkErrorReader(1);
    expect([reader.first('a'), reader.first('a'), reader.first('b'), reader.first('b'), reader.first('a')]).toEqual([true, false, true, true, false]);
    // by default, a job's diagnostics
    const job = new LinkErrorReader();
    for (let i = 0; i < SERVICE_BOUNDS.diagnosticsPerJob; i++) expect(job.first(`e${i}`)).toBe(true);
    expect([job.first('e0'), job.first('more'), job.first('more')]).toEqual([false, true, true]);
  });
});
