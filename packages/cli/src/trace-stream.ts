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
import { LogClock, MAX_LINE_CHARS, MinHeap, isLogFileName, countRecord, type RecordCounts, recordOfLine, unendedLine, type TraceRecord, type TraceRecordBase, type UnknownRecord } from '@contract-studio/build-service/trace';
import { boundedLines, CHUNK_BYTES, MAX_SKIP_BYTES, type BoundedLine } from './bounded-lines.js';
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
        logs.push({ name, handle, size: st.size });
    }
    if (logs.length === 0) return `no readable CSV log in ${safeName(dir)}`;
    return logs;
}

export async function closeLogs(logs: readonly OpenLog[]): Promise<void> {
    await Promise.all(logs.map((l) => l.handle.close().catch(() => {})));
}

interface Keyed {
    key: bigint;
    index: number;
    record: TraceRecord;
    /** Characters of its line (what the record keeps, at most). */
    chars: number;
}

/** One log's records in file order, a batch of lines at a time, each keyed by its time (an unknown line by the time before it). */
class LogRecords {
    private readonly lines: AsyncGenerator<BoundedLine[]>;
    /** What was left out of the file, and why. */
    readonly problems: string[] = [];
    private lineNo = 0;
    private index = 0;
    private lastKey = 0n;
    /** The log's time check (its lines read in file order). */
    private readonly clock = new LogClock();
    private pending: Keyed[] = [];
    private at = 0;
    private ended = false;

    constructor(private readonly log: OpenLog, chunkBytes: number) {
        // a line of MAX_LINE_CHARS and its `\r` is whole: recordOfLine reads it as parseTrace does
        this.lines = boundedLines(log.handle, log.size, { maxChars: MAX_LINE_CHARS + 1, chunkBytes });
    }

    /** The next record; null when the next lines must be read first (`readChunk`), undefined at the end. */
    next(): Keyed | null | undefined {
        if (this.at < this.pending.length) return this.pending[this.at++];
        return this.ended ? undefined : null;
    }

    /** Reads the next batch of lines' records (none at the end of the size seen: then `next` gives undefined). */
    async readChunk(): Promise<void> {
        this.pending = [];
        this.at = 0;
        const batch = await this.lines.next();
        if (batch.done) {
            this.ended = true;
            return;
        }
        for (const l of batch.value) {
            // a line too long is one unreadable record (recordOfLine says why)
            this.line(l.kind === 'line' ? l.text : l.head, l.kind !== 'noEnd' && l.unended === true);
            if (l.kind === 'noEnd')
                this.problems.push(`${this.log.name}: no line end in ${MAX_SKIP_BYTES / 1024 / 1024} MiB after line ${this.lineNo}: the rest of the file (${l.leftBytes} bytes) left out`);
        }
    }

    private line(raw: string, unended: boolean): void {
        const read = recordOfLine(this.log.name, this.lineNo++, raw, this.clock);
        if (!read) return;
        const record = unended ? unendedLine(read) : read;
        if (record.kind !== 'unknown') this.lastKey = BigInt((record as TraceRecordBase).monoNs);
        // what the record keeps: its line, or, a line that is no record, why and its first 200 characters (copies)
        const chars = record.kind === 'unknown' ? (record as UnknownRecord).text.length + (record as UnknownRecord).reason.length : raw.length;
        this.pending.push({ key: this.lastKey, index: this.index++, record, chars });
    }
}

/**
 * One file's window: its next `size` records in order (time, then line), and no more than `chars`
 * characters of their lines (always one record at least). A log is in time order, so a record
 * read almost always goes last; one out of order is put in its place.
 */
class LogWindow {
    /** The records from `head` on (those before it were taken: their places emptied). */
    private held: (Keyed | undefined)[] = [];
    private head = 0;
    /** Characters of the lines of the records held. */
    private heldChars = 0;
    private lastOut: bigint | undefined;
    outOfOrder = 0;

    constructor(
        private readonly records: LogRecords,
        readonly order: number,
        private readonly size: number,
        private readonly chars: number,
    ) {}

    get length(): number {
        return this.held.length - this.head;
    }

    get problems(): readonly string[] {
        return this.records.problems;
    }

    /** Reads records in until the window is full or the file ended. */
    async fill(): Promise<void> {
        while (this.topUp()) await this.records.readChunk();
    }

    /** Reads in the records at hand; true when the file must be read to go on (`fill`). */
    topUp(): boolean {
        while (this.length < this.size && (this.heldChars < this.chars || this.length === 0)) {
            const r = this.records.next();
            if (r === undefined) return false;
            if (r === null) return true;
            this.hold(r);
        }
        return false;
    }

    private hold(r: Keyed): void {
        const held = this.held;
        this.heldChars += r.chars;
        if (this.length === 0 || held[held.length - 1]!.key <= r.key) {
            held.push(r);
            return;
        }
        // after every held record of the same or an earlier time (they came first in the file)
        let lo = this.head;
        let hi = held.length;
        while (lo < hi) {
            const mid = (lo + hi) >>> 1;
            if (held[mid]!.key <= r.key) lo = mid + 1;
            else hi = mid;
        }
        held.splice(lo, 0, r);
    }

    peek(): Keyed | undefined {
        return this.held[this.head];
    }

    /** The first record held (the window then is one short: `fill` it). */
    take(): TraceRecord {
        const k = this.held[this.head]!;
        this.held[this.head++] = undefined; // told: its place no longer keeps it (and its line) until the array is cut
        this.heldChars -= k.chars;
        if (this.head > 4096 && this.head * 2 > this.held.length) {
            this.held = this.held.slice(this.head);
            this.head = 0;
        }
        if (this.lastOut !== undefined && k.key < this.lastOut) this.outOfOrder++;
        else this.lastOut = k.key;
        return k.record;
    }
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
        const files = new MinHeap<LogWindow>((f, g) => {
            const a = f.peek()!;
            const b = g.peek()!;
            return a.key < b.key || (a.key === b.key && f.order < g.order);
        });
        for (const w of windows) if (w.peek()) files.push(w);
        let batch: TraceRecord[] = [];
        while (files.size) {
            const w = files.peek()!;
            batch.push(w.take());
            if (w.topUp()) await w.fill();
            if (w.peek()) files.topChanged();
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
 */
export async function jsonLinesOf(logs: readonly OpenLog[], sink: (piece: Buffer) => Promise<boolean | void> | boolean | void, observe?: (r: TraceRecord) => void): Promise<{ counts: RecordCounts; outOfOrder: number; problems: string[] }> {
    const stream = streamTrace(logs);
    const counts: RecordCounts = { records: 0, unreadable: 0 };
    const lines = new JsonLines(PIECE_BYTES + 64 * 1024);
    for await (const batch of stream.batches) {
        for (const r of batch) {
            lines.add(r);
            countRecord(counts, r);
            observe?.(r);
        }
        if (lines.length >= PIECE_BYTES) {
            const go = await sink(lines.take());
            if (go === false) return { counts, outOfOrder: stream.outOfOrder(), problems: stream.problems() };
        }
    }
    if (lines.length) await sink(lines.take());
    return { counts, outOfOrder: stream.outOfOrder(), problems: stream.problems() };
}
