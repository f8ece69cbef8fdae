/**
 * The lines of a file `contract trace` reads (a run's CSV log, a trace file), which may be
 * hostile: read in chunks up to the size it had when opened (a log still growing cannot make the
 * read endless), decoded as UTF-8 across chunk ends. A complete line is given whole (its reader
 * bounds it); a line still without its end past `maxChars` is not held: it is given once, at its
 * end, as its head (`overLong`), its rest dropped as it is read. With no line end in
 * `maxSkipBytes` the rest of the file is left out: the last item is then `noEnd`, which stands for
 * that line too. Both readers of trace-stream.ts (logs) and trace-file-stream.ts (trace files)
 * use it, each making its own records of the lines.
 */
import type { promises as fsp } from 'node:fs';
import { StringDecoder } from 'node:string_decoder';

/** A line with no end past this many bytes ends the read of its file (a sparse file of a terabyte). */
export const MAX_SKIP_BYTES = 64 * 1024 * 1024;
/** Bytes read from a file at a time. */
export const CHUNK_BYTES = 1 << 20;

export type BoundedLine =
    /** A whole line, without its '\n'. */
    | { kind: 'line'; text: string }
    /** A line longer than maxChars before its end: its first maxChars + 1 characters. */
    | { kind: 'overLong'; head: string }
    /** The last item: no line end in maxSkipBytes after this line began (its head), `leftBytes` not read. */
    | { kind: 'noEnd'; head: string; leftBytes: number };

export interface BoundedLinesOptions {
    /** The longest line held while its end is looked for. */
    maxChars: number;
    chunkBytes?: number;
    maxSkipBytes?: number;
}

/** The lines of `handle` up to `size` bytes, a batch per chunk read (a chunk inside a long line gives none). */
export async function* boundedLines(handle: fsp.FileHandle, size: number, { maxChars, chunkBytes = CHUNK_BYTES, maxSkipBytes = MAX_SKIP_BYTES }: BoundedLinesOptions): AsyncGenerator<BoundedLine[]> {
    const decoder = new StringDecoder('utf8');
    const buffer = Buffer.allocUnsafe(Math.max(1, Math.min(chunkBytes, size)));
    /** The line read so far (without an end yet); only its head while skipping. */
    let partial = '';
    /** The line being read is past maxChars: its characters are dropped up to its end. */
    let skipping = false;
    /** Characters of the line being skipped read so far. */
    let lineChars = 0;
    let read = 0;
    const overLong = (): BoundedLine => ({ kind: 'overLong', head: partial });
    while (read < size) {
        const { bytesRead } = await handle.read(buffer, 0, Math.min(chunkBytes, size - read), read);
        if (bytesRead === 0) break;
        read += bytesRead;
        const text = decoder.write(buffer.subarray(0, bytesRead));
        const out: BoundedLine[] = [];
        let pos = 0;
        for (let nl = text.indexOf('\n'); nl >= 0; nl = text.indexOf('\n', pos)) {
            out.push(skipping ? overLong() : { kind: 'line', text: partial + text.slice(pos, nl) });
            skipping = false;
            partial = '';
            pos = nl + 1;
        }
        if (skipping) lineChars += text.length - pos;
        else {
            partial += text.slice(pos);
            if (partial.length > maxChars) {
                skipping = true;
                lineChars = partial.length;
                partial = partial.slice(0, maxChars + 1);
            }
        }
        if (skipping && lineChars > maxSkipBytes) {
            out.push({ kind: 'noEnd', head: partial, leftBytes: size - read });
            yield out;
            return;
        }
        if (out.length) yield out;
    }
    const rest = partial + decoder.end();
    if (skipping) yield [overLong()];
    else if (rest) yield [{ kind: 'line', text: rest }];
}
