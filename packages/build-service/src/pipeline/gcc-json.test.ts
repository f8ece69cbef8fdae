/**
 * gcc JSON lines are sandbox output: user code prints any JSON-looking line it likes (an
 * `__asm__(".warning ...")` is enough). Lines not of the declared shape stay plain text lines.
 */
import { describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { parseGccJsonLine } from './gcc-json.js';
import { BuildOutputRouter, GCC_JSON_UNREADABLE } from './output-router.js';

const ctx = { cwd: '/work/src-gen/MAA_mod', root: '/work/src-gen', regions: new Map() };

function nested(depth: number): unknown {
  let d: Record<string, unknown> = { kind: 'note', message: 'leaf' };
  for (let i = 0; i < depth; i++) d = { kind: 'note', message: `level ${i}`, children: [d] };
  return { ...d, kind: 'error' };
}

describe('gcc JSON lines of the wrong shape stay text', () => {
  test.each([
    ['children a number', '[{"kind":"error","children":5}]'],
    ['children an object', '[{"kind":"error","children":{"kind":"note"}}]'],
    ['children a string', '[{"kind":"error","children":"x"}]'],
    ['children of numbers', '[{"kind":"error","children":[1,2]}]'],
    ['locations not an array', '[{"kind":"error","locations":{"caret":{"line":1}}}]'],
    ['caret line as a string', '[{"kind":"error","locations":[{"caret":{"file":"a.c","line":"1"}}]}]'],
    ['caret a string', '[{"kind":"error","locations":["a.c:1"]}]'],
    ['negative column', '[{"kind":"error","locations":[{"caret":{"line":1,"column":-3}}]}]'],
    ['fractional line', '[{"kind":"error","locations":[{"caret":{"line":1.5}}]}]'],
    ['message an object', '[{"kind":"error","message":{"toString":1}}]'],
    ['kind a number', '[{"kind":7}]'],
    ['an element not an object', '[{"kind":"error"},null]'],
    ['null fields', '[{"kind":"error","message":null}]'],
    ['too long a message', JSON.stringify([{ kind: 'error', message: 'x'.repeat(SERVICE_BOUNDS.diagnosticTextChars + 1) }])],
    ['nesting one level too deep', JSON.stringify([nested(SERVICE_BOUNDS.diagnosticDepth + 1)])],
    ['huge nesting', `[${'{"kind":"error","children":['.repeat(5000)}${']}'.repeat(5000)}]`], // too deep for JSON.stringify here
  ])('%s', (_name, line) => {
    expect(() => parseGccJsonLine(line, ctx)).not.toThrow();
    expect(parseGccJsonLine(line, ctx)).toBeNull();
    const router = new BuildOutputRouter({ startDir: ctx.cwd, root: ctx.root, regions: ctx.regions });
    const routed = router.route(line, 'stderr');
    expect(routed.diagnostics).toEqual([]);
    expect(routed.lines).toEqual([{ source: 'build', line }]);
    expect(routed.unreadable).toBe(GCC_JSON_UNREADABLE); // said: the diagnostics it may hold are not reported
  });
});

describe('gcc JSON lines of more diagnostics than are read', () => {
  test.each([
    ['too many children', JSON.stringify([{ kind: 'warning', children: [...Array.from({ length: SERVICE_BOUNDS.diagnosticChildren }, () => ({ kind: 'note' })), { kind: 'error', message: 'last' }] }]), 2], // the warning and its error; its notes stay its children
    ['too many diagnostics', JSON.stringify([...Array.from({ length: SERVICE_BOUNDS.diagnosticsPerJsonLine }, () => ({ kind: 'warning' })), { kind: 'error', message: 'last' }]), SERVICE_BOUNDS.diagnosticsPerJsonLine],
  ])('%s: read up to the bound, the error kept first, the one left out said', (_name, line, read) => {
    expect(parseGccJsonLine(line, ctx)).toBeNull(); // not of the declared shape as a whole
    const routed = new BuildOutputRouter({ startDir: ctx.cwd, root: ctx.root, regions: ctx.regions }).route(line, 'stderr');
    expect(routed.diagnostics[0]).toMatchObject({ severity: 'error', message: 'last' });
    expect(routed.diagnostics.filter((d) => d.severity !== 'note')).toHaveLength(read);
    expect(routed.cut).toMatch(/its errors first \(1 error\(s\)\), 1 other\(s\) not reported$/);
  });
});

describe('gcc JSON lines of the declared shape', () => {
  test('nesting up to the bound is read, with every level typed', () => {
    const diags = parseGccJsonLine(JSON.stringify([nested(SERVICE_BOUNDS.diagnosticDepth)]), ctx)!;
    expect(diags).toHaveLength(1);
    let d = diags[0]!;
    for (let i = 0; i < SERVICE_BOUNDS.diagnosticDepth; i++) d = d.children[0]!;
    expect(d).toMatchObject({ severity: 'note', message: 'leaf', file: null, line: null, children: [] });
  });

  test('unknown fields are ignored, known ones mapped to the tree', () => {
    const line = JSON.stringify([
      {
        kind: 'warning',
        message: 'unused variable',
        option: '-Wunused-variable',
        option_url: 'https://gcc.gnu.org/',
        'column-origin': 1,
        locations: [{ caret: { file: 'module.c', line: 4, 'display-column': 7, 'byte-column': 7, column: 7 }, finish: { file: 'module.c', line: 4, column: 12 } }],
        children: [],
        'escape-source': false,
      },
    ]);
    expect(parseGccJsonLine(line, ctx)).toEqual([
      { severity: 'warning', message: 'unused variable', option: '-Wunused-variable', line: 4, column: 7, endLine: 4, endColumn: 12, children: [], file: 'MAA_mod/module.c', protectedRegion: null },
    ]);
  });
});
