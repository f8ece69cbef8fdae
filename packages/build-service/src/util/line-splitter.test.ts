import fc from 'fast-check';
import { describe, expect, test } from 'vitest';
import { CUT_LINE, LineSplitter } from './line-splitter.js';

function split(chunks: Buffer[], maxBytes = 1 << 20, maxLineBytes?: number): { lines: string[]; truncatedAt: number | null } {
  const lines: string[] = [];
  let truncatedAt: number | null = null;
  const s = new LineSplitter({ maxBytes, maxLineBytes, onLine: (l) => lines.push(l), onTruncated: (n) => (truncatedAt = n) });
  for (const c of chunks) s.push(c);
  s.end();
  return { lines, truncatedAt };
}

describe('LineSplitter', () => {
  test('any chunking of a text gives the same lines as splitting it at once', () => {
    fc.assert(
      fc.property(fc.array(fc.constantFrom('a', 'b', '\n', 'é', ' '), { maxLength: 200 }), fc.array(fc.nat(10)), (chars, cuts) => {
        const text = chars.join('');
        const buf = Buffer.from(text);
        const chunks: Buffer[] = [];
        let at = 0;
        for (const c of cuts) {
          chunks.push(buf.subarray(at, Math.min(buf.length, at + c)));
          at = Math.min(buf.length, at + c);
        }
        chunks.push(buf.subarray(at));
        const expected = text === '' ? [] : (text.endsWith('\n') ? text.slice(0, -1) : text).split('\n');
        expect(split(chunks).lines).toEqual(expected);
      }),
    );
  });

  test('stops at maxBytes, reports the truncation once, keeps draining', () => {
    const { lines, truncatedAt } = split([Buffer.from('12345\n67'), Buffer.from('890\nabc\n'), Buffer.from('more\n')], 10);
    expect(lines).toEqual(['12345', `6789${CUT_LINE}`]); // the cut line is said cut: '6789' is not a line of the output
    expect(truncatedAt).toBe(10);
    // a bound on a line's end cuts no line
    expect(split([Buffer.from('12345\n6789\nabc\n')], 11).lines).toEqual(['12345', '6789']);
  });

  test('splits overlong lines and strips CR', () => {
    expect(split([Buffer.from('abcdefg\r\nxy\r\n')], 100, 3).lines).toEqual(['abc', 'def', 'g', 'xy']);
  });
});
