/**
 * `contract run --trace FILE`: the run's records written to FILE as they arrive on the build
 * service's live trace channel (docs/build-service-api.md "Trace channel"), one JSON line per
 * record (as `contract trace --format json`), written through per event (no buffering here).
 * Only a digest of what was written is kept (a run of minutes at 1 kHz is gigabytes of JSON): at
 * the end the caller compares it with the digest of the collected logs' JSON lines (read as a
 * stream, trace-stream.ts) and rewrites the file when they differ.
 *
 * The launcher's end lines of a module that ended on its own (`contract-launch: module MAB (pid 41)
 * died by signal 9 (Killed)`: the job's `line` events of source `launcher`, never a module's
 * output, which comes tagged with its name; not `exited with status 0` at the run's stop) are
 * written among the records as `launcher_line` objects (build-service
 * trace/launcher-line-record.ts). The live channel gives such a line no time of its own: it is
 * written at the time of the last record written before it came; the end-of-run check writes it
 * again at the time the launcher's lines file of the logs folder (contract-launch.log) gives it,
 * in time order among the records (settleTraceFile: the file rewritten when that differs).
 */
import { createHash, type Hash } from 'node:crypto';
import { constants, promises as fsp } from 'node:fs';
import { lstat, type FileHandle } from 'node:fs/promises';
import type { JobEvent } from '@contract-studio/build-service';
import { LauncherLinesQueue, LogClocks, countRecord, endedOnItsOwn, launcherEndLine, launcherLineJson, parseStreamedLine, type RecordCounts, type TraceRecord, type TraceRecordBase } from '@contract-studio/build-service/trace';
import { readLauncherLines } from './launcher-lines.js';
import { lockTraceFile, openTraceFile } from './trace-files.js';
import { JsonLines } from './record-json.js';
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

    /** Bytes written (the file's size when nothing else wrote it). */
    private bytes = 0;
    /** The records' JSON lines, as `contract trace --format json` writes them (record-json.ts). */
    private readonly lines = new JsonLines(16 * 1024);

    private constructor(private readonly handle: FileHandle, private readonly path: string, private readonly unlock: () => void) {}

    /**
     * Opens or creates FILE, never through a link, a FIFO or anything but a regular file; not
     * emptied yet. Takes its writer lock first (lockTraceFile: another run writing it refuses this one).
     */
    static async open(path: string): Promise<LiveTrace> {
        const unlock = lockTraceFile(path);
        try {
            return new LiveTrace(await openTraceFile(path), path, unlock);
        } catch (e) {
            unlock();
            throw e;
        }
    }

    /** The writer lock let go, once the file is whole (after settleTraceFile). */
    release(): void {
        this.unlock();
    }

    /** Empties the file, once, before the first write. */
    private empty(): void {
        if (this.emptied) return;
        this.emptied = true;
        this.writing = this.writing.then(() => this.handle.truncate(0)).catch((err: Error) => void (this.failed ??= err));
    }

    /** The latest time of a record written (monotonic ns, its text), none before the first. */
    private lastMonoNs: bigint | undefined;

    /**
     * A job event: a trace event's records are appended to the file (emptied at the first); a
     * launcher's end line (the run step's `line` event of source `launcher`) as a `launcher_line`
     * at the latest record's time (none before the first record: no module's start to match yet;
     * the end-of-run check adds it at its own time).
     */
    event(e: JobEvent): void {
        if (this.failed) return;
        if (e.type === 'line') {
            if (e.source !== 'launcher' || e.step !== 'run' || this.lastMonoNs === undefined) return;
            // only a module's end on its own (a kill from outside, an exit with a status): the end
            // of every module at the run's stop is its exit record's to say, and written live at
            // another time than its own it would make a normal run's file differ from its logs'
            const end = launcherEndLine(e.line);
            if (!end || !endedOnItsOwn(end.how)) return;
            this.lines.add(launcherLineJson({ monoNs: this.lastMonoNs, line: e.line }));
        } else if (e.type === 'trace') {
            const records = e.records.map((l) => parseStreamedLine(l.file, l.line, l.text, this.clocks.of(l.file)));
            for (const r of records) countRecord(this.counts, r);
            for (const r of records) {
                this.lines.add(r);
                if (r.kind === 'unknown') continue;
                const mono = (r as TraceRecordBase).monoNs;
                if (!/^\d{1,20}$/.test(mono)) continue;
                const at = BigInt(mono);
                if (this.lastMonoNs === undefined || at > this.lastMonoNs) this.lastMonoNs = at;
            }
        } else return;
        const bytes = this.lines.take();
        this.written.update(bytes);
        this.bytes += bytes.length;
        this.empty();
        this.writing = this.writing.then(() => this.handle.write(bytes)).catch((err: Error) => void (this.failed ??= err));
    }

    /**
     * The run ran: waits for the writes (the file emptied if no record came) and closes; the
     * sha256 (hex) of what was written, and whether the file at its path is still this one and
     * holds just that (`intact`: another run writing the same file, or the file moved or replaced
     * meanwhile, make it false). Throws a write error.
     */
    async close(): Promise<{ digest: string; intact: boolean }> {
        this.empty();
        await this.writing;
        let intact = false;
        try {
            const own = await this.handle.stat();
            const there = await lstat(this.path);
            intact = there.isFile() && there.ino === own.ino && there.dev === own.dev && own.size === this.bytes;
        } catch {
            intact = false; // gone from its path
        }
        await this.handle.close();
        if (this.failed) throw this.failed;
        return { digest: this.written.digest('hex'), intact };
    }

    /** Nothing ran (the build failed): closes; true when the file was left as it was (no record had come). */
    async abandon(): Promise<boolean> {
        await this.writing;
        await this.handle.close().catch(() => {});
        this.unlock();
        return !this.emptied;
    }
}

/**
 * The JSON lines of the run's saved logs `names` in `dir`: their digest compared with what was
 * written live (`live.digest`), and `traceFile` rewritten from them when it differs or when the
 * file is not intact (LiveTrace.close: another writer, a move or a replacement during the run):
 * written whole to a new file beside it, then renamed over the path (never through a link: a link
 * put there meanwhile is replaced, its target untouched). The records counted (with `replaced`
 * when the file was not intact, `rewritten` when a new file took the path), or why the logs could not be read. A run that left no logs keeps
 * what came live (`live.counts`). `observe` sees each record of the logs once, in the order written.
 * The launcher's end lines of `dir`'s contract-launch.log are written among the records, in time
 * order (`launcher_line` objects, as `contract trace DIR --format json` writes them).
 */
export async function settleTraceFile(dir: string, names: readonly string[], traceFile: string, live: { digest: string; counts: RecordCounts; intact?: boolean }, observe?: (r: TraceRecord) => void): Promise<(RecordCounts & { replaced?: boolean; rewritten?: boolean }) | string> {
    const replaced = live.intact === false ? { replaced: true } : {};
    if (!names.length) return { ...live.counts, ...replaced };
    const logs = await openLogFolder(dir, names);
    if (typeof logs === 'string') return logs;
    try {
        // the launcher's lines file is the launcher's alone (written through a descriptor no module inherits)
        const launcher = await readLauncherLines(dir, []);
        const hash = createHash('sha256');
        const { counts } = await jsonLinesOf(logs, (piece) => void hash.update(piece), observe, new LauncherLinesQueue(launcher));
        if (hash.digest('hex') === live.digest && live.intact !== false) return counts;
        const temp = `${traceFile}.tmp-${process.pid}`;
        const out = await fsp.open(temp, constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW, 0o644);
        try {
            try {
                await jsonLinesOf(logs, async (piece) => void (await out.write(piece)), undefined, new LauncherLinesQueue(launcher));
            } finally {
                await out.close();
            }
            await fsp.rename(temp, traceFile);
        } catch (e) {
            await fsp.unlink(temp).catch(() => {});
            throw e;
        }
        return { ...counts, ...replaced, rewritten: true };
    } finally {
        await closeLogs(logs);
    }
}
