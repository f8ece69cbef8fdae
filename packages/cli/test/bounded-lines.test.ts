/**
 * bounded-lines.ts, the one line reader of `contract trace` (CSV logs and trace files): lines
 * across chunk ends and multi-byte characters cut by them, a line longer than the bound given
 * once as its head at its end, a line with no end left out past the skip bound with the bytes
 * not read, nothing past the size the file had when opened.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { open } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { boundedLines, type BoundedLine, type BoundedLinesOptions } from '../src/bounded-lines.js';

const dir = mkdtempSync(join(tmpdir(), 'bounded-lines-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

async function linesOf(text: string | Buffer, opts: BoundedLinesOptions, size?: number): Promise<{ items: BoundedLine[]; batches: number }> {
    const path = join(dir, 'f');
    writeFileSync(path, text);
    const handle = await open(path, 'r');
    try {
        const items: BoundedLine[] = [];
        let batches = 0;
        for await (const batch of boundedLines(handle, size ?? (await handle.stat()).size, opts)) {
            expect(batch.length).toBeGreaterThan(0);
            items.push(...batch);
            batches++;
        }
        return { items, batches };
    } finally {
        await handle.close();
    }
}

describe('boundedLines', () => {
    it('gives every line whole (its text) whatever the chunk size, multi-byte characters cut by a chunk end included, the last one without its newline as a line with no end', async () => {
        const text = 'première ligne\nzwei ✓ drei\n\nπ∑ last';
        for (const chunkBytes of [1, 2, 3, 5, 7, 64]) {
            const { items } = await linesOf(text, { maxChars: 100, chunkBytes });
            // the last one, with no line end, is said to have none (a writer stopped mid-line)
            expect(items, `chunk ${chunkBytes}`).toEqual(['première ligne', 'zwei ✓ drei', '', { kind: 'line', text: 'π∑ last', unended: true }]);
        }
    });

    it('a line longer than maxChars before its end is given once, at its end, as its first maxChars + 1 characters; the next lines follow', async () => {
        const { items } = await linesOf(`a\n${'x'.repeat(50)}\nb\n${'y'.repeat(30)}`, { maxChars: 10, chunkBytes: 4 });
        expect(items).toEqual([
            'a',
            { kind: 'overLong', head: 'x'.repeat(11) },
            'b',
            { kind: 'overLong', head: 'y'.repeat(11), unended: true },
        ]);
        // whole in one chunk too: a long line is never given whole (its pieces would keep it, or the chunk, alive)
        expect((await linesOf(`${'z'.repeat(50)}\n`, { maxChars: 10, chunkBytes: 1024 })).items).toEqual([{ kind: 'overLong', head: 'z'.repeat(11) }]);
        // a line of maxChars characters is whole, in bytes of any length (3 a character), cut by chunks anywhere
        for (const chunkBytes of [1, 2, 5, 31, 32, 33, 1024]) {
            expect((await linesOf(`${'€'.repeat(10)}\n${'€'.repeat(11)}\n${'€'.repeat(12)}`, { maxChars: 10, chunkBytes })).items, `chunk ${chunkBytes}`).toEqual([
                '€'.repeat(10),
                { kind: 'overLong', head: '€'.repeat(11) },
                { kind: 'overLong', head: '€'.repeat(11), unended: true },
            ]);
        }
    });

    it('no line end in maxSkipBytes: the last item says how many bytes were not read', async () => {
        const { items } = await linesOf(Buffer.concat([Buffer.from('ok\n'), Buffer.alloc(10_000)]), { maxChars: 10, chunkBytes: 100, maxSkipBytes: 1000 });
        expect(items[0]).toEqual('ok');
        expect(items).toHaveLength(2);
        const last = items[1] as Extract<BoundedLine, { kind: 'noEnd' }>;
        expect(last.kind).toBe('noEnd');
        expect(last.head).toHaveLength(11);
        // 11 chunks of 100 bytes read: 1097 characters of the line (> 1000)
        expect(last.leftBytes).toBe(10_003 - 1100);
    });

    it('gives a chunk of many lines in batches of at most batchLines lines, about batchChars characters (their records are made a batch at a time)', async () => {
        const lines = Array.from({ length: 100 }, (_, i) => `line ${String(i).padStart(2, '0')}`); // 7 characters each
        const text = lines.join('\n') + '\n';
        const byLines = await linesOf(text, { maxChars: 100, chunkBytes: 1 << 20, batchLines: 10 });
        expect(byLines.items).toEqual(lines);
        expect(byLines.batches).toBe(10);
        const byChars = await linesOf(text, { maxChars: 100, chunkBytes: 1 << 20, batchChars: 70 });
        expect(byChars.items).toEqual(lines);
        expect(byChars.batches).toBe(10);
    });

    it('reads no further than the size given (the size a growing file had when opened)', async () => {
        const { items } = await linesOf('one\ntwo\n', { maxChars: 100, chunkBytes: 2 }, 4);
        expect(items).toEqual(['one']);
        expect((await linesOf('', { maxChars: 100, chunkBytes: 2 })).items).toEqual([]);
    });
});
