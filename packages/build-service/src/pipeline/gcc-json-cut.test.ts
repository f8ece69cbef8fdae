/**
 * A compilation with hundreds of diagnostics, from real gcc: gcc writes them as one JSON line
 * (gcc 12 nests the `#warning`s, and the error after them, in the first one's `children`), longer
 * than the common 64 KiB line bound. The error is reported with its place whatever the nesting; a
 * line an output bound cut gives its complete diagnostics, errors first, and says the cut.
 */
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { LineSplitter } from '../util/line-splitter.js';
import { looksLikeGccJson, MESSAGE_CUT, parseCutGccJsonLine, parseGccJsonLine } from './gcc-json.js';
import { BuildOutputRouter, GCC_JSON_UNREADABLE } from './output-router.js';

const dir = mkdtempSync(join(tmpdir(), 'gccjson-cut-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

const ERROR_LINE = 'int bad = undeclared_symbol_x;';

/** gcc's JSON line for a file of `before` #warnings, the error, then `after` #warnings. */
function compile(before: number, after: number): string {
  const warnings = (from: number, n: number) => Array.from({ length: n }, (_, i) => `#warning "w${from + i}"`);
  writeFileSync(join(dir, 'module.c'), [...warnings(0, before), ERROR_LINE, ...warnings(before, after), ''].join('\n'));
  const r = spawnSync('gcc', ['-std=c11', '-c', 'module.c', '-o', '/dev/null', '-fdiagnostics-format=json'], { cwd: dir, encoding: 'utf8' });
  return r.stderr.trim();
}

const ctx = () => ({ cwd: dir, root: dir, regions: new Map() });
const theError = { severity: 'error', message: expect.stringContaining('undeclared_symbol_x'), file: 'module.c' };

describe('a compilation of hundreds of diagnostics (one gcc JSON line)', () => {
  test('200 #warnings and an error: one line past 64 KiB, within gccJsonLineBytes; the error reported first, at its line, each warning its own', () => {
    const line = compile(200, 0);
    expect(line.length).toBeGreaterThan(64 * 1024);
    expect(line.length).toBeLessThan(SERVICE_BOUNDS.gccJsonLineBytes);
    const diags = parseGccJsonLine(line, ctx())!;
    expect(diags).toHaveLength(201);
    expect(diags.slice(0, 200).map((d) => d.message)).toEqual(Array.from({ length: 200 }, (_, i) => `#warning "w${i}"`));
    expect(diags[200]).toMatchObject({ ...theError, line: 201, column: 11 });
    expect(diags.every((d) => d.children.every((c) => c.severity === 'note'))).toBe(true);
    // the job's diagnostics: the error first (a job keeps diagnosticsPerJob); the log in gcc's order
    const routed = new BuildOutputRouter({ startDir: dir, root: dir, regions: new Map(), diagnosticsOnStdout: true }).route(line, 'stdout');
    expect(routed.diagnostics[0]).toMatchObject({ ...theError, line: 201 });
    expect(routed.lines[0]!.line).toMatch(/warning: #warning "w0"/);
    expect(routed.lines).toHaveLength(201);
  });

  test('the documented 1000 diagnostics of one line are read (gcc 12 nests them: 999 children of the first)', () => {
    const diags = parseGccJsonLine(compile(999, 0), ctx())!;
    expect(diags).toHaveLength(1000);
    expect(diags[999]).toMatchObject({ ...theError, line: 1000 });
  });

  test('past the documented 1000 (1001 #warnings, nested, then the error; or 1000 top-level warnings then the error): read up to the bound, the error first, the rest said left out', () => {
    const nested = compile(1001, 0);
    expect(parseGccJsonLine(nested, ctx())).toBeNull(); // past the declared shape (1001 children of the first)
    const routed = new BuildOutputRouter({ startDir: dir, root: dir, regions: new Map(), diagnosticsOnStdout: true }).route(nested, 'stdout');
    expect(routed.diagnostics[0]).toMatchObject({ ...theError, line: 1002 });
    expect(routed.cut).toMatch(/held more than the 1000 diagnostics read .*: 1001 read, its errors first \(1 error\(s\)\), 1 other\(s\) not reported$/);
    // 1000 unused functions (top-level warnings, gcc's order) and the error in the last one's body
    const fns = Array.from({ length: 1000 }, (_, i) => `static int unused_v${i}(void) { return 0; }`);
    writeFileSync(join(dir, 'module.c'), [...fns, `int f(void) { ${ERROR_LINE} return bad; }`, ''].join('\n'));
    const r = spawnSync('gcc', ['-std=c11', '-Wall', '-c', 'module.c', '-o', '/dev/null', '-fdiagnostics-format=json'], { cwd: dir, encoding: 'utf8' });
    const flat = r.stderr.trim();
    expect(flat.length).toBeLessThan(SERVICE_BOUNDS.gccJsonLineBytes);
    const top = new BuildOutputRouter({ startDir: dir, root: dir, regions: new Map(), diagnosticsOnStdout: true }).route(flat, 'stdout');
    expect(top.diagnostics[0]).toMatchObject({ ...theError, line: 1001 });
    expect(top.diagnostics).toHaveLength(1000);
    expect(top.cut).toMatch(/1000 read, its errors first \(1 error\(s\)\), 1 other\(s\) not reported$/);
  });

  test('the splitter keeps a gcc JSON line whole up to gccJsonLineBytes; another line is split at 64 KiB', () => {
    const json = compile(200, 0);
    const split = (text: string): string[] => {
      const lines: string[] = [];
      const s = new LineSplitter({ maxBytes: 8 * 1024 * 1024, onLine: (l) => lines.push(l), onTruncated: () => {}, longLine: { maxBytes: SERVICE_BOUNDS.gccJsonLineBytes, begins: looksLikeGccJson } });
      const bytes = Buffer.from(`${text}\n`);
      for (let i = 0; i < bytes.length; i += 4096) s.push(bytes.subarray(i, i + 4096));
      s.end();
      return lines;
    };
    expect(split(json)).toEqual([json]);
    expect(split('x'.repeat(100 * 1024)).map((l) => l.length)).toEqual([64 * 1024, 36 * 1024]);
    // past its own bound, a JSON line is split there (what follows is no JSON line: 64 KiB pieces)
    const long = `${json}${'x'.repeat(SERVICE_BOUNDS.gccJsonLineBytes)}`;
    const pieces = split(long);
    expect(pieces.map((l) => Buffer.byteLength(l))).toEqual([SERVICE_BOUNDS.gccJsonLineBytes, 64 * 1024, Buffer.byteLength(long) - SERVICE_BOUNDS.gccJsonLineBytes - 64 * 1024]);
    expect(pieces.join('')).toBe(long);
  });

  test('a line cut after the error: its complete diagnostics, the error first with its place, the cut said', () => {
    const line = compile(100, 400);
    const cutAt = 64 * 1024;
    expect(line.length).toBeGreaterThan(cutAt);
    const cut = line.slice(0, cutAt);
    expect(parseGccJsonLine(cut, ctx())).toBeNull();
    const salvaged = parseCutGccJsonLine(cut, ctx())!;
    expect(salvaged.diagnostics[100]).toMatchObject({ ...theError, line: 101, column: 11 });
    // the first #warning holds the others (gcc 12), left open by the cut: its message if gcc wrote it before its children
    expect(salvaged.diagnostics[0]).toMatchObject({ severity: 'warning', line: 1, message: expect.toBeOneOf(['#warning "w0"', MESSAGE_CUT]) });
    expect(salvaged.diagnostics[1]).toMatchObject({ severity: 'warning', line: 2, message: '#warning "w1"' });
    expect(salvaged.diagnostics.filter((d) => d.severity === 'error')).toHaveLength(1);
    expect(salvaged.diagnostics.length).toBeGreaterThan(150);
    expect(salvaged.readChars).toBeLessThanOrEqual(cutAt + 8);
    const routed = new BuildOutputRouter({ startDir: dir, root: dir, regions: new Map(), diagnosticsOnStdout: true }).route(`${cut} [cut here: the output limit]`, 'stdout');
    expect(routed.diagnostics).toEqual([salvaged.diagnostics[100], ...salvaged.diagnostics.filter((d) => d.severity !== 'error')]);
    expect(routed.cut).toMatch(new RegExp(`^a line of gcc's JSON diagnostics \\(one compilation's\\) was cut after ${cutAt + 29} characters by an output bound .*: its first ${salvaged.diagnostics.length} complete diagnostic\\(s\\) \\(1 error\\(s\\)\\) were read .*, those after them are lost$`));
  });

  test('a diagnostic the cut left open keeps the fields it had, its message said cut; its complete children are read', () => {
    const at = (line: number) => ({ caret: { file: 'module.c', line, column: 1 } });
    const line = `[{"kind":"warning","locations":[${JSON.stringify(at(1))}],"children":[{"kind":"error","message":"e","locations":[${JSON.stringify(at(3))}]},{"kind":"note","mess`;
    expect(parseCutGccJsonLine(line, ctx())?.diagnostics).toEqual([
      expect.objectContaining({ severity: 'warning', line: 1, message: MESSAGE_CUT, children: [] }),
      expect.objectContaining({ severity: 'error', line: 3, message: 'e', file: 'module.c' }),
    ]);
  });

  test('a cut line with no complete diagnostic, or a JSON-looking line that is no gcc output, stays text, said unreadable', () => {
    const router = new BuildOutputRouter({ startDir: dir, root: dir, regions: new Map(), diagnosticsOnStdout: true });
    for (const line of [compile(1, 0).slice(0, 40), '[{"kind":"error","message":"x"', `[${'{"kind":"error","children":['.repeat(200)}{"kind":"error"}`]) {
      expect(parseCutGccJsonLine(line, ctx())).toBeNull();
      expect(router.route(line, 'stdout')).toEqual({ lines: [{ source: 'build', line }], diagnostics: [], unreadable: GCC_JSON_UNREADABLE });
    }
  });
});
