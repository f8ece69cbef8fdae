/**
 * `contract run --trace FILE`: the run's records written to FILE as they arrive on the build
 * service's live trace channel (docs/build-service-api.md "Trace channel"), one JSON line per
 * record (as `contract trace --format json`), written through per event (no buffering here).
 * Only a digest of what was written is kept (a run of minutes at 1 kHz is gigabytes of JSON): at
 * the end the caller compares it with the digest of the collected logs' JSON lines (read as a
 * stream, trace-stream.ts) and rewrites the file when they differ.
 */
import { createHash, type Hash } from 'node:crypto';
import type { FileHandle } from 'node:fs/promises';
import type { JobEvent } from '@contract-studio/build-service';
import { LogClocks, countRecord, parseRecordLine, type RecordCounts, type TraceRecord } from '@contract-studio/build-service/trace';
import { openTraceFile, toJsonLines } from './trace-files.js';
import { closeLogs, jsonLinesOf, openLogFolder } from './trace-stream.js';

export class LiveTrace {
    private writing: Promise<unknown> = Promise.resolve();
    private failed: Error | null = null;
    private readonly written: Hash = createHash('sha256');
    /** Written so far: records (readable ones) and, apart, unreadable lines (their `unknown` objects). */
    readonly counts: RecordCounts = { records: 0, unreadable: 0 };

    /** Emptied yet: the file keeps what it held until the run's first records (or its end). */
    private emptied = false;
    /** Each log's time check: its lines come in file order. */
    private readonly clocks = new LogClocks();

    private constructor(private readonly handle: FileHandle) {}

    /** Opens or creates FILE, never through a link, a FIFO or anything but a regular file; not emptied yet. */
    static async open(path: string): Promise<LiveTrace> {
        return new LiveTrace(await openTraceFile(path));
    }

    /** Empties the file, once, before the first write. */
    private empty(): void {
        if (this.emptied) return;
        this.emptied = true;
        this.writing = this.writing.then(() => this.handle.truncate(0)).catch((err: Error) => void (this.failed ??= err));
    }

    /** A job event: a trace event's records are appended to the file (emptied at the first). */
    event(e: JobEvent): void {
        if (e.type !== 'trace' || this.failed) return;
        const records = e.records.map((l) => parseRecordLine(l.file, l.line, l.text, this.clocks.of(l.file)));
        for (const r of records) countRecord(this.counts, r);
        const text = toJsonLines(records);
        this.written.update(text);
        this.empty();
        this.writing = this.writing.then(() => this.handle.write(text)).catch((err: Error) => void (this.failed ??= err));
    }

    /** The run ran: waits for the writes (the file emptied if no record came) and closes; the sha256 (hex) of what the file holds. Throws a write error. */
    async close(): Promise<string> {
        this.empty();
        await this.writing;
        await this.handle.close();
        if (this.failed) throw this.failed;
        return this.written.digest('hex');
    }

    /** Nothing ran (the build failed): closes; true when the file was left as it was (no record had come). */
    async abandon(): Promise<boolean> {
        await this.writing;
        await this.handle.close().catch(() => {});
        return !this.emptied;
    }
}

/**
 * The JSON lines of the run's saved logs `names` in `dir`: their digest compared with what was
 * written live (`live.digest`), and `traceFile` rewritten from them when it differs. The records
 * counted, or why the logs could not be read. A run that left no logs keeps what came live
 * (`live.counts`). `observe` sees each record of the logs once, in the order written.
 */
export async function settleTraceFile(dir: string, names: readonly string[], traceFile: string, live: { digest: string; counts: RecordCounts }, observe?: (r: TraceRecord) => void): Promise<RecordCounts | string> {
    if (!names.length) return { ...live.counts };
    const logs = await openLogFolder(dir, names);
    if (typeof logs === 'string') return logs;
    try {
        const hash = createHash('sha256');
        const { counts } = await jsonLinesOf(logs, (piece) => void hash.update(piece), observe);
        if (hash.digest('hex') === live.digest) return counts;
        const out = await openTraceFile(traceFile, { empty: true });
        try {
            await jsonLinesOf(logs, async (piece) => void (await out.write(piece)));
        } finally {
            await out.close();
        }
        return counts;
    } finally {
        await closeLogs(logs);
    }
}
