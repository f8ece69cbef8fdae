/**
 * The node side of the run-time trace (docs/runtime-api.md "Trace records"): which files of a
 * log folder are CSV logs, reading them with bounds, and writing records as JSON lines. The
 * parsing itself is the browser-safe reader of @contract-studio/build-service/trace.
 */
import { constants, promises as fsp } from 'node:fs';
import { join } from 'node:path';
import type { LogFile, TraceRecord } from '@contract-studio/build-service/trace';

/** `<MODULE>_<date>.csv`, as runtime/src/csvlog.c names them. */
export const LOG_FILE_NAME = /^[A-Za-z_]\w*_[\w.-]*\.csv$/;
/** Bigger logs are refused whole rather than read partly (a run's logs are megabytes). */
export const MAX_LOG_BYTES = 256 * 1024 * 1024;

/** The CSV logs of `dir` (regular files only: a FIFO, socket or device is left out; never through a link), or an error message. */
export async function readLogFolder(dir: string): Promise<LogFile[] | string> {
    let names: string[];
    try {
        names = (await fsp.readdir(dir)).filter((n) => LOG_FILE_NAME.test(n)).sort();
    } catch (e) {
        return `cannot read the log folder ${dir}: ${(e as Error).message}`;
    }
    if (names.length === 0) return `no CSV log (<MODULE>_*.csv) in ${dir}`;
    const files: LogFile[] = [];
    let total = 0;
    for (const name of names) {
        let handle;
        try {
            // O_NONBLOCK: a FIFO named like a log must not wait for a writer for ever (it is left out below)
            handle = await fsp.open(join(dir, name), constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
        } catch (e) {
            return `cannot open ${join(dir, name)}: ${(e as Error).message}`;
        }
        try {
            const st = await handle.stat();
            if (!st.isFile()) continue;
            total += st.size;
            if (total > MAX_LOG_BYTES) return `the logs of ${dir} exceed ${MAX_LOG_BYTES / 1024 / 1024} MiB`;
            // the size seen is what is read: a log still growing (a run writing to it) cannot pass the bound
            const bytes = Buffer.alloc(st.size);
            const { bytesRead } = await handle.read(bytes, 0, st.size, 0);
            files.push({ name, text: bytes.toString('utf8', 0, bytesRead) });
        } finally {
            await handle.close();
        }
    }
    return files;
}

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
