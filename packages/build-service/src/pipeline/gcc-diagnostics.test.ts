import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { makeEnteringDirectory, renderDiagnostic } from './gcc-diagnostics.js';
import { looksLikeGccJson, parseGccJsonLine } from './gcc-json.js';
import { parseGccTextLine } from './gcc-text.js';
import { findProtectedRegions, regionAt } from './protected-regions.js';
import { BuildOutputRouter, makeRecipeStatus, routeRunLine } from './output-router.js';
import { buildJobs, DEFAULT_LIMITS } from '../limits.js';

const dir = mkdtempSync(join(tmpdir(), 'gccdiag-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

const SOURCE = [
  '#include <stdio.h>', // 1
  'int compute(int x) {', // 2
  '  /*PROTECTED REGION ID(protect_compute_MAA) ENABLED START*/', // 3
  '  int unused;', // 4
  '  return x + missing;', // 5
  '  /*PROTECTED REGION END*/', // 6
  '}', // 7
  'int other(void) { return undeclared_too; }', // 8
  '',
].join('\n');

function compile(format: 'json' | 'text'): string {
  mkdirSync(join(dir, 'MAA_mod'), { recursive: true });
  writeFileSync(join(dir, 'MAA_mod', 'module.c'), SOURCE);
  const r = spawnSync('gcc', ['-std=c11', '-Wall', '-c', 'module.c', '-o', '/dev/null', ...(format === 'json' ? ['-fdiagnostics-format=json'] : ['-fno-diagnostics-show-caret'])], {
    cwd: join(dir, 'MAA_mod'),
    encoding: 'utf8',
  });
  return r.stderr;
}

const ctx = () => ({
  cwd: join(dir, 'MAA_mod'),
  root: dir,
  regions: new Map([['MAA_mod/module.c', findProtectedRegions(SOURCE)]]),
});

describe('protected regions', () => {
  test('finds regions and the one enclosing a line', () => {
    const regions = findProtectedRegions(SOURCE);
    expect(regions).toEqual([{ id: 'protect_compute_MAA', startLine: 3, endLine: 6 }]);
    expect(regionAt(regions, 5)?.id).toBe('protect_compute_MAA');
    expect(regionAt(regions, 8)).toBeNull();
  });
});

describe('gcc diagnostics', () => {
  test('real gcc JSON output maps to tree-relative files, marks protected regions', () => {
    const stderr = compile('json').trim();
    expect(looksLikeGccJson(stderr)).toBe(true);
    const diags = parseGccJsonLine(stderr, ctx())!;
    const inRegion = diags.find((d) => /.missing. undeclared/.test(d.message))!;
    expect(inRegion).toMatchObject({ severity: 'error', file: 'MAA_mod/module.c', line: 5, column: 14 });
    expect(inRegion.protectedRegion).toEqual({ id: 'protect_compute_MAA', startLine: 3, endLine: 6 });
    const outside = diags.find((d) => /.undeclared_too. undeclared/.test(d.message))!;
    expect(outside).toMatchObject({ file: 'MAA_mod/module.c', line: 8, protectedRegion: null });
    const warn = diags.find((d) => d.severity === 'warning')!;
    expect(warn).toMatchObject({ line: 4, option: '-Wunused-variable' });
    expect(renderDiagnostic(inRegion)).toMatch(/^MAA_mod\/module.c:5:14: error: .* \(in protected region protect_compute_MAA\)$/);
  });

  test('src-gen/ older than the model: a line in a region is told in the user\'s copy of it, any other at the built file\'s, said', () => {
    const stderr = compile('json').trim();
    // the user's copy: 4 lines more above the region (an older model's tables), the region's text the same
    const mine = ['/* 1 */', '/* 2 */', '/* 3 */', '/* 4 */', SOURCE].join('\n');
    const withCopy = { ...ctx(), userCopies: new Map([['MAA_mod/module.c', { regions: findProtectedRegions(mine) }]]) };
    const diags = parseGccJsonLine(stderr, withCopy)!;
    const inRegion = diags.find((d) => /.missing. undeclared/.test(d.message))!;
    expect(inRegion).toMatchObject({ file: 'MAA_mod/module.c', line: 9, column: 14, protectedRegion: { id: 'protect_compute_MAA', startLine: 7, endLine: 10 } });
    expect(mine.split('\n')[inRegion.line! - 1]).toContain('missing');
    expect(inRegion.message).not.toMatch(/as this build generated it/);
    const outside = diags.find((d) => /.undeclared_too. undeclared/.test(d.message))!;
    expect(outside.line).toBe(8);
    expect(outside.message).toMatch(/ \(line 8 of the file as this build generated it: your copy in src-gen\/ differs, older than the model; contract generate, or Generate All in the IDE, brings src-gen\/ up to date\)$/);
    // no copy of the file at all (src-gen/ never generated): every line is the built file's, said
    const none = parseGccJsonLine(stderr, { ...ctx(), userCopies: new Map([['MAA_mod/module.c', { regions: null }]]) })!;
    expect(none.find((d) => /.missing. undeclared/.test(d.message))).toMatchObject({ line: 5, message: expect.stringMatching(/\(line 5 of the file as this build generated it: src-gen\/ has no copy of it; /) });
    // a copy whose region is not there any more (or not the same length): not moved, said
    const other = ['/* 1 */', SOURCE.replace('protect_compute_MAA', 'protect_other')].join('\n');
    const gone = parseGccJsonLine(stderr, { ...ctx(), userCopies: new Map([['MAA_mod/module.c', { regions: findProtectedRegions(other) }]]) })!;
    expect(gone.find((d) => /.missing. undeclared/.test(d.message))).toMatchObject({ line: 5, protectedRegion: { id: 'protect_compute_MAA' }, message: expect.stringMatching(/your copy in src-gen\/ differs/) });
  });

  test('gcc text output is parsed the same way (fallback)', () => {
    const lines = compile('text').split('\n');
    const diags = lines.map((l) => parseGccTextLine(l, ctx())).filter((d) => d !== null);
    const err = diags.find((d) => /.missing. undeclared/.test(d.message))!;
    expect(err).toMatchObject({ severity: 'error', file: 'MAA_mod/module.c', line: 5, column: 14 });
    expect(err.protectedRegion?.id).toBe('protect_compute_MAA');
    expect(diags.find((d) => d.severity === 'warning')?.option).toBe('-Wunused-variable');
  });

  test("the ContrACT Eclipse tool's logFile used in a region: the error says it is gone and what replaces it (JSON and text, C and UTF-8 locales)", () => {
    const old = ['#include <stdio.h>', 'void _exit_module(void){', '  /*PROTECTED REGION ID(protect_exit_MAA) ENABLED START*/', '  fprintf(logFile, "end\\n");', '  /*PROTECTED REGION END*/', '}', ''].join('\n');
    const sub = join(dir, 'old', 'MAA_mod');
    mkdirSync(sub, { recursive: true });
    writeFileSync(join(sub, 'module.c'), old);
    const oldCtx = { cwd: sub, root: join(dir, 'old'), regions: new Map([['MAA_mod/module.c', findProtectedRegions(old)]]) };
    const hint = "; the ContrACT Eclipse tool's `FILE* logFile` is gone: libmodule writes each module's CSV log; add a record to it with ContractLog() (docs/runtime-api.md, docs/migrating.md)";
    for (const locale of ['C', 'C.UTF-8']) {
      const gcc = (args: string[]) => spawnSync('gcc', ['-std=c11', '-c', 'module.c', '-o', '/dev/null', ...args], { cwd: sub, encoding: 'utf8', env: { ...process.env, LC_ALL: locale } }).stderr;
      const json = parseGccJsonLine(gcc(['-fdiagnostics-format=json']).trim(), oldCtx)!;
      const text = gcc(['-fno-diagnostics-show-caret']).split('\n').map((l) => parseGccTextLine(l, oldCtx)).filter((d) => d !== null);
      for (const diags of [json, text]) {
        const err = diags.find((d) => d.severity === 'error')!;
        expect(err, locale).toMatchObject({ file: 'MAA_mod/module.c', line: 4, protectedRegion: { id: 'protect_exit_MAA' } });
        expect(err.message, locale).toMatch(/^.logFile. undeclared \(first use in this function\); /);
        expect(err.message.endsWith(hint), locale).toBe(true);
      }
    }
    // any other undeclared name: no hint
    expect(parseGccJsonLine(compile('json').trim(), ctx())!.some((d) => d.message.includes('ContractLog'))).toBe(false);
  });

  test('make directory tracking resolves paths of sub-makes', () => {
    const router = new BuildOutputRouter({ startDir: '/work/src-gen/generated/architecture', root: '/work/src-gen', regions: new Map() });
    router.route("make[1]: Entering directory '/work/src-gen/generated/MAA_mod'", 'stdout');
    const { diagnostics } = router.route('module.c:12:3: error: expected ‘;’ before ‘}’ token', 'stderr');
    expect(diagnostics[0]).toMatchObject({ file: 'generated/MAA_mod/module.c', line: 12, column: 3 });
    router.route("make[1]: Leaving directory '/work/src-gen/generated/MAA_mod'", 'stdout');
    expect(router.route('x.c:1:1: warning: w', 'stderr').diagnostics[0]!.file).toBe('generated/architecture/x.c');
    expect(makeEnteringDirectory("make: Entering directory '/a b'")).toBe('/a b');
    expect(execFileSync('gcc', ['--version'], { encoding: 'utf8' })).toMatch(/gcc/);
  });

  test('launcher tags name the module', () => {
    expect(routeRunLine('[MAA] hello world')).toEqual({ source: 'MAA', line: 'hello world' });
    expect(routeRunLine('contract-launch: module MSC exited')).toEqual({ source: 'launcher', line: 'module MSC exited' });
    expect(routeRunLine('make: Entering directory')).toEqual({ source: 'run', line: 'make: Entering directory' });
    // a bare CR (or U+2028) inside a module's line keeps it that module's, not make's
    expect(routeRunLine('[CTL] 50%\rOVER\u2028x')).toEqual({ source: 'CTL', line: '50%\rOVER\u2028x' });
  });

  test("make's line for a failed recipe gives its target and status; nothing else does", () => {
    expect(makeRecipeStatus('make: *** [Makefile:67: run] Error 1')).toEqual({ target: 'run', status: 1 });
    expect(makeRecipeStatus('make[1]: *** [Makefile:23: MAA] Error 2')).toEqual({ target: 'MAA', status: 2 });
    for (const line of ['make: *** [Makefile:6: run] Killed', 'make: Entering directory', '[MAA] make: *** [Makefile:1: run] Error 9',
      'make: *** [Makefile:67: run] Error 1 and more', `make: *** [${'x'.repeat(500)}: run] Error 1`]) {
      expect(makeRecipeStatus(line)).toBeNull();
    }
  });

  test('a parallel build (make -j --output-sync, 2>&1): every module\'s diagnostics map to its own files', () => {
    // a tree shaped like the generated one: a top Makefile making each module in its folder
    const top = join(dir, 'parallel', 'architecture');
    const modules = ['A', 'B', 'C', 'D'];
    mkdirSync(top, { recursive: true });
    const rule = (m: string) => `${m}:\n\t$(MAKE) -C modules/${m}_mod\n`;
    writeFileSync(join(top, 'Makefile'), `.PHONY: all ${modules.join(' ')}\nall: ${modules.join(' ')}\n${modules.map(rule).join('')}`);
    modules.forEach((m, i) => {
      mkdirSync(join(top, 'modules', `${m}_mod`), { recursive: true });
      writeFileSync(join(top, 'modules', `${m}_mod`, 'Makefile'), `${m}: module.c\n\tcc -std=c11 -c $(EXTRA_CFLAGS) -o ${m}.o module.c\n`);
      // module i has its error on line i + 2
      writeFileSync(join(top, 'modules', `${m}_mod`, 'module.c'), `${'\n'.repeat(i + 1)}int f(void) { return undeclared_${m}; }\n`);
    });
    const r = spawnSync('sh', ['-c', 'exec "$@" 2>&1', 'sh', 'make', '-k', '-j4', '--output-sync=recurse', '-C', top, 'all', 'EXTRA_CFLAGS=-fdiagnostics-format=json'], { encoding: 'utf8' });
    expect(r.stderr).toBe('');
    const route = (diagnosticsOnStdout: boolean) => {
      const router = new BuildOutputRouter({ startDir: top, root: join(dir, 'parallel'), regions: new Map(), ...(diagnosticsOnStdout ? { diagnosticsOnStdout } : {}) });
      return r.stdout.split('\n').flatMap((l) => router.route(l, 'stdout').diagnostics);
    };
    const found = route(true).filter((d) => d.severity === 'error').map((d) => [d.file, d.line, /undeclared_(\w)/.exec(d.message)?.[1]]);
    expect(found.sort()).toEqual(modules.map((m, i) => [`architecture/modules/${m}_mod/module.c`, i + 2, m]));
    // without the option, a JSON line on stdout is plain text (a plain Makefile's build keeps its streams apart)
    expect(route(false)).toEqual([]);
  });

  test('build jobs: one per CPU, at most 4, at most one per 128 MiB of the memory limit', () => {
    expect(buildJobs(DEFAULT_LIMITS, 2)).toBe(2);
    expect(buildJobs(DEFAULT_LIMITS, 64)).toBe(4);
    expect(buildJobs({ ...DEFAULT_LIMITS, memoryMiB: 256 }, 64)).toBe(2);
    expect(buildJobs({ ...DEFAULT_LIMITS, memoryMiB: 64 }, 64)).toBe(1);
    expect(buildJobs(DEFAULT_LIMITS, 1)).toBe(1);
  });
});
