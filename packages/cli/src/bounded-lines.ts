/**
 * The lines of a file `contract trace` reads (a run's CSV log, a trace file), which may be
 * hostile: read in chunks up to the size it had when opened (a log still growing cannot make the
 * read endless). A line of at most `maxChars` characters is given whole; a longer one is never
 * held: it is given once, at its end, as its head (`overLong`), its rest dropped as it is read.
 * With no line end in `maxSkipBytes` the rest of the file is left out: the last item is then
 * `noEnd`, which stands for that line too. Both readers of trace-stream.ts (logs) and
 * trace-file-stream.ts (trace files) use it, each making its own records of the lines.
 *
 * Each line is decoded (UTF-8) on its own from the bytes read, never cut out of a string of the
 * whole chunk: V8 makes a piece of a string (slice, split) a view that keeps the whole string
 * alive, so a record held for the merge, or a name the story keeps, would keep its chunk (1 MiB)
 * with it: an attacker's long lines made the memory grow with the logs' size.
 */
import type { promises as fsp } from 'node:fs';
import { StringDecoder } from 'node:string_decoder';

/** A line with no end past this many bytes ends the read of its file (a sparse file of a terabyte). */
export const MAX_SKIP_BYTES = 64 * 1024 * 1024;
/** Bytes read from a file at a time. */
export const CHUNK_BYTES = 1 << 20;
/** Lines given at a time at most, and characters of them (a chunk is given in batches: their records are made a batch at a time). */
export const BATCH_LINES = 1024;
export const BATCH_CHARS = 64 * 1024;

export type BoundedLine =
    /** A whole line of at most maxChars characters, without its '\n' (the common line: a string, no object made for it). */
    | string
    /** The file's last line, whole, with no '\n' after it. */
    | { kind: 'line'; text: string; unended: true }
    /** A line longer than maxChars: its first maxChars + 1 characters (`unended` as for a line). */
    | { kind: 'overLong'; head: string; unended?: boolean }
    /** The last item: no line end in maxSkipBytes after this line began (its head), `leftBytes` not read. */
    | { kind: 'noEnd'; head: string; leftBytes: number };

export interface BoundedLinesOptions {
    /** The longest line given whole. */
    maxChars: number;
    chunkBytes?: number;
    maxSkipBytes?: number;
    batchLines?: number;
    batchChars?: number;
}

/**
 * The lines of `handle` up to `size` bytes, in batches of at most batchLines lines and about
 * batchChars characters (one line more at most; a chunk inside a long line gives none).
 */
export async function* boundedLines(handle: fsp.FileHandle, size: number, { maxChars, chunkBytes = CHUNK_BYTES, maxSkipBytes = MAX_SKIP_BYTES, batchLines = BATCH_LINES, batchChars = BATCH_CHARS }: BoundedLinesOptions): AsyncGenerator<BoundedLine[]> {
    const buffer = Buffer.allocUnsafe(Math.max(1, Math.min(chunkBytes, size)));
    /**
     * Bytes enough for maxChars + 1 characters (a UTF-16 unit takes 3 bytes at most) and a
     * character cut at their end: a line with more bytes is longer than maxChars.
     */
    const holdBytes = 3 * (maxChars + 1) + 3;
    /** The start of the line being read, from earlier chunks (copied: the buffer is read into again), at most holdBytes + 1 bytes. */
    let carry: Buffer[] = [];
    let carryBytes = 0;
    /** The head of the line being read once it is past maxChars: its bytes are then dropped up to its end. */
    let skipped: string | undefined;
    /** Bytes of the line being skipped read so far. */
    let lineBytes = 0;
    let read = 0;
    /** maxChars + 1 characters of a line (`bytes`: its first holdBytes bytes or more; a character they cut is left out). */
    const headOf = (bytes: Buffer): string => new StringDecoder('utf8').write(bytes.subarray(0, holdBytes)).slice(0, maxChars + 1);
    /** The line of `bytes` (all of it), whole or its head. */
    const lineOf = (bytes: Buffer, from: number, to: number): string | { kind: 'overLong'; head: string } => {
        if (to - from > holdBytes) return { kind: 'overLong', head: headOf(bytes.subarray(from, to)) };
        const text = bytes.toString('utf8', from, to);
        return text.length > maxChars ? { kind: 'overLong', head: text.slice(0, maxChars + 1) } : text;
    };
    /** The line ending at chunk[0, end) after the carried bytes (or the skipped head). */
    const endLine = (chunk: Buffer, end: number): BoundedLine => {
        if (skipped !== undefined) return { kind: 'overLong', head: skipped };
        const take = Math.min(end, holdBytes + 1 - carryBytes);
        const bytes = Buffer.concat([...carry, chunk.subarray(0, Math.max(0, take))]);
        return carryBytes + end > holdBytes ? { kind: 'overLong', head: headOf(bytes) } : lineOf(bytes, 0, bytes.length);
    };
    let out: BoundedLine[] = [];
    /** Characters of the lines in `out`. */
    let outChars = 0;
    while (read < size) {
        const { bytesRead } = await handle.read(buffer, 0, Math.min(buffer.length, size - read), read);
        if (bytesRead === 0) break;
        read += bytesRead;
        const chunk = buffer.subarray(0, bytesRead);
        let pos = 0;
        for (let nl = chunk.indexOf(10); nl >= 0; nl = chunk.indexOf(10, pos)) {
            let line: BoundedLine;
            if (pos === 0 && (carryBytes > 0 || skipped !== undefined)) {
                line = endLine(chunk, nl);
                carry = [];
                carryBytes = 0;
                skipped = undefined;
            } else line = lineOf(chunk, pos, nl);
            out.push(line);
            outChars += typeof line === 'string' ? line.length : line.kind === 'line' ? line.text.length : line.head.length;
            pos = nl + 1;
            if (out.length >= batchLines || outChars >= batchChars) {
                yield out;
                out = [];
                outChars = 0;
            }
        }
        // the rest of the chunk begins a line (or goes on with one)
        if (pos < bytesRead) {
            if (skipped !== undefined) lineBytes += bytesRead - pos;
            else {
                const keep = Math.min(bytesRead - pos, holdBytes + 1 - carryBytes);
                if (keep > 0) carry.push(Buffer.from(chunk.subarray(pos, pos + keep)));
                lineBytes = carryBytes + bytesRead - pos;
                carryBytes += keep;
                if (carryBytes > holdBytes) {
                    skipped = headOf(Buffer.concat(carry));
                    carry = [];
                    carryBytes = 0;
                }
            }
        }
        if (skipped !== undefined && lineBytes > maxSkipBytes) {
            out.push({ kind: 'noEnd', head: skipped, leftBytes: size - read });
            yield out;
            return;
        }
        if (out.length) {
            yield out;
            out = [];
            outChars = 0;
        }
    }
    if (skipped !== undefined) yield [{ kind: 'overLong', head: skipped, unended: true }];
    else if (carryBytes) {
        const bytes = Buffer.concat(carry);
        const line = lineOf(bytes, 0, bytes.length);
        yield [typeof line === 'string' ? { kind: 'line', text: line, unended: true } : { ...line, unended: true }];
    }
}
