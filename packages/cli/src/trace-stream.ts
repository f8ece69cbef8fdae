/**
 * A recorded run's trace read as a stream (`contract trace`): the CSV logs of a folder, read in
 * chunks and merged in time order as parseTrace orders them (mono_ns, then file name, then line),
 * holding a bounded window of records per file instead of the whole run: a 1 kHz schema writes
 * about 1.5 MB of logs a second, so a run of minutes is gigabytes.
 *
 * A module writes its log in time order; a record further than its file's window from its place
 * (a hostile or clock-stepped line) is told where the window lets it, and counted. A window holds
 * WINDOW records, and no more than WINDOW_CHARS characters of their lines: memory is bounded
 * whatever the lines' length (a record keeps only its own line: bounded-lines.ts).
 */
import { constants, promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { CSV_HEADER, MinHeap, isLogFileName, isLogHeaderIn, countRecord, endedOnItsOwn, launcherLineJson, type LauncherLinesQueue, type RecordCounts, type TraceRecord, type TraceRecordBase } from '@contract-studio/build-service/trace';
import { CHUNK_BYTES } from './bounded-lines.js';
import { LogRecords, LogWindow } from './log-window.js';
import { JsonLines } from './record-json.js';
import { safeName } from './terminal-text.js';

/** Records held per file to put slightly out-of-order lines in place (fewer when there are more than 64 files). */
export const WINDOW = 4096;
/** Records held in all files' windows. */
const HELD_RECORDS = 262_144;
/**
 * Characters of lines held per record of a window, on average: a window of WINDOW records holds
 * at most WINDOW * LINE_CHARS_HELD characters (512 Ki: 4,096 records of the runtime's lines,
 * which are 80 to 110 characters on average, 170 at most in a tutorial run; 128 of the longest
 * lines a record may have). All windows together: 32 Mi characters at most, whatever the lines.
 */
export const LINE_CHARS_HELD = 128;
/** Characters of lines held in one window (of WINDOW records). */
export const WINDOW_CHARS = WINDOW * LINE_CHARS_HELD;

/** Records held per file when `files` logs are read together: WINDOW, fewer past 64 files. */
export function windowFor(files: number): number {
    return Math.min(WINDOW, Math.max(64, Math.floor(HELD_RECORDS / Math.max(1, files))));
}

/** Bytes read from a log at a time when `files` logs are read together (a buffer each): 1 MiB, less past 16 files (16 MiB in all; 64 KiB at least). */
export function chunkFor(files: number): number {
    return Math.min(CHUNK_BYTES, Math.max(64 * 1024, Math.floor((16 * CHUNK_BYTES) / Math.max(1, files))));
}
/** A run writes one log per module; a folder with more is not a run's (each log holds a descriptor while read). */
export const MAX_LOG_FILES = 1024;

export interface OpenLog {
    name: string;
    handle: fsp.FileHandle;
    /** The size seen when opened: what is read (a log still growing cannot make the read endless). */
    size: number;
    /** Its first line is not the runtime's header: no log, refused whole by its reader (log-window.ts), and no module's second log. */
    notALog?: true;
}

/** Whether an open file's first line is something else than the runtime's header (an empty file is not refused: it holds nothing). */
async function beginsOtherwise(handle: fsp.FileHandle, size: number): Promise<boolean> {
    if (size === 0) return false;
    const buf = Buffer.alloc(CSV_HEADER.length + 2);
    const { bytesRead } = await handle.read(buf, 0, buf.length, 0).catch(() => ({ bytesRead: 0 }));
    const head = buf.toString('latin1', 0, bytesRead);
    const nl = head.indexOf('\n');
    return !isLogHeaderIn(head, 0, nl < 0 ? head.length : nl) || (nl < 0 && bytesRead === buf.length);
}

/** What a file that is not a regular file is, for the warning that leaves it out. */
function kindOf(st: { isFIFO(): boolean; isSocket(): boolean; isCharacterDevice(): boolean; isBlockDevice(): boolean; isDirectory(): boolean }): string {
    if (st.isFIFO()) return 'a FIFO';
    if (st.isSocket()) return 'a socket';
    if (st.isCharacterDevice() || st.isBlockDevice()) return 'a device';
    if (st.isDirectory()) return 'a folder';
    return 'not a regular file';
}

/**
 * The CSV logs of `dir` (those named in `only` when given), opened (regular files only; never
 * through a link), or an error message. A file named like a log that is not read — a symbolic
 * link, a FIFO, socket or device (never waited on), one that cannot be opened — is left out and
 * said in `skipped` (`NAME: why`); the others are read. `shownAs`: the folder as the user wrote it
 * (the messages name it so).
 */
export async function openLogFolder(dir: string, only?: readonly string[], skipped: string[] = [], shownAs = dir): Promise<OpenLog[] | string> {
    let names: string[];
    try {
        names = (await fsp.readdir(dir)).filter((n) => isLogFileName(n) && (!only || only.includes(n))).sort();
    } catch (e) {
        return `cannot read the log folder ${safeName(shownAs)}: ${(e as Error).message.replace(dir, shownAs)}`;
    }
    if (names.length === 0) {
        // a project folder given for its logs folder: say where `contract run` wrote them
        const logs = await fsp.stat(join(dir, 'logs')).then((st) => st.isDirectory(), () => false);
        return `no CSV log (*.csv) in ${safeName(shownAs)}${logs ? `; its logs/ folder (where contract run writes a run's logs) may hold them: contract trace ${safeName(join(shownAs, 'logs'))}` : ''}`;
    }
    if (names.length > MAX_LOG_FILES) return `${safeName(shownAs)} holds ${names.length} CSV logs: more than the ${MAX_LOG_FILES} read at once (a run writes one per module); give the folder of one run`;
    const logs: OpenLog[] = [];
    for (const name of names) {
        let handle: fsp.FileHandle;
        try {
            // O_NONBLOCK: a FIFO named like a log must not wait for a writer for ever (it is left out below)
            handle = await fsp.open(join(dir, name), constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
        } catch (e) {
            const code = (e as NodeJS.ErrnoException).code;
            skipped.push(code === 'ELOOP' ? `${name}: a symbolic link, not read (logs are never read through a link)` : `${name}: cannot be opened (${code ?? (e as Error).message})`);
            continue;
        }
        const st = await handle.stat().catch(() => undefined);
        if (!st?.isFile()) {
            await handle.close().catch(() => {});
            skipped.push(`${name}: ${st ? kindOf(st) : 'cannot be read'}, not read`);
            continue;
        }
        logs.push((await beginsOtherwise(handle, st.size)) ? { name, handle, size: st.size, notALog: true } : { name, handle, size: st.size });
    }
    if (logs.length === 0) return `no readable CSV log in ${safeName(dir)}`;
    return logs;
}

export async function closeLogs(logs: readonly OpenLog[]): Promise<void> {
    await Promise.all(logs.map((l) => l.handle.close().catch(() => {})));
}

export interface TraceStream {
    /** The records in time order, in batches. */
    batches: AsyncGenerator<TraceRecord[]>;
    /** Records told later than their time (further than the window from their place), once the stream ended. */
    outOfOrder(): number;
    /** What was left out of the logs, and why (a file's rest with no line end). */
    problems(): string[];
}

/** Records handed on at a time. */
const BATCH = 1024;

/**
 * The records of `logs` in time order (files in name order break ties), read `window` records
 * (and `window * LINE_CHARS_HELD` characters of lines at most) ahead per file.
 */
export function streamTrace(logs: readonly OpenLog[], { window = windowFor(logs.length), chunkBytes = chunkFor(logs.length) } = {}): TraceStream {
    const sorted = [...logs].sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
    const windows = sorted.map((log, i) => new LogWindow(new LogRecords(log, chunkBytes), i, window, window * LINE_CHARS_HELD));
    async function* batches(): AsyncGenerator<TraceRecord[]> {
        for (const w of windows) await w.fill();
        const files = new MinHeap<LogWindow>((f, g) => f.before(g));
        for (const w of windows) if (w.length) files.push(w);
        let batch: TraceRecord[] = [];
        while (files.size) {
            const w = files.peek()!;
            batch.push(w.take());
            if (w.topUp()) await w.fill();
            if (w.length) files.topChanged();
            else files.pop();
            if (batch.length >= BATCH) {
                yield batch;
                batch = [];
            }
        }
        if (batch.length) yield batch;
    }
    return { batches: batches(), outOfOrder: () => windows.reduce((n, w) => n + w.outOfOrder, 0), problems: () => windows.flatMap((w) => w.problems) };
}

/** JSON lines are handed on in pieces of about this many bytes. */
export const PIECE_BYTES = 256 * 1024;

/**
 * The records of `logs` as JSON lines (one object per record, time order: `contract trace
 * --format json`), handed to `sink` in pieces of whole lines (UTF-8 bytes, record-json.ts), each
 * awaited; a sink answering false stops the read. `observe` sees each record as it is written
 * (another reader of the same pass: `contract run`'s schema figures). Returns the records handed
 * on (readable ones, and unreadable lines apart: countRecord) and those told later than their time.
 * `launcher`: the logs folder's launcher end lines (its contract-launch.log), each that says a
 * module ended on its own (endedOnItsOwn: a signal the launcher did not send, an exit with a
 * status; not the end of every module at the run's stop, which its exit record says) written as a
 * `launcher_line` object before the first record of a later time (the rest after the last record).
 */
export async function jsonLinesOf(logs: readonly OpenLog[], sink: (piece: Buffer) => Promise<boolean | void> | boolean | void, observe?: (r: TraceRecord) => void, launcher?: LauncherLinesQueue): Promise<{ counts: RecordCounts; outOfOrder: number; problems: string[] }> {
    const stream = streamTrace(logs);
    const counts: RecordCounts = { records: 0, unreadable: 0 };
    const lines = new JsonLines(PIECE_BYTES + 64 * 1024);
    for await (const batch of stream.batches) {
        for (const r of batch) {
            if (launcher && r.kind !== 'unknown') for (const l of launcher.before((r as TraceRecordBase).monoNs)) if (endedOnItsOwn(l.how)) lines.add(launcherLineJson(l));
            lines.add(r);
            countRecord(counts, r);
            observe?.(r);
        }
        if (lines.length >= PIECE_BYTES) {
            const go = await sink(lines.take());
            if (go === false) return { counts, outOfOrder: stream.outOfOrder(), problems: stream.problems() };
        }
    }
    for (const l of launcher?.rest() ?? []) if (endedOnItsOwn(l.how)) lines.add(launcherLineJson(l));
    if (lines.length) await sink(lines.take());
    return { counts, outOfOrder: stream.outOfOrder(), problems: stream.problems() };
}
