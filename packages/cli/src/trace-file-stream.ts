/**
 * A trace file (`*.jsonl`: `contract run --trace`, `contract trace --format json`, `contract
 * simulate --trace`) read as a stream of records for `contract trace FILE.jsonl`: in chunks, line
 * by line, each line read by the build service's trace-file reader (traceFileItemOfJsonLine: written back
 * as the runtime's CSV line and read with the CSV reader's checks). The records are told in the
 * file's order, the order its writer gave them (time order). The file is hostile: a line longer
 * than a record's (MAX_JSON_LINE_CHARS) is skipped up to its end, never held, and named; with no
 * line end in MAX_SKIP_BYTES (a sparse file of a terabyte) the rest of the file is left out, said
 * (the lines: bounded-lines.ts, as for the CSV logs).
 */
import type { promises as fsp } from 'node:fs';
import { LogClocks, MAX_JSON_LINE_CHARS, isLauncherLine, traceFileItemOfJsonLine, unendedLine, type LauncherLineItem, type TraceRecord } from '@contract-studio/build-service/trace';
import { boundedLines, CHUNK_BYTES, MAX_SKIP_BYTES } from './bounded-lines.js';

/** Records of a trace file in batches (one batch a chunk read), until the file's size when opened; the launcher's end lines (`launcher_line`) among them, in the file's order. */
export async function* traceFileBatches(handle: fsp.FileHandle, name: string, chunkBytes = CHUNK_BYTES): AsyncGenerator<(TraceRecord | LauncherLineItem)[]> {
    const size = (await handle.stat()).size;
    let lineNo = 0;
    /** Each module's time check (its records come in the file's order). */
    const clocks = new LogClocks();
    /** The record that stands for a line no record can be (`head`: its first characters). */
    const noRecord = (reason: string, head: string): TraceRecord => ({ kind: 'unknown', file: name, line: lineNo, reason, text: head.slice(0, 200) });
    // a line of MAX_JSON_LINE_CHARS and its `\r` is whole: its reader takes the `\r` off
    for await (const lines of boundedLines(handle, size, { maxChars: MAX_JSON_LINE_CHARS + 1, chunkBytes })) {
        const out: (TraceRecord | LauncherLineItem)[] = [];
        for (const l of lines) {
            lineNo++;
            if (typeof l === 'string' || l.kind === 'line') {
                const text = typeof l === 'string' ? l : l.text;
                const r = traceFileItemOfJsonLine(name, lineNo, text.endsWith('\r') ? text.slice(0, -1) : text, clocks);
                // a launcher line is whole JSON even with no line end after it: taken as it is
                if (r) out.push(typeof l === 'string' || isLauncherLine(r) ? r : unendedLine(r));
            } else if (l.kind === 'overLong') {
                const r = noRecord(`longer than ${MAX_JSON_LINE_CHARS} characters`, l.head);
                out.push(l.unended ? unendedLine(r) : r);
            }
            else out.push(noRecord(`no line end in ${MAX_SKIP_BYTES / 1024 / 1024} MiB: the rest of the file (${l.leftBytes} bytes) left out`, l.head));
        }
        if (out.length) yield out;
    }
}
