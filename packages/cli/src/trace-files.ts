/**
 * The node side of the run-time trace (docs/runtime-api.md "Trace records"): which files of a
 * log folder are CSV logs, and writing records as JSON lines (trace-stream.ts reads a folder).
 * The parsing itself is the browser-safe reader of @contract-studio/build-service/trace.
 */
import { constants, promises as fsp } from 'node:fs';
import type { TraceRecord } from '@contract-studio/build-service/trace';

/** `<MODULE>_<date>.csv`, as runtime/src/csvlog.c names them. */
export const LOG_FILE_NAME = /^[A-Za-z_]\w*_[\w.-]*\.csv$/;

/** One JSON object per line, in order. */
export function toJsonLines(records: TraceRecord[]): string {
    return records.map((r) => JSON.stringify(r)).join('\n') + (records.length ? '\n' : '');
}

/** Writes `text` to `path` (created or truncated), never through a link found there. */
export async function writeNoFollow(path: string, text: string): Promise<void> {
    const handle = await fsp.open(path, constants.O_WRONLY | constants.O_CREAT | constants.O_TRUNC | constants.O_NOFOLLOW, 0o644);
    try {
        await handle.writeFile(text);
    } finally {
        await handle.close();
    }
}
