/**
 * One CSV log of a run read for the time-ordered merge of `contract trace` (trace-stream.ts): its
 * records in file order, a batch of lines at a time (LogRecords), and a bounded window of the next
 * ones in time order (LogWindow) that the merge takes from.
 *
 * A long run is millions of records, each held in a window for thousands of records before it is
 * told: per record nothing is made but the record itself. Its time is kept as two exact numbers
 * (monoKey: mono_ns is past 2^53, a double's exact integers, on a machine up for 105 days) in typed
 * arrays beside it, not as a bigint in an object of its own; the window is a ring of fixed size.
 */
import { MAX_LINE_CHARS, isLogHeaderIn, notALogRecord, NOT_A_LOG_WHY, recordOfLine, unendedLine, LogClock, type TraceRecord, type TraceRecordBase, type UnknownRecord } from '@contract-studio/build-service/trace';
import { safeName } from './terminal-text.js';
import { boundedLines, MAX_SKIP_BYTES, type BoundedLine } from './bounded-lines.js';
import type { OpenLog } from './trace-stream.js';

/** A time's key: mono_ns = hi * 1e9 + lo, both exact (hi below 2^34 for a 64-bit time). */
interface MonoKey {
    hi: number;
    lo: number;
}

/** Puts the key of `mono` (1 to 20 digits, a 64-bit time: the reader checked it) into `key`. */
export function monoKey(mono: string, key: MonoKey): void {
    const split = mono.length - 9;
    let hi = 0;
    let lo = 0;
    for (let i = 0; i < split; i++) hi = hi * 10 + (mono.charCodeAt(i) - 48);
    for (let i = Math.max(0, split); i < mono.length; i++) lo = lo * 10 + (mono.charCodeAt(i) - 48);
    key.hi = hi;
    key.lo = lo;
}

/** One log's records in file order, a batch of lines at a time, each keyed by its time (an unknown line by the time before it). */
export class LogRecords {
    private readonly lines: AsyncGenerator<BoundedLine[]>;
    /** What was left out of the file, and why. */
    readonly problems: string[] = [];
    private lineNo = 0;
    /** The time of the last record read (an unknown line's key). */
    private readonly last: MonoKey = { hi: 0, lo: 0 };
    /** The log's time check (its lines read in file order). */
    private readonly clock = new LogClock();
    /** The batch read and not yet taken (from `at` on): each record, its key and the characters it keeps. */
    readonly records: (TraceRecord | undefined)[] = [];
    readonly hi: number[] = [];
    readonly lo: number[] = [];
    readonly chars: number[] = [];
    at = 0;
    private ended = false;
    /** Its first line is not the runtime's header: no log, refused whole (trace/parse.ts NOT_A_LOG_WHY). */
    private refused = false;

    constructor(private readonly log: OpenLog, chunkBytes: number) {
        // a line of MAX_LINE_CHARS and its `\r` is whole: recordOfLine reads it as parseTrace does
        this.lines = boundedLines(log.handle, log.size, { maxChars: MAX_LINE_CHARS + 1, chunkBytes });
    }

    /** Whether a record is at hand (at `at`); when not, `readChunk` (or the file ended: `done`). */
    get ready(): boolean {
        return this.at < this.records.length;
    }

    get done(): boolean {
        return this.ended && this.at >= this.records.length;
    }

    /** The record at `at` is taken: its place no longer keeps it. */
    taken(): void {
        this.records[this.at++] = undefined;
    }

    /** Reads the next batch of lines' records (none at the end of the size seen: then `done`). */
    async readChunk(): Promise<void> {
        this.records.length = this.hi.length = this.lo.length = this.chars.length = 0;
        this.at = 0;
        // a refused file (no log) is read no further
        const batch = this.refused ? { done: true as const } : await this.lines.next();
        if (batch.done) {
            this.ended = true;
            return;
        }
        for (const l of batch.value) {
            // a line too long is one unreadable record (recordOfLine says why)
            if (typeof l === 'string') {
                this.line(l, false);
                continue;
            }
            this.line(l.kind === 'line' ? l.text : l.head, l.kind !== 'noEnd' && l.unended === true);
            if (l.kind === 'noEnd')
                this.problems.push(`${this.log.name}: no line end in ${MAX_SKIP_BYTES / 1024 / 1024} MiB after line ${this.lineNo}: the rest of the file (${l.leftBytes} bytes) left out`);
        }
    }

    private line(raw: string, unended: boolean): void {
        if (this.refused) return;
        if (this.lineNo === 0 && !isLogHeaderIn(raw)) {
            // no log (a module's code made the file): said once, as one unreadable line, and nothing of it read
            this.refused = true;
            this.lineNo++;
            this.problems.push(`${safeName(this.log.name)}: ${NOT_A_LOG_WHY}`);
            const record = notALogRecord(this.log.name, raw.slice(0, 200));
            this.push(record, record.text.length + record.reason.length);
            return;
        }
        const read = recordOfLine(this.log.name, this.lineNo++, raw, this.clock);
        if (!read) return;
        const record = unended ? unendedLine(read) : read;
        let chars: number;
        if (record.kind === 'unknown') {
            // what it keeps: why, and the line's first 200 characters (copies)
            chars = (record as UnknownRecord).text.length + (record as UnknownRecord).reason.length;
        } else {
            monoKey((record as TraceRecordBase).monoNs, this.last);
            chars = raw.length;
        }
        this.push(record, chars);
    }

    private push(record: TraceRecord, chars: number): void {
        this.records.push(record);
        this.hi.push(this.last.hi);
        this.lo.push(this.last.lo);
        this.chars.push(chars);
    }
}

/**
 * One file's window: its next `size` records in order (time, then line), and no more than `chars`
 * characters of their lines (always one record at least), in a ring of `size` places. A log is in
 * time order, so a record read almost always goes last; one out of order is put in its place.
 */
export class LogWindow {
    private readonly held: (TraceRecord | undefined)[];
    private readonly hi: Float64Array;
    private readonly lo: Float64Array;
    private readonly heldCharsOf: Float64Array;
    /** The ring's first place, and the records held from it on. */
    private head = 0;
    length = 0;
    /** Characters of the lines of the records held. */
    private heldChars = 0;
    /** The key of the last record told in its time (none yet: hasOut false). */
    private hasOut = false;
    private outHi = 0;
    private outLo = 0;
    outOfOrder = 0;

    constructor(
        private readonly records: LogRecords,
        readonly order: number,
        private readonly size: number,
        private readonly chars: number,
    ) {
        this.held = new Array<TraceRecord | undefined>(size).fill(undefined);
        this.hi = new Float64Array(size);
        this.lo = new Float64Array(size);
        this.heldCharsOf = new Float64Array(size);
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
        const r = this.records;
        while (this.length < this.size && (this.heldChars < this.chars || this.length === 0)) {
            if (!r.ready) return !r.done;
            const at = r.at;
            this.hold(r.records[at]!, r.hi[at]!, r.lo[at]!, r.chars[at]!);
            r.taken();
        }
        return false;
    }

    /** The ring's place of the window's `i`-th record. */
    private place(i: number): number {
        const p = this.head + i;
        return p < this.size ? p : p - this.size;
    }

    private hold(record: TraceRecord, hi: number, lo: number, chars: number): void {
        this.heldChars += chars;
        let at = this.length;
        if (at > 0) {
            const last = this.place(at - 1);
            if (this.hi[last]! > hi || (this.hi[last] === hi && this.lo[last]! > lo)) {
                // after every held record of the same or an earlier time (they came first in the file)
                let lo_ = 0;
                let hi_ = at;
                while (lo_ < hi_) {
                    const mid = (lo_ + hi_) >>> 1;
                    const p = this.place(mid);
                    if (this.hi[p]! < hi || (this.hi[p] === hi && this.lo[p]! <= lo)) lo_ = mid + 1;
                    else hi_ = mid;
                }
                for (let i = at; i > lo_; i--) this.move(this.place(i - 1), this.place(i));
                at = lo_;
            }
        }
        const p = this.place(at);
        this.held[p] = record;
        this.hi[p] = hi;
        this.lo[p] = lo;
        this.heldCharsOf[p] = chars;
        this.length++;
    }

    private move(from: number, to: number): void {
        this.held[to] = this.held[from];
        this.hi[to] = this.hi[from]!;
        this.lo[to] = this.lo[from]!;
        this.heldCharsOf[to] = this.heldCharsOf[from]!;
    }

    /** Whether this window's first record comes out before `other`'s (time, then file order); both hold one. */
    before(other: LogWindow): boolean {
        const a = this.hi[this.head]!;
        const b = other.hi[other.head]!;
        if (a !== b) return a < b;
        const c = this.lo[this.head]!;
        const d = other.lo[other.head]!;
        return c < d || (c === d && this.order < other.order);
    }

    /** The first record held (the window then is one short: `fill` it). */
    take(): TraceRecord {
        const p = this.head;
        const record = this.held[p]!;
        this.held[p] = undefined; // told: its place no longer keeps it (and its line)
        this.heldChars -= this.heldCharsOf[p]!;
        this.head = p + 1 === this.size ? 0 : p + 1;
        this.length--;
        const hi = this.hi[p]!;
        const lo = this.lo[p]!;
        if (this.hasOut && (hi < this.outHi || (hi === this.outHi && lo < this.outLo))) this.outOfOrder++;
        else {
            this.hasOut = true;
            this.outHi = hi;
            this.outLo = lo;
        }
        return record;
    }
}
