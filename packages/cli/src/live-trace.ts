/**
 * `contract run --trace FILE`: the run's records written to FILE as they arrive on the build
 * service's live trace channel (docs/build-service-api.md "Trace channel"), one JSON line per
 * record (as `contract trace --format json`), written through per event (no buffering here).
 * At the end the caller hands the file's expected whole text (the collected logs read by
 * parseTrace): close() tells whether the live text is exactly that, else the caller rewrites it.
 */
import { constants, promises as fsp } from 'node:fs';
import type { FileHandle } from 'node:fs/promises';
import type { JobEvent } from '@contract-studio/build-service';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { toJsonLines } from './trace-files.js';

export class LiveTrace {
    private writing: Promise<unknown> = Promise.resolve();
    private failed: Error | null = null;
    private readonly written: string[] = [];
    /** Records written so far. */
    records = 0;

    private constructor(private readonly handle: FileHandle) {}

    /** Creates or truncates FILE, never through a link found there. */
    static async open(path: string): Promise<LiveTrace> {
        return new LiveTrace(await fsp.open(path, constants.O_WRONLY | constants.O_CREAT | constants.O_TRUNC | constants.O_NOFOLLOW, 0o644));
    }

    /** A job event: a trace event's records are appended to the file. */
    event(e: JobEvent): void {
        if (e.type !== 'trace' || this.failed) return;
        const text = toJsonLines(e.records.map((l) => parseRecordLine(l.file, l.line, l.text)));
        this.records += e.records.length;
        this.written.push(text);
        this.writing = this.writing.then(() => this.handle.write(text)).catch((err: Error) => void (this.failed ??= err));
    }

    /** Waits for the writes and closes; true when the file holds exactly `whole`. Throws a write error. */
    async close(whole?: string): Promise<boolean> {
        await this.writing;
        await this.handle.close();
        if (this.failed) throw this.failed;
        return whole !== undefined && this.written.join('') === whole;
    }
}
