import { describe, expect, test } from 'vitest';
import fc from 'fast-check';
import { decodeTraceRecords, encodeTraceRecords, forEachTraceLine, TraceWireError, type TraceLine } from './wire.js';

/** Record lines as the tail hands them: any text without a newline, files interleaved, lines anywhere. */
const lineArb: fc.Arbitrary<TraceLine> = fc.record({
  file: fc.constantFrom('ORD_1.csv', 'MAA_1.csv', 'SUP_1.csv', 'a,b "c".csv'),
  line: fc.integer({ min: 1, max: 1_000_000 }),
  text: fc.string({ unit: 'grapheme', maxLength: 60 }).map((t) => t.replace(/\n/g, ' ')),
}).chain((l) => fc.boolean().map((cut): TraceLine => (cut && l.line % 7 === 0 ? { ...l, cut: true as const } : l)))
  // now and then an entry standing for lines the service counted without sending them (its text empty)
  .chain((l) => fc.integer({ min: 0, max: 30 }).map((n): TraceLine => (n > 0 && l.line % 5 === 0 && !l.cut ? { file: l.file, line: l.line, text: '', unsent: n } : l)));

describe('trace wire form', () => {
  test('decode(encode(records)) is the records, in order (any texts, files, line numbers)', () => {
    fc.assert(
      fc.property(fc.array(lineArb, { maxLength: 200 }), (records) => {
        const wire = encodeTraceRecords(records);
        expect(decodeTraceRecords(JSON.parse(JSON.stringify(wire)))).toEqual(records);
        // the same records as ranges of the batch's text, in order, one text for all
        const ranged: TraceLine[] = [];
        const texts = new Set<string>();
        forEachTraceLine(wire, (file, line, text, from, to, cut, unsent) => {
          texts.add(text);
          const l: TraceLine = { file, line, text: text.slice(from, to) };
          if (cut) l.cut = true;
          if (unsent) l.unsent = unsent;
          ranged.push(l);
        });
        expect(ranged).toEqual(records);
        expect(texts.size).toBeLessThanOrEqual(1);
      }),
      { numRuns: 500 },
    );
  });

  test('consecutive lines of one file are one run; each file is named once', () => {
    const r = (file: string, line: number): TraceLine => ({ file, line, text: `${file}:${line}` });
    const wire = encodeTraceRecords([r('A.csv', 2), r('A.csv', 3), r('A.csv', 4), r('B.csv', 7), r('A.csv', 5), r('A.csv', 9), r('', 1)]);
    expect(wire.files).toEqual(['A.csv', 'B.csv', '']);
    expect(wire.runs).toEqual([0, 2, 3, 1, 7, 1, 0, 5, 1, 0, 9, 1, 2, 1, 1]);
    expect(wire.text.split('\n')).toHaveLength(7);
    expect(encodeTraceRecords([])).toEqual({ files: [], runs: [], text: '' });
    // a record cut at its log's end (its module killed inside it) is named by its index
    const cut = encodeTraceRecords([r('A.csv', 2), { ...r('A.csv', 3), cut: true }, r('B.csv', 9)]);
    expect(cut.cut).toEqual([1]);
    expect(decodeTraceRecords(cut)[1]).toEqual({ file: 'A.csv', line: 3, text: 'A.csv:3', cut: true });
    expect(decodeTraceRecords({ files: [], runs: [], text: '' })).toEqual([]);
    // an entry standing for unsent lines: named with its count; the line after it starts a run of its own
    const skipped = encodeTraceRecords([r('A.csv', 2), { file: 'A.csv', line: 3, text: '', unsent: 40 }, r('A.csv', 43), r('A.csv', 44)]);
    expect(skipped.unsent).toEqual([1, 40]);
    expect(skipped.runs).toEqual([0, 2, 2, 0, 43, 2]);
    expect(decodeTraceRecords(skipped)).toEqual([r('A.csv', 2), { file: 'A.csv', line: 3, text: '', unsent: 40 }, r('A.csv', 43), r('A.csv', 44)]);
    // empty texts survive (the count, not the text, says how many lines)
    const blanks = [r('A.csv', 2), { file: 'A.csv', line: 3, text: '' }, { file: 'A.csv', line: 4, text: '' }];
    expect(decodeTraceRecords(encodeTraceRecords(blanks))).toEqual(blanks);
  });

  test.each([
    ['not an object', null, /not an object/],
    ['files not strings', { files: [1], runs: [], text: '' }, /"files"/],
    ['runs not triples', { files: ['A'], runs: [0, 1], text: 'x' }, /triples/],
    ['a file index out of the list', { files: ['A'], runs: [1, 1, 1], text: 'x' }, /names no listed file/],
    ['a negative index', { files: ['A'], runs: [-1, 1, 1], text: 'x' }, /names no listed file/],
    ['line 0', { files: ['A'], runs: [0, 0, 1], text: 'x' }, /starts at line 0/],
    ['a zero count', { files: ['A'], runs: [0, 1, 0], text: '' }, /counts 0 records/],
    ['a fractional count', { files: ['A'], runs: [0, 1, 1.5], text: 'x' }, /counts 1.5 records/],
    ['more lines than counted', { files: ['A'], runs: [0, 1, 1], text: 'x\ny' }, /count 1 records, the text holds 2 lines/],
    ['fewer lines than counted', { files: ['A'], runs: [0, 1, 3], text: 'x\ny' }, /count 3 records, the text holds 2 lines/],
    ['text without records', { files: [], runs: [], text: 'x' }, /text without records/],
    ['the old object form', { records: [{ file: 'A', line: 1, text: 'x' }] }, /"files"/],
    ['cut not a list', { files: ['A'], runs: [0, 1, 2], text: 'x\ny', cut: 1 }, /"cut"/],
    ['cut past the records', { files: ['A'], runs: [0, 1, 2], text: 'x\ny', cut: [2] }, /"cut"/],
    ['cut not ascending', { files: ['A'], runs: [0, 1, 2], text: 'x\ny', cut: [1, 0] }, /"cut"/],
    ['cut twice', { files: ['A'], runs: [0, 1, 2], text: 'x\ny', cut: [1, 1] }, /"cut"/],
    ['unsent not pairs', { files: ['A'], runs: [0, 1, 2], text: 'x\n', unsent: [1] }, /"unsent"/],
    ['unsent past the records', { files: ['A'], runs: [0, 1, 2], text: 'x\n', unsent: [2, 5] }, /"unsent"/],
    ['unsent counting 0 lines', { files: ['A'], runs: [0, 1, 2], text: 'x\n', unsent: [1, 0] }, /"unsent"/],
    ['unsent not ascending', { files: ['A'], runs: [0, 1, 2], text: '\n', unsent: [1, 3, 0, 2] }, /"unsent"/],
  ])('a malformed batch (%s) is refused with a clear error, nothing decoded', (_name, wire, message) => {
    const got: unknown[] = [];
    expect(() => got.push(...decodeTraceRecords(wire))).toThrow(TraceWireError);
    expect(() => decodeTraceRecords(wire)).toThrow(message);
    expect(got).toEqual([]);
  });
});
