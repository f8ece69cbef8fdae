/**
 * The node side of the run-time trace (docs/runtime-api.md "Trace records"): which files of a
 * log folder are CSV logs, records as JSON lines (trace-stream.ts reads a folder), and the
 * trace file's opening for writing (`--trace`: never through a link).
 * The parsing itself is the browser-safe reader of @contract-studio/build-service/trace.
 */
import { closeSync, constants, openSync, promises as fsp, writeSync } from 'node:fs';
import type { FileHandle } from 'node:fs/promises';
import type { TraceRecord } from '@contract-studio/build-service/trace';
import { escapeControls } from './terminal-text.js';

/**
 * A record as one JSON line, spelled as `contract trace --format json` prints it: DEL, C1 and the
 * bidi and line-separator characters, which JSON.stringify leaves raw, written `\uXXXX` (the same
 * JSON; a `cat` of a trace file does not act on them), so a `--trace` file is byte for byte that output.
 */
export function jsonLine(r: TraceRecord): string {
    return escapeControls(JSON.stringify(r));
}

/** One JSON object per line, in order. */
export function toJsonLines(records: TraceRecord[]): string {
    return records.map(jsonLine).join('\n') + (records.length ? '\n' : '');
}

/** Flags of a trace file opened for writing: created or truncated, never through a link found there. */
const TRACE_FILE_FLAGS = constants.O_WRONLY | constants.O_CREAT | constants.O_TRUNC | constants.O_NOFOLLOW;

/** ELOOP said as what it is: a link where the trace file goes (`--trace` never writes through one). */
export function traceFileError(e: unknown): Error {
    const code = (e as NodeJS.ErrnoException).code;
    return code === 'ELOOP' ? new Error('it is a symbolic link: a trace file is never written through a link (remove it, or name another file)') : (e as Error);
}

/** Opens a trace file for writing (TRACE_FILE_FLAGS); a link there is said so (traceFileError). */
export async function openTraceFile(path: string): Promise<FileHandle> {
    try {
        return await fsp.open(path, TRACE_FILE_FLAGS, 0o644);
    } catch (e) {
        throw traceFileError(e);
    }
}

/** Writes a whole trace file at once, with openTraceFile's rules. */
export function writeTraceFileSync(path: string, text: string): void {
    let fd: number;
    try {
        fd = openSync(path, TRACE_FILE_FLAGS, 0o644);
    } catch (e) {
        throw traceFileError(e);
    }
    try {
        writeSync(fd, text);
    } finally {
        closeSync(fd);
    }
}
