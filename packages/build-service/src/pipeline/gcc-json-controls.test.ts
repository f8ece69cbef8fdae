/**
 * A control character in a `#warning` (a BEL, an ESC) is written raw by gcc 12 inside its JSON
 * string: the compilation's line was invalid JSON and every diagnostic of that file vanished, its
 * real errors and gcc's own -Wbidi-chars (Trojan Source) warning included. gcc of the host compiles
 * the field tester's file here; gcc-json-controls.bwrap.test.ts builds it through a whole job.
 */
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { controlsEscapedInStrings, parseGccJson } from './gcc-json-controls.js';
import { BuildOutputRouter, GCC_JSON_UNREADABLE } from './output-router.js';

const dir = mkdtempSync(join(tmpdir(), 'gcc-json-controls-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

/** gcc's JSON diagnostics line of `source` compiled as module.c (its stderr: one line); `fails`: it has an error. */
function gccJson(source: string, fails = true): string {
  writeFileSync(join(dir, 'module.c'), source);
  const r = spawnSync('gcc', ['-std=c11', '-fdiagnostics-format=json', '-c', 'module.c', '-o', '/dev/null'], { cwd: dir, encoding: 'utf8' });
  expect(r.status === 0).toBe(!fails);
  const lines = r.stderr.split('\n').filter(Boolean);
  expect(lines).toHaveLength(1);
  return lines[0]!;
}

const route = (line: string) => new BuildOutputRouter({ startDir: dir, root: dir, regions: new Map() }).route(line, 'stderr');

describe('gcc\'s JSON line of a #warning holding a control character', () => {
  test.each([
    ['a BEL', '\x07', '\\u0007'],
    ['an ESC', '\x1b[2J', '\\u001b[2J'],
  ])('%s: every diagnostic is read, the real error too, the character shown as its escape', (_name, raw, shown) => {
    const line = gccJson(`#warning "plain warning one"\n#warning "bell ${raw} here"\nint undeclared_use(void){ return nosuchvar; }\n`);
    expect(() => JSON.parse(line)).toThrow(); // gcc's line as it is: no JSON
    const routed = route(line);
    expect(routed.unreadable).toBeUndefined();
    expect(routed.diagnostics.map((d) => [d.severity, d.line, d.message])).toEqual([
      ['error', 3, expect.stringContaining('nosuchvar')],
      ['warning', 1, '#warning "plain warning one"'],
      ['warning', 2, `#warning "bell ${shown} here"`],
    ]);
    expect(routed.diagnostics[0]).toMatchObject({ file: 'module.c', column: 34 });
  });

  test('gcc\'s -Wbidi-chars warning of a U+202E is read beside an ESC in a #warning (Trojan Source is told)', () => {
    const line = gccJson('#warning "esc \x1b here"\nconst char *s = "a\u202e b";\nint f(void){ return 0; }\n', false);
    expect(() => JSON.parse(line)).toThrow();
    const routed = route(line);
    expect(routed.diagnostics.map((d) => [d.severity, d.line, d.option ?? '', d.message])).toEqual([
      ['warning', 1, '-Wcpp', '#warning "esc \\u001b here"'],
      ['warning', 2, '-Wbidi-chars=', 'unpaired UTF-8 bidirectional control character detected'],
    ]);
    // the text log's lines: no raw control character either
    expect(routed.lines.map((l) => l.line).join('\n')).not.toMatch(/[\x00-\x08\x0b-\x1f]/);
  });
});

describe('controlsEscapedInStrings', () => {
  test('escapes raw control characters inside strings only, leaves escapes and whitespace outside strings alone', () => {
    expect(controlsEscapedInStrings('[{"message": "a\x07b\\"\x1b"},\t{"k": "\\n"}]')).toBe('[{"message": "a\\u0007b\\"\\u001b"},\t{"k": "\\n"}]');
    const same = '[{"message": "plain"}]';
    expect(controlsEscapedInStrings(same)).toBe(same);
    expect(parseGccJson('[{"message": "a\x00b"}]')).toEqual([{ message: 'a\x00b' }]);
    expect(parseGccJson('[{"message": "a\x07b" x]')).toBeUndefined();
  });
});

describe('a line that begins as gcc\'s JSON and cannot be read at all', () => {
  test('is logged as text, and the build says its diagnostics were not read', () => {
    const line = '[{"kind": "error", "message": "x" ,, ]';
    const routed = route(line);
    expect(routed.diagnostics).toEqual([]);
    expect(routed.lines).toEqual([{ source: 'build', line }]);
    expect(routed.unreadable).toBe(GCC_JSON_UNREADABLE);
    expect(GCC_JSON_UNREADABLE).toMatch(/^a line of gcc's JSON diagnostics \(one compilation's\) could not be read/);
  });
});
