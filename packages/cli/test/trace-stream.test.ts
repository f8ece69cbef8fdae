/** `contract trace` reads a run as a stream: the same records in the same order as parseTrace, in bounded memory. */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import fc from 'fast-check';
import { afterEach, describe, expect, it } from 'vitest';
import { CSV_HEADER, MAX_LINE_CHARS, parseLogFile, parseTrace, type LogFile, type TraceRecord, type TraceRecordBase } from '@contract-studio/build-service/trace';
import { closeLogs, openLogFolder, streamTrace } from '../src/trace-stream.js';

const dirs: string[] = [];
afterEach(() => {
    for (const d of dirs.splice(0)) rmSync(d, { recursive: true, force: true });
});

async function streamed(files: LogFile[], opts: { window?: number; chunkBytes?: number }): Promise<{ records: TraceRecord[]; late: number }> {
    const dir = mkdtempSync(join(tmpdir(), 'contract-trace-stream-'));
    dirs.push(dir);
    for (const f of files) writeFileSync(join(dir, f.name), f.text);
    const logs = await openLogFolder(dir);
    if (typeof logs === 'string') throw new Error(logs);
    try {
        const stream = streamTrace(logs, opts);
        const records: TraceRecord[] = [];
        for await (const batch of stream.batches) records.push(...batch);
        return { records, late: stream.outOfOrder() };
    } finally {
        await closeLogs(logs);
    }
}

describe('streamed trace', () => {
    it('gives parseTrace\'s records in its order: times out of order within the window, ties, bad lines, chunks cut anywhere (multi-byte characters too)', async () => {
        const line = fc.oneof(
            { arbitrary: fc.constant('bad'), weight: 2 },
            { arbitrary: fc.constant('x'.repeat(MAX_LINE_CHARS + 10)), weight: 1 }, // longer than a record: skipped across chunks
            { arbitrary: fc.tuple(fc.integer({ min: 0, max: 40 }), fc.constantFrom('A', 'B'), fc.constantFrom('d', 'é', '😀', '')).map(([t, m, d]) => `${t},w,${m},error,,,0,${d}${t}`), weight: 20 },
        );
        const file = fc.tuple(fc.constantFrom('A_1.csv', 'B_1.csv', 'C_1.csv'), fc.array(line, { maxLength: 25 }), fc.boolean())
            .map(([name, lines, lastNewline]) => ({ name, text: [CSV_HEADER, ...lines].join('\n') + (lastNewline ? '\n' : '') }));
        const files = fc.uniqueArray(file, { minLength: 1, maxLength: 3, selector: (f) => f.name });
        await fc.assert(fc.asyncProperty(files, fc.integer({ min: 1, max: 64 }), async (fs, chunkBytes) => {
            // a window as long as a file: every record in its place, as parseTrace's sort puts it
            const { records, late } = await streamed(fs, { window: 32, chunkBytes });
            expect(records).toEqual(parseTrace(fs));
            expect(late).toBe(0);
        }), { numRuns: 150 });
    });

    it('a window of any size holds a file\'s next records in time order, and the merge tells the first of all windows: as a plain model of it does (records far out of order, ties, a window going round many times)', async () => {
        /** The merge as the windows are meant to make it: each an array of a file's next `window` records, a record put after those of its time or earlier. */
        const model = (fs: LogFile[], window: number): { records: TraceRecord[]; late: number } => {
            const files = [...fs].sort((a, b) => (a.name < b.name ? -1 : 1)).map((f) => {
                let key = 0n;
                return parseLogFile(f).map((record) => {
                    if (record.kind !== 'unknown') key = BigInt((record as TraceRecordBase).monoNs);
                    return { key, record };
                });
            });
            const held = files.map(() => [] as { key: bigint; record: TraceRecord }[]);
            const fill = (f: number) => {
                while (held[f]!.length < window && files[f]!.length) {
                    const r = files[f]!.shift()!;
                    const at = held[f]!.findIndex((h) => h.key > r.key);
                    held[f]!.splice(at < 0 ? held[f]!.length : at, 0, r);
                }
            };
            files.forEach((_, f) => fill(f));
            const records: TraceRecord[] = [];
            const lastOut = files.map((): bigint | undefined => undefined);
            let late = 0;
            for (;;) {
                let first = -1;
                held.forEach((h, f) => {
                    if (h.length && (first < 0 || h[0]!.key < held[first]![0]!.key)) first = f;
                });
                if (first < 0) return { records, late };
                const { key, record } = held[first]!.shift()!;
                if (lastOut[first] !== undefined && key < lastOut[first]!) late++;
                else lastOut[first] = key;
                records.push(record);
                fill(first);
            }
        };
        const line = fc.oneof(
            { arbitrary: fc.constant('bad'), weight: 1 },
            { arbitrary: fc.tuple(fc.integer({ min: 0, max: 900 }), fc.constantFrom('A', 'B')).map(([t, m]) => `${t},w,${m},error,,,0,d${t}`), weight: 10 },
        );
        const file = fc.tuple(fc.constantFrom('A_1.csv', 'B_1.csv', 'C_1.csv'), fc.array(line, { maxLength: 60 }))
            .map(([name, lines]) => ({ name, text: [CSV_HEADER, ...lines].join('\n') + '\n' }));
        const files = fc.uniqueArray(file, { minLength: 1, maxLength: 3, selector: (f) => f.name });
        await fc.assert(fc.asyncProperty(files, fc.integer({ min: 1, max: 7 }), async (fs, window) => {
            expect(await streamed(fs, { window, chunkBytes: 97 })).toEqual(model(fs, window));
        }), { numRuns: 150 });
    });

    it('orders times past 2^53 exactly (a machine up for 105 days: a double would take them for equal), up to a 64-bit time', async () => {
        const times = ['9007199254740993', '9007199254740992', '9223372036854775807', '9223372036854775806', '000000000000000000001'.slice(1)];
        const files = times.map((t, i) => ({ name: `${'ABCDE'[i]}_1.csv`, text: `${CSV_HEADER}\n${t},w,${'ABCDE'[i]},error,,,0,t${i}\n` }));
        const { records } = await streamed(files, {});
        expect(records.map((r) => (r as TraceRecordBase).monoNs)).toEqual(['00000000000000000001', '9007199254740992', '9007199254740993', '9223372036854775806', '9223372036854775807']);
        expect(records).toEqual(parseTrace(files));
    });

    it('a record further out of order than the window is told later than its time, and counted', async () => {
        const rows = [CSV_HEADER];
        for (let i = 1; i <= 20; i++) rows.push(`${i * 10},w,ORD,error,,,0,e${i}`);
        rows.push('5,w,ORD,error,,,0,early'); // belongs first; 20 records from its place
        const { records, late } = await streamed([{ name: 'ORD_1.csv', text: rows.join('\n') + '\n' }], { window: 4 });
        expect(late).toBe(1);
        // told as soon as it is read into the window (the 4 records after e17), not at its time
        const e = (from: number, to: number) => Array.from({ length: to - from + 1 }, (_, i) => `e${from + i}`);
        expect(records.map((r) => (r as { detail: string }).detail)).toEqual([...e(1, 17), 'early', ...e(18, 20)]);
        // within the window it is put in its place
        const wide = await streamed([{ name: 'ORD_1.csv', text: rows.join('\n') + '\n' }], { window: 32 });
        expect(wide.late).toBe(0);
        expect((wide.records[0] as { detail: string }).detail).toBe('early');
    });

    it('a line with no end (megabytes without a newline) is one unreadable record, the lines after it keep their numbers', async () => {
        const text = [CSV_HEADER, '1,w,SUP,error,,,0,before', 'y'.repeat(3_000_000), '2,w,SUP,error,,,0,after'].join('\n') + '\n';
        const { records } = await streamed([{ name: 'SUP_1.csv', text }], { chunkBytes: 65_536 });
        expect(records.map((r) => r.kind)).toEqual(['error', 'unknown', 'error']);
        expect(records[1]).toMatchObject({ line: 3, reason: `line longer than ${MAX_LINE_CHARS} characters` });
        expect(records).toEqual(parseTrace([{ name: 'SUP_1.csv', text }]));
    });
});
