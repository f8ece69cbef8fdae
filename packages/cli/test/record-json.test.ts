/**
 * Trace records written as JSON lines straight into bytes (record-json.ts) are byte for byte the
 * general path, escapeControls(JSON.stringify(record)): `contract trace --format json`, the live
 * `--trace` writer and the check that settles the file all write through it, and a file settled
 * against logs must not differ from what was written live by a byte. Hostile field contents:
 * quotes, backslashes, every control, DEL and C1, non-ASCII, U+2028/2029, bidi marks, lone
 * surrogates (a trace file's `\ud800` read back), fields around the length where the copy changes
 * method, very long ones.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import fc from 'fast-check';
import { afterEach, describe, expect, it } from 'vitest';
import { CSV_HEADER, csvField, parseRecordLine } from '@contract-studio/build-service/trace';
import { JsonLines, recordJson } from '../src/record-json.js';
import { escapeControls } from '../src/terminal-text.js';
import { jsonLine, toJsonLines } from '../src/trace-files.js';
import { closeLogs, jsonLinesOf, openLogFolder, streamTrace } from '../src/trace-stream.js';

/** The general path every writer must equal. */
const general = (r: object): string => escapeControls(JSON.stringify(r));

/** Strings a hostile log or trace file may hold. */
const HOSTILE = [
    '', 'plain', 'a "quoted" word', 'back\\slash', '\\', '"', '\\"', 'tab\there', 'new\nline', 'cr\rend', '\x00\x01\x07\x08\x0b\x0c\x1b[2J\x1f',
    'DEL\x7f', 'C1 \x80\x85\x9b\x9f', 'é à ü', '日本語', '😀 emoji', 'line\u2028sep\u2029para', 'bidi \u202e evil \u2066\u2069 \u200e\u200f\u061c',
    'lone \ud800 high', 'lone \udfff low', '\udc00\ud800 reversed pair', 'ends with a high \ud83d', '\u00a0nbsp \ufeffbom \ufffd',
    'x'.repeat(39), 'x'.repeat(40), 'x'.repeat(41), `${'y'.repeat(39)}"`, `${'y'.repeat(40)}\\`, `"${'y'.repeat(40)}`, `${'z'.repeat(45)}\x7f`, `${'z'.repeat(45)}\u2028`,
    'w'.repeat(200_000), `${'w'.repeat(200_000)}\x1b`, `\u202e${'w'.repeat(100_000)}`,
];

describe('record JSON', () => {
    it('a record of any hostile strings, numbers and nesting is written as escapeControls(JSON.stringify(record))', () => {
        for (const s of HOSTILE) {
            const r = { kind: 'user', monoNs: '1', wallTime: s, module: 'M', peer: s, port: null, size: 0, detail: s, fields: { event: s, [s]: s } };
            expect(jsonLine(r as never)).toBe(general(r));
        }
        const odd = {
            kind: 'x', n: [0, -0, 1, -1, 1.5, -2.25e-7, 1e21, 123456789012345, 2 ** 53, 2 ** 53 + 2, Number.MAX_VALUE, NaN, Infinity, -Infinity],
            b: [true, false, null], nested: { a: [[], {}, [{ 'k"ey': 'v\\' }]], u: undefined, f: () => 1, s: Symbol('s') }, arr: [undefined, () => 1],
            10: 'integer key first', '2': 'and in order', [Symbol('hidden')]: 1,
        };
        expect(recordJson(odd)).toBe(general(odd));
        const proto = Object.assign(Object.create(null), { a: 'no prototype' }) as object;
        expect(recordJson(proto)).toBe(general(proto));
    });

    it('a value that is not plain data goes the general way (toJSON, a Date, a boxed value, a class), a bigint throws as JSON.stringify throws', () => {
        class Point { constructor(readonly x = 1) {} }
        for (const r of [{ d: new Date(0) }, { t: { toJSON: (k: string) => `key ${k}` } }, { n: Object(5) as object }, { s: Object('é') as object }, { p: new Point() }, { m: new Map([[1, 2]]) }]) {
            expect(recordJson(r)).toBe(general(r));
        }
        expect(() => recordJson({ big: 1n })).toThrow(TypeError);
        expect(recordJson({ after: 'a throw leaves nothing behind' })).toBe('{"after":"a throw leaves nothing behind"}');
    });

    it('any strings (fast-check, full Unicode and lone surrogates) in records, one at a time and as lines, give the general path\'s bytes', () => {
        const str = fc.oneof(fc.string({ unit: 'binary' }), fc.string({ unit: 'grapheme' }), fc.string({ minLength: 30, maxLength: 60, unit: fc.constantFrom('a', '"', '\\', '\x7f', '\u2028', '\ud800', 'é', ' ') }));
        const rec = fc.record({ kind: str, monoNs: str, detail: str, port: fc.option(fc.integer(), { nil: null }), size: fc.double(), fields: fc.dictionary(str, fc.oneof(str, fc.integer(), fc.boolean())) });
        fc.assert(fc.property(fc.array(rec, { maxLength: 8 }), (records) => {
            const lines = new JsonLines(16);
            for (const r of records) lines.add(r);
            const want = records.map((r) => general(r) + '\n').join('');
            expect(lines.take().equals(Buffer.from(want, 'utf8'))).toBe(true);
            expect(toJsonLines(records as never)).toBe(want);
        }), { numRuns: 300 });
    });

    describe('a log folder', () => {
        const dirs: string[] = [];
        afterEach(() => {
            for (const d of dirs.splice(0)) rmSync(d, { recursive: true, force: true });
        });

        it('jsonLinesOf gives the bytes of the general path for every record of hostile logs (quoted fields, controls, non-ASCII, long details, unreadable lines)', async () => {
            const dir = mkdtempSync(join(tmpdir(), 'contract-record-json-'));
            dirs.push(dir);
            const lines = [CSV_HEADER];
            HOSTILE.forEach((s, i) => {
                const detail = s.replace(/[\ud800-\udfff]/g, '?'); // a log is UTF-8: no lone surrogate in it
                lines.push(`${1000 + i},2026-12-07T05:34:39.684061Z,MAA,${i % 2 ? 'gripper_closed' : 'error'},${csvField(detail.slice(0, 50))},${i % 3 ? '' : 2},${i},${csvField(detail)}`);
                lines.push(`${1000 + i},2026-12-07T05:34:39.684061Z,MAA,sup_rule,,,0,${csvField(`f.r active cause=MAB:2 value="${detail.slice(0, 80)}"`)}`);
                lines.push(`not a record ${detail.slice(0, 300).replace(/[\r\n]/g, ' ')}`);
            });
            writeFileSync(join(dir, 'MAA_7-Dec-2026-05h34m39s.csv'), `${lines.join('\n')}\n1,w,MAA,error,,,0,a last line cut \u202e`);
            const logs = await openLogFolder(dir);
            if (typeof logs === 'string') throw new Error(logs);
            try {
                const pieces: Buffer[] = [];
                const { counts } = await jsonLinesOf(logs, (piece) => void pieces.push(piece));
                let want = '';
                for await (const batch of streamTrace(logs).batches) for (const r of batch) want += general(r) + '\n';
                expect(counts.records + counts.unreadable).toBe(3 * HOSTILE.length + 1);
                expect(Buffer.concat(pieces).equals(Buffer.from(want, 'utf8'))).toBe(true);
            } finally {
                await closeLogs(logs);
            }
        });
    });

    it('a parsed record of a runtime line is one line of JSON', () => {
        const r = parseRecordLine('MAA_1.csv', 1, '2000,2026-12-07T05:34:39.684061Z,MAA,priority_changed,SUP,,0,"nice 17 (priority 10, was 40)"');
        expect(jsonLine(r)).toBe(general(r));
        expect(jsonLine(r)).toContain('"detail":"nice 17 (priority 10, was 40)"');
    });
});
