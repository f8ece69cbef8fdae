/**
 * The node side of the run-time trace (docs/runtime-api.md "Trace records"): which files of a
 * log folder are CSV logs, records as JSON lines (trace-stream.ts reads a folder), and the
 * trace file's opening for writing (`--trace`: never through a link).
 * The parsing itself is the browser-safe reader of @contract-studio/build-service/trace.
 */
import { closeSync, constants, openSync, promises as fsp, readFileSync, readSync, unlinkSync, writeSync } from 'node:fs';
import { basename } from 'node:path';
import { pidAlive } from '@contract-studio/codegen/stale-temp';
import type { FileHandle } from 'node:fs/promises';
import type { TraceRecord } from '@contract-studio/build-service/trace';
import { safeName as safeNameOf } from './terminal-text.js';
import { recordJson, recordsJson } from './record-json.js';

/**
 * A record as one JSON line, spelled as `contract trace --format json` prints it: DEL, C1 and the
 * bidi and line-separator characters, which JSON.stringify leaves raw, written `\uXXXX` (the same
 * JSON; a `cat` of a trace file does not act on them), so a `--trace` file is byte for byte that
 * output: `escapeControls(JSON.stringify(r))`, written in one pass (record-json.ts).
 */
export function jsonLine(r: TraceRecord): string {
    return recordJson(r);
}

/** One JSON object per line, in order (jsonLine's, each ended by its newline). */
export function toJsonLines(records: TraceRecord[]): string {
    return recordsJson(records);
}

/**
 * Why `--trace FILE` is refused before anything is built or run, or undefined: a trace file is
 * named `*.jsonl` (as `contract trace` reads only those), so that a slip of the name (`--trace
 * model.contract`) never overwrites a file that is not a trace.
 */
export function traceNameProblem(file: string): string | undefined {
    if (file.endsWith('.jsonl') && basename(file) !== '.jsonl') return undefined; // as contract trace reads them: .JSONL is not one
    return `--trace ${safeNameOf(file)}: a trace file is named *.jsonl (e.g. --trace run.jsonl): it is created or emptied, and only such a name is taken, so that no other file is overwritten`;
}

/**
 * Flags of a trace file opened for writing: created if missing, never through a link found
 * there, never waiting on a FIFO (non-blocking: with no reader the open fails at once, ENXIO);
 * not truncated by the opening (the caller empties it when it writes the first record: a build
 * that fails leaves an earlier trace as it was).
 */
const TRACE_FILE_FLAGS = constants.O_WRONLY | constants.O_CREAT | constants.O_NOFOLLOW | constants.O_NONBLOCK;

/** The opening's errors said as what they are: a link, a FIFO, a folder where the trace file goes. */
export function traceFileError(e: unknown): Error {
    const code = (e as NodeJS.ErrnoException).code;
    if (code === 'ELOOP') return new Error('it is a symbolic link: a trace file is never written through a link (remove it, or name another file)');
    if (code === 'ENXIO') return new Error('it is a FIFO: a trace file is a regular file (remove it, or name another file)');
    if (code === 'EISDIR') return new Error('it is a folder: name a file in it (e.g. run.jsonl)');
    return e as Error;
}

/** What a path found open is, when it is not a regular file (the trace is never written into one). */
function notRegular(kind: { isFIFO(): boolean; isDirectory(): boolean; isFile(): boolean }): Error | undefined {
    if (kind.isFile()) return undefined;
    return new Error(kind.isFIFO() ? 'it is a FIFO: a trace file is a regular file (remove it, or name another file)' : 'it is not a regular file (a device or a socket): name another file');
}

/**
 * Opens a trace file for writing (TRACE_FILE_FLAGS: not emptied; `empty: true` empties it at
 * once). A link, a FIFO, a folder or any other file that is not a regular one is refused with
 * what it is (traceFileError).
 */
export async function openTraceFile(path: string, opts: { empty?: boolean } = {}): Promise<FileHandle> {
    let handle: FileHandle;
    try {
        handle = await fsp.open(path, TRACE_FILE_FLAGS, 0o644);
    } catch (e) {
        throw traceFileError(e);
    }
    try {
        const bad = notRegular(await handle.stat());
        if (bad) throw bad;
        if (opts.empty) await handle.truncate(0);
        return handle;
    } catch (e) {
        await handle.close().catch(() => {});
        throw e;
    }
}

/** How many attempts at a trace file's writer lock (a dead writer's lock removed in between). */
const LOCK_TRIES = 3;

/**
 * One writer of a trace file at a time: `FILE.writing` beside it, created exclusively (never
 * through a link), holding the writer's pid, removed when it is done (two `contract run --trace
 * run.jsonl` at once mixed their records in one file, a line cut, and both said it was whole).
 * Another live writer's lock refuses this one, saying whose; a dead writer's is taken over.
 * The release.
 */
export function lockTraceFile(path: string): () => void {
    const lock = `${path}.writing`;
    for (let attempt = 0; attempt < LOCK_TRIES; attempt++) {
        let fd: number;
        try {
            fd = openSync(lock, constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW, 0o644);
        } catch (e) {
            if ((e as NodeJS.ErrnoException).code !== 'EEXIST') throw e;
            let holder = NaN;
            try {
                const rfd = openSync(lock, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
                try {
                    const buffer = Buffer.alloc(32);
                    holder = Number(/^(\d{1,10})\n?$/.exec(buffer.subarray(0, readSync(rfd, buffer, 0, 32, 0)).toString('utf8'))?.[1]);
                } finally {
                    closeSync(rfd);
                }
            } catch {
                // a link or unreadable: no writer of ours
            }
            if (Number.isSafeInteger(holder) && holder !== process.pid && pidAlive(holder)) {
                throw new Error(`it is being written by another contract command (pid ${holder}; its lock ${safeNameOf(basename(lock))}): wait for it to end, or name another file`);
            }
            try {
                unlinkSync(lock); // a dead writer's (killed), or garbage
            } catch {
                // removed meanwhile
            }
            continue;
        }
        try {
            writeSync(fd, `${process.pid}\n`);
        } finally {
            closeSync(fd);
        }
        let released = false;
        const release = (): void => {
            if (released) return;
            released = true;
            process.off('exit', release);
            try {
                if (readFileSync(lock, 'utf8') === `${process.pid}\n`) unlinkSync(lock);
            } catch {
                // gone already
            }
        };
        process.once('exit', release); // an interrupted command leaves no lock behind
        return release;
    }
    throw new Error(`its lock ${safeNameOf(basename(lock))} could not be taken`);
}
