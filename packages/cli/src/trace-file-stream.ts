/**
 * A trace file (`*.jsonl`: `contract run --trace`, `contract trace --format json`, `contract
 * simulate --trace`) read as a stream of records for `contract trace FILE.jsonl`: in chunks, line
 * by line, each line read by the build service's trace-file reader (recordOfJsonLine: written back
 * as the runtime's CSV line and read with the CSV reader's checks). The records are told in the
 * file's order, the order its writer gave them (time order). The file is hostile: a line longer
 * than a record's (MAX_JSON_LINE_CHARS) is skipped up to its end, never held, and named; with no
 * line end in MAX_SKIP_BYTES (a sparse file of a terabyte) the rest of the file is left out, said.
 */
import { promises as fsp } from 'node:fs';
import { StringDecoder } from 'node:string_decoder';
import { MAX_JSON_LINE_CHARS, recordOfJsonLine, type TraceRecord } from '@contract-studio/build-service/trace';
import { CHUNK_BYTES, MAX_SKIP_BYTES } from './trace-stream.js';

/** Records of a trace file in batches (one batch a chunk read), until the file's size when opened. */
export async function* traceFileBatches(handle: fsp.FileHandle, name: string, chunkBytes = CHUNK_BYTES): AsyncGenerator<TraceRecord[]> {
    const size = (await handle.stat()).size;
    const decoder = new StringDecoder('utf8');
    const buffer = Buffer.alloc(chunkBytes);
    let partial = '';
    /** The current line is past the bound: its characters are dropped up to its newline. */
    let skipping = false;
    let lineNo = 0;
    let read = 0;
    /** Characters dropped of the line being skipped. */
    let dropped = 0;
    /** The record that stands for a line no record can be (`head`: its first characters), at line `at`. */
    const noRecord = (at: number, reason: string, head: string): TraceRecord => ({ kind: 'unknown', file: name, line: at, reason, text: head.slice(0, 200) });
    const tooLong = `longer than ${MAX_JSON_LINE_CHARS} characters`;
    const recordOf = (line: string, out: TraceRecord[]) => {
        lineNo++;
        const r = recordOfJsonLine(name, lineNo, line.endsWith('\r') ? line.slice(0, -1) : line);
        if (r) out.push(r);
    };
    while (read < size) {
        const { bytesRead } = await handle.read(buffer, 0, Math.min(chunkBytes, size - read), read);
        if (bytesRead === 0) break;
        read += bytesRead;
        const text = decoder.write(buffer.subarray(0, bytesRead));
        const out: TraceRecord[] = [];
        let pos = 0;
        for (let nl = text.indexOf('\n'); nl >= 0; nl = text.indexOf('\n', pos)) {
            if (skipping) {
                out.push(noRecord(++lineNo, tooLong, partial));
                skipping = false;
                dropped = 0;
                partial = '';
            } else {
                recordOf(partial + text.slice(pos, nl), out);
                partial = '';
            }
            pos = nl + 1;
        }
        if (!skipping) {
            partial += text.slice(pos);
            if (partial.length > MAX_JSON_LINE_CHARS) {
                skipping = true;
                dropped = partial.length;
                partial = partial.slice(0, 200);
            }
        } else dropped += text.length - pos;
        if (skipping && dropped > MAX_SKIP_BYTES) {
            out.push(noRecord(lineNo + 1, `no line end in ${MAX_SKIP_BYTES / 1024 / 1024} MiB: the rest of the file (${size - read} bytes) left out`, partial));
            yield out;
            return;
        }
        if (out.length) yield out;
    }
    const rest = partial + decoder.end();
    if (skipping) yield [noRecord(lineNo + 1, tooLong, partial)];
    else if (rest) {
        const out: TraceRecord[] = [];
        recordOf(rest, out);
        if (out.length) yield out;
    }
}
