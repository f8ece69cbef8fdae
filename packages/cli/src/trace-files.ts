/**
 * The node side of the run-time trace (docs/runtime-api.md "Trace records"): which files of a
 * log folder are CSV logs, and records as JSON lines (trace-stream.ts reads a folder).
 * The parsing itself is the browser-safe reader of @contract-studio/build-service/trace.
 */
import type { TraceRecord } from '@contract-studio/build-service/trace';

/** `<MODULE>_<date>.csv`, as runtime/src/csvlog.c names them. */
export const LOG_FILE_NAME = /^[A-Za-z_]\w*_[\w.-]*\.csv$/;

/** One JSON object per line, in order. */
export function toJsonLines(records: TraceRecord[]): string {
    return records.map((r) => JSON.stringify(r)).join('\n') + (records.length ? '\n' : '');
}
