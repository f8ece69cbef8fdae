/**
 * A link error missing a function that the project defines only in src-gen/orphans/ (a helper
 * written outside the protected regions, moved aside by generate) names that copy and the way
 * back (orphan-hints.ts): definitions found as written (`{` on the line or the next), not
 * declarations, calls or keywords; ld's line with or without a place; hostile text stays bounded.
 */
import { describe, expect, test } from 'vitest';
import { parseLinkerLine } from './ld-text.js';
import { orphanedDefinitions, withOrphanHint } from './orphan-hints.js';

const ORPHAN = 'src-gen/orphans/generated/architecture/modules/CTL_mod/module.c';
const files = new Map<string, Buffer>([
  [ORPHAN, Buffer.from([
    '/* Orphaned user code of ... */',
    'double clamp(double v, double lo, double hi)',
    '{',
    '    if (v < lo) return lo;',
    '    return v > hi ? hi : v;',
    '}',
    'static inline int *pick(int *a) { return a; }',
    'double declared_only(double v);',
    '    } else if (x) {',
    '',
  ].join('\n'))],
  // not an orphan: the generated tree itself, and a file of the project elsewhere
  ['src-gen/generated/architecture/modules/CTL_mod/module.c', Buffer.from('int generated_fn(void) {\n}\n')],
  ['notes.c', Buffer.from('int notes_fn(void) {\n}\n')],
]);

describe('orphanedDefinitions + withOrphanHint', () => {
  const defs = orphanedDefinitions(files);

  test('finds the definitions of the orphans copies only', () => {
    expect([...defs.keys()].sort()).toEqual(['clamp', 'pick']);
    expect(defs.get('clamp')).toEqual([ORPHAN]);
  });

  test('ld\'s undefined reference, in either quoting, with or without a place, gets the hint', () => {
    const ctx = { cwd: '/work/src-gen/generated/architecture/modules/CTL_mod', root: '/work/src-gen', regions: new Map(), orphanedDefinitions: defs };
    for (const line of [
      "/usr/bin/ld: /work/src-gen/generated/architecture/modules/CTL_mod/module.c:250: undefined reference to `clamp'",
      '/usr/bin/ld: module.o:module.c:(.text+0x16): undefined reference to ‘clamp’',
    ]) {
      const parsed = parseLinkerLine(line, ctx);
      expect(parsed?.kind).toBe('diagnostic');
      const message = parsed?.kind === 'diagnostic' ? parsed.diagnostic.message : '';
      expect(message).toContain(`\`clamp\` is defined in ${ORPHAN}, where \`contract generate\` moved code written outside the protected regions`);
    }
    expect(withOrphanHint("undefined reference to `declared_only'", defs)).toBe("undefined reference to `declared_only'");
    expect(withOrphanHint("multiple definition of `clamp'", defs)).toBe("multiple definition of `clamp'");
    expect(withOrphanHint("undefined reference to `clamp'", undefined)).toBe("undefined reference to `clamp'");
  });

  test('hostile orphans: long lines and many words are skipped quickly, never thrown on', () => {
    const hostile = new Map([[`${ORPHAN}.2.c`, Buffer.from(`${'a '.repeat(200_000)}\n${'int x'.repeat(50)}(\n${'*'.repeat(400)} f() {\n`)]]);
    const t0 = Date.now();
    expect(() => orphanedDefinitions(hostile)).not.toThrow();
    expect(Date.now() - t0).toBeLessThan(2000);
  });
});
