/**
 * Past its kept-output cap a build's stream is still read for the lines the diagnostics reader
 * needs (gcc's JSON lines, make's directory lines), whole up to their own bound, at any chunking;
 * every other line is dropped as it goes, and none of them reaches the kept log.
 */
import fc from 'fast-check';
import { describe, expect, test } from 'vitest';
import { CUT_LINE, LineSplitter } from './line-splitter.js';

const JSON_LINE = (n: number) => `[{"kind": "warning", "message": "w${n}", "pad": "${'x'.repeat(100)}"}]`;

function read(text: string, cuts: number[], maxBytes: number, bound = 1 << 20): { kept: string[]; pastCap: string[] } {
  const kept: string[] = [];
  const pastCap: string[] = [];
  const s = new LineSplitter({
    maxBytes,
    onLine: (l) => kept.push(l),
    onTruncated: () => {},
    pastCap: { wanted: (head) => head.startsWith('[{"kind"') || head.startsWith('make: Entering'), boundOf: () => bound, onLine: (l) => pastCap.push(l) },
  });
  const buf = Buffer.from(text);
  let at = 0;
  for (const c of cuts) {
    s.push(buf.subarray(at, Math.min(buf.length, at + c)));
    at = Math.min(buf.length, at + c);
  }
  s.push(buf.subarray(at));
  s.end();
  return { kept, pastCap };
}

describe('LineSplitter past its cap (pastCap)', () => {
  const text = ['cc -c a.c', JSON_LINE(1), 'cc -c b.c', "make: Entering directory '/work/src-gen/generated/architecture/modules/MAB_mod'", 'x'.repeat(5000), JSON_LINE(2), 'tail'].join('\n') + '\n';

  test('the gcc JSON line the cap cuts and those after it are read whole, at any chunking; other lines are dropped; the log keeps only what is under the cap', () => {
    fc.assert(
      fc.property(fc.array(fc.nat(300)), (cuts) => {
        const { kept, pastCap } = read(text, cuts, 40); // the cap cuts the first JSON line
        expect(kept).toEqual(['cc -c a.c']);
        expect(pastCap).toEqual([JSON_LINE(1), "make: Entering directory '/work/src-gen/generated/architecture/modules/MAB_mod'", JSON_LINE(2)]);
      }),
    );
  });

  test('an ordinary line the cap cuts is kept as cut (as without pastCap); a wanted line past its own bound is given as its head', () => {
    const { kept, pastCap } = read(text, [], 5, 50);
    expect(kept).toEqual([`cc -c${CUT_LINE}`]);
    expect(pastCap).toEqual([JSON_LINE(1).slice(0, 50), "make: Entering directory '/work/src-gen/generated/", JSON_LINE(2).slice(0, 50)]);
  });

  test('without pastCap nothing past the cap is read (as before)', () => {
    const kept: string[] = [];
    const s = new LineSplitter({ maxBytes: 40, onLine: (l) => kept.push(l), onTruncated: () => {} });
    s.push(Buffer.from(text));
    s.end();
    expect(kept).toEqual(['cc -c a.c', `${JSON_LINE(1).slice(0, 30)}${CUT_LINE}`]);
  });
});
