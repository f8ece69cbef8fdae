/**
 * Fuzzing the parsers of a sandbox's output (fast-check): random and adversarial lines are parsed
 * in bounded time and never throw; random JSON shapes never throw and only give well-typed
 * diagnostics; the linear text scanner reads ordinary lines exactly as gcc's format says (checked
 * against the format as a backtracking regular expression, on lines short enough for it to be fast).
 */
import fc from 'fast-check';
import { describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { relativeToRoot, type GccDiagnostic } from './gcc-diagnostics.js';
import { parseGccJsonLine } from './gcc-json.js';
import { parseGccTextLine } from './gcc-text.js';
import { BuildOutputRouter, routeRunLine } from './output-router.js';

const ctx = { cwd: '/work/src-gen/MAA_mod', root: '/work/src-gen', regions: new Map([['MAA_mod/module.c', [{ id: 'protect_x', startLine: 1, endLine: 9 }]]]) };

/** Per-line time bound: far above the microseconds a line takes, far below a stalled event loop. */
const LINE_MS = 50;

function routeAll(line: string): void {
  const router = new BuildOutputRouter({ startDir: ctx.cwd, root: ctx.root, regions: ctx.regions });
  for (const stream of ['stdout', 'stderr'] as const) router.route(line, stream);
  routeRunLine(line);
}

/**
 * The time one line takes: the least of three runs, so that the machine's load (other processes,
 * a GC pause) is not counted while a slow parser (the same work every run) still is.
 */
function timed(line: string): number {
  let best = Infinity;
  for (let i = 0; i < 3; i++) {
    const t0 = performance.now();
    routeAll(line);
    best = Math.min(best, performance.now() - t0);
  }
  return best;
}

/** True when `d` has exactly the types the API documents (docs/build-service-api.md). */
function wellTyped(d: unknown, depth = 0): boolean {
  if (!d || typeof d !== 'object' || depth > SERVICE_BOUNDS.diagnosticDepth) return false;
  const x = d as Record<string, unknown>;
  const intOrNull = (v: unknown): boolean => v === null || (Number.isInteger(v) && (v as number) >= 0);
  return (
    ['error', 'warning', 'note'].includes(x.severity as string) &&
    typeof x.message === 'string' &&
    (x.option === undefined || typeof x.option === 'string') &&
    (x.file === null || typeof x.file === 'string') &&
    intOrNull(x.line) &&
    intOrNull(x.column) &&
    (x.endLine === undefined || intOrNull(x.endLine)) &&
    (x.endColumn === undefined || intOrNull(x.endColumn)) &&
    (x.protectedRegion === null || typeof (x.protectedRegion as { id?: unknown })?.id === 'string') &&
    Array.isArray(x.children) &&
    x.children.every((c) => wellTyped(c, depth + 1))
  );
}

/** Pieces that make regular-expression engines backtrack: runs of them make adversarial lines. */
const PIECES = [' ', '  ', '\t', ':', '::', '1', '123', ':1:', ':1:1:', ' error:', ' warning: ', 'note:', 'fatal error: ', '[', ']', '[-W', ' [-Wx', '-W', 'a', '/', '"', '{', '}', '\\', '\u0000', 'é', '\u{1F600}', '\u2028', '\r', 'make: Entering directory \'', '[MAA]'];

const adversarialLine = fc
  .tuple(fc.array(fc.constantFrom(...PIECES), { minLength: 1, maxLength: 8 }), fc.integer({ min: 1, max: 100_000 }), fc.string({ maxLength: 40 }), fc.string({ maxLength: 40 }))
  .map(([unit, n, prefix, suffix]) => {
    const u = unit.join('');
    return (prefix + u.repeat(Math.ceil(n / u.length)) + suffix).slice(0, 100_000);
  });

describe('lines of a sandbox: bounded time, no exception', () => {
  test('one line of "a:1:1: error: " + " [-Wx" x 13000 (a backtracking parser stalls on it)', () => {
    const line = 'a:1:1: error: ' + ' [-Wx'.repeat(13000);
    expect(timed(line)).toBeLessThan(LINE_MS);
    const d = parseGccTextLine(line, ctx)!;
    expect(d).toMatchObject({ severity: 'error', file: 'MAA_mod/a', line: 1, column: 1 });
    // cut before parsing, with a marker; the line itself is still logged whole by the router
    expect(d.message).toMatch(/\[… \d+ characters cut\]$/);
    expect(d.message.length).toBeLessThan(SERVICE_BOUNDS.parsedLineChars + 100);
    const routed = new BuildOutputRouter({ startDir: ctx.cwd, root: ctx.root, regions: ctx.regions }).route(line, 'stderr');
    expect(routed.lines).toEqual([{ source: 'build', line }]);
  });

  test.each([
    ['spaces', 'a:1:1: error:' + ' '.repeat(100_000) + 'x'],
    ['colons', ':'.repeat(100_000)],
    ['digits and colons', '1:'.repeat(50_000)],
    ['line:col heads', 'f' + ':1:1: '.repeat(16_000)],
    ['brackets', 'a:1: error: ' + '['.repeat(50_000) + ']'.repeat(50_000)],
    ['options', 'a:1: warning: m' + ' [-W'.repeat(25_000) + ']'],
    ['make directories', "make[1]: Entering directory '" + "'".repeat(100_000)],
    ['JSON opening', '[{"kind"' + ' '.repeat(100_000)],
    ['NUL', '\u0000'.repeat(100_000)],
    ['ld places', '/usr/bin/ld: ' + 'a.o:'.repeat(25_000) + ': undefined reference to `x\''],
    ['ld definitions', 'ld: x:1: multiple definition of `g\'' + '; a:1'.repeat(20_000) + ': first defined here'],
    ['ld functions', '/usr/bin/ld: ' + ": in function `".repeat(7_000) + "':"],
    ['unicode', 'é:1: error: ' + '\u{1F600}'.repeat(40_000)],
  ])('%s (100k characters)', (_name, line) => {
    expect(timed(line)).toBeLessThan(LINE_MS);
  });

  test('random adversarial lines up to 100k characters: < 50 ms each, never a throw', () => {
    let worst = 0;
    fc.assert(
      fc.property(adversarialLine, (line) => {
        worst = Math.max(worst, timed(line));
        const d = parseGccTextLine(line, ctx);
        return d === null || wellTyped(d);
      }),
      { numRuns: 300 },
    );
    expect(worst).toBeLessThan(LINE_MS);
  });

  test('random strings (any unicode) never throw', () => {
    fc.assert(
      fc.property(fc.string({ unit: 'binary', maxLength: 2000 }), (line) => {
        routeAll(line);
        const d = parseGccTextLine(line, ctx);
        return d === null || wellTyped(d);
      }),
      { numRuns: 2000 },
    );
  });
});

/** The format as a backtracking regular expression: the reference (quadratic and worse on crafted lines). */
const OLD_TEXT = /^(.+?):(\d+):(?:(\d+):)?\s+(fatal error|error|warning|note):\s+(.*?)(?:\s+\[(-W[^\]]+)\])?$/;

describe('the text scanner reads gcc lines as the format says', () => {
  const TOKENS = ['a', 'b.c', '/', 'x y', ' ', '\t', ':', '1', '12', '0', 'error', 'warning', 'note', 'fatal error', 'fatal', '[-W', '[-Wall]', '[', ']', '-W', 'é', '\u00a0'];
  test('same result as the old expression on short lines', () => {
    fc.assert(
      fc.property(fc.array(fc.constantFrom(...TOKENS), { maxLength: 24 }), (tokens) => {
        const line = tokens.join('');
        const m = OLD_TEXT.exec(line);
        const got = parseGccTextLine(line, ctx);
        if (!m || (m[1]!.includes(' ') && !m[1]!.includes('/'))) return got === null;
        if (m[2]!.length > 9 || (m[3]?.length ?? 0) > 9) return true; // not gcc's numbers: the scanner refuses them
        const expected: Partial<GccDiagnostic> = {
          file: relativeToRoot(m[1]!, ctx) ?? m[1]!,
          line: Number(m[2]),
          column: m[3] ? Number(m[3]) : null,
          severity: m[4] === 'warning' ? 'warning' : m[4] === 'note' ? 'note' : 'error',
          message: m[5]!,
        };
        expect(got).toMatchObject(expected);
        expect(got!.option).toBe(m[6]);
        return true;
      }),
      { numRuns: 5000 },
    );
  });

  test('gcc lines', () => {
    expect(parseGccTextLine("module.c:12:3: error: expected ';' before '}' token", ctx)).toMatchObject({ file: 'MAA_mod/module.c', line: 12, column: 3, severity: 'error', protectedRegion: null });
    expect(parseGccTextLine('module.c:4:7: warning: unused variable ‘x’ [-Wunused-variable]', ctx)).toMatchObject({ line: 4, message: 'unused variable ‘x’', option: '-Wunused-variable', protectedRegion: { id: 'protect_x' } });
    expect(parseGccTextLine('/usr/include/stdio.h:1: fatal error: x.h: No such file or directory', ctx)).toMatchObject({ file: '/usr/include/stdio.h', line: 1, column: null, severity: 'error', message: 'x.h: No such file or directory' });
    expect(parseGccTextLine('In file included from a.c:1:', ctx)).toBeNull();
    expect(parseGccTextLine('a.c:99999999999: error: x', ctx)).toBeNull();
  });
});

describe('gcc JSON path: random shapes', () => {
  const kinds = fc.constantFrom('error', 'warning', 'note', 'fatal error', 'ice', '');
  const position = fc.record({ file: fc.oneof(fc.string(), fc.anything()), line: fc.oneof(fc.nat(), fc.anything()), column: fc.oneof(fc.nat(), fc.anything()) }, { requiredKeys: [] });
  const diagnostic = fc.letrec((tie) => ({
    diag: fc.record(
      {
        kind: fc.oneof(kinds, fc.anything()),
        message: fc.oneof(fc.string(), fc.anything()),
        option: fc.oneof(fc.string(), fc.anything()),
        locations: fc.oneof(fc.array(fc.record({ caret: position, finish: position }, { requiredKeys: [] }), { maxLength: 3 }), fc.anything()),
        children: fc.oneof({ depthSize: 'small', withCrossShrink: true }, fc.constant([]), fc.array(tie('diag'), { maxLength: 3 }), fc.anything()),
      },
      { requiredKeys: [] },
    ),
  })).diag;

  test('gcc-like shapes, fc.jsonValue and fc.anything: never a throw, only well-typed diagnostics', () => {
    const check = (value: unknown): boolean => {
      let line: string;
      try {
        line = JSON.stringify(value) ?? 'null';
      } catch {
        return true; // not JSON-representable (BigInt...): not something a sandbox can print
      }
      const diags = parseGccJsonLine(line, ctx);
      routeAll(line);
      return diags === null || (Array.isArray(diags) && diags.every((d) => wellTyped(d)));
    };
    fc.assert(fc.property(fc.array(diagnostic, { maxLength: 4 }), check), { numRuns: 1500 });
    fc.assert(fc.property(fc.jsonValue(), check), { numRuns: 1500 });
    fc.assert(fc.property(fc.array(fc.jsonValue()), check), { numRuns: 500 });
    fc.assert(fc.property(fc.anything(), check), { numRuns: 1500 });
  });
});
