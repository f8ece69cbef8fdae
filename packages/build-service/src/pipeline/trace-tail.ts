/**
 * The live trace channel's reader (docs/build-service-api.md "Trace channel"): while the run step
 * runs, reads the run's log folder (LOG_DIR = <work>/logs, a host folder for bwrap and none: the
 * work dir is bound into the sandbox) when it changes (inotify, through fs.watch: at once when every
 * log's mark says it was written for the last flush boundary, else `wakeMs` later) and every
 * `pollMs` in any case, reads only the new bytes of each `*.csv` and, before them, the
 * word of its flush mark (`<log>.mark`, runtime/src/csvlog.c: up to when the log is whole), and
 * hands their record lines, in mono_ns order across the files (trace-order.ts), to the job.
 *
 * The folder is the running sandbox's, so it can change under every call (docs/sandbox.md,
 * "Workspaces and host safety"): the logs folder is opened once as a directory without following
 * a link (O_DIRECTORY | O_NOFOLLOW) and every file is opened through that descriptor
 * (/proc/self/fd/N/<name>, so a logs/ renamed or replaced by a link later is never walked through),
 * with O_NOFOLLOW (a link is refused) and O_NONBLOCK (a FIFO does not block the open), then kept
 * only when fstat says it is a regular file. Reads are bounded per poll (`readBytesPerPoll`), names
 * and file counts are bounded, lines are bounded (trace-lines.ts). Nothing here throws into the
 * job: a fault stops the channel with one system line; the collected logs stay the record.
 */
import { constants, promises as fsp, readSync, watch, writeSync, type FSWatcher } from 'node:fs';
import type { FileHandle } from 'node:fs/promises';
import { endianness } from 'node:os';
import { join } from 'node:path';
import { SERVICE_BOUNDS } from '../limits.js';
import { ARTIFACT_BOUNDS, LOG_DIR, SAFE_NAME } from './artifacts.js';
import type { TraceLine } from './job-events.js';
import { TraceLineSplitter } from './trace-lines.js';
import { endsItsLog, monoDigits, monoOf, TraceOrder } from './trace-order.js';
import { openDirNoFollow, openedDirPath, openRegularFileIn } from '../util/safe-fs.js';

export interface TraceTailBounds {
  pollMs: number;
  /** Delay from a change of logs/ to the read it wakes; 0: no watch, polls only. */
  wakeMs: number;
  readBytesPerPoll: number;
  orderWindowMs: number;
  /** The order window when every log has its flush mark. */
  markHoldMs: number;
  /** Flush delay asked of the modules (their marks' second word) while a client watches. */
  watchedFlushMs: number;
  files: number;
  /** Entries of logs/ looked at per listing. */
  entries: number;
  linesPerEvent: number;
  linesKept: number;
  /** Lines that are no record sent per run; the later ones are counted in `unsent` entries (trace/wire.ts). */
  unreadableKept: number;
  /** Bytes read of one log at most: as far as the collector keeps of it (artifacts.ts artifactBoundsFor). */
  fileBytes: number;
}

export const TRACE_TAIL_BOUNDS: Readonly<TraceTailBounds> = Object.freeze({
  pollMs: SERVICE_BOUNDS.tracePollMs,
  wakeMs: SERVICE_BOUNDS.traceWakeMs,
  readBytesPerPoll: SERVICE_BOUNDS.traceReadBytesPerPoll,
  orderWindowMs: SERVICE_BOUNDS.traceOrderWindowMs,
  markHoldMs: SERVICE_BOUNDS.traceMarkHoldMs,
  watchedFlushMs: SERVICE_BOUNDS.traceWatchedFlushMs,
  files: SERVICE_BOUNDS.traceFiles,
  entries: SERVICE_BOUNDS.listedEntries,
  linesPerEvent: SERVICE_BOUNDS.traceLinesPerEvent,
  linesKept: SERVICE_BOUNDS.traceLinesKept,
  unreadableKept: SERVICE_BOUNDS.traceUnreadableKept,
  fileBytes: ARTIFACT_BOUNDS.fileBytes,
});

/** Where the tail's output goes (the job: trace events and system lines). */
export interface TraceSink {
  /** Lines kept in the job's event log (replayable from seq 0). */
  trace(lines: TraceLine[]): void;
  /** Lines beyond the kept-lines bound: sent to the clients attached now, not kept. */
  live(lines: TraceLine[]): void;
  system(line: string): void;
  /** A log changed otherwise than by appends while it was read (a run issue, run-issues.ts log-tampered). */
  tampered?(file: string, why: string): void;
}

interface Tailed {
  name: string;
  fh: FileHandle;
  splitter: TraceLineSplitter;
  done: boolean;
  /**
   * A log an earlier run left (a reused workspace) that has not grown since this run started: not
   * read (its old bytes are read, counted and not sent, only once it grows) and not holding the
   * ordering watermark.
   */
  dormantUntil: number;
  /** The log's flush mark, opened read-only (null while none was found). */
  mark: FileHandle | null;
  /** Rounds left in which a missing mark is looked for again. */
  markTries: number;
  /** The mark was opened for writing too (its second word: the flush delay asked). */
  markWritable: boolean;
}

const CHUNK = 64 * 1024;
/** The flush mark's name for a log (runtime/src/csvlog.c). */
export const MARK_SUFFIX = '.mark';
/** Rounds after a log was opened in which its mark is looked for (the runtime creates it first). */
const MARK_TRIES = 3;
const readWord = endianness() === 'LE' ? (b: Buffer) => b.readBigUInt64LE(0) : (b: Buffer) => b.readBigUInt64BE(0);

export class TraceTail {
  private dir: FileHandle | null = null;
  private readonly files = new Map<string, Tailed>();
  /** Names not tailed (not a regular file, a link, over the file bound): looked at once. */
  private readonly ignored = new Set<string>();
  /** Sizes of the logs that were there before the run: their old lines are counted, not sent. */
  private readonly before = new Map<string, number>();
  private readonly order: TraceOrder;
  private timer: NodeJS.Timeout | null = null;
  /** Date.now() when the timer fires. */
  private timerDue = 0;
  /** Date.now() when the last read began. */
  private readAt = 0;
  private watcher: FSWatcher | null = null;
  /** A read is running. */
  private reading = false;
  /** logs/ changed while a read ran: the next read comes after wakeMs, not pollMs. */
  private changedMeanwhile = false;
  private readonly word = Buffer.alloc(8);
  /** A client follows the job: the modules are asked to write their logs sooner. */
  private watched = false;
  private polling: Promise<void> = Promise.resolve();
  private stopped = false;
  /** finish() or stop() was called: no poll is scheduled any more. */
  private ending = false;
  /** Some log had bytes left unread by the last poll (the per-poll read bound). */
  private behind = false;
  /** process.hrtime (CLOCK_MONOTONIC, the clock of mono_ns: bwrap, none, and Docker containers, which get no time namespace) at the last listing. */
  private listedAt: bigint | null = null;
  private sent = 0;
  /** Lines that are no record sent so far (unreadableKept), and those counted only. */
  private unreadableSent = 0;
  private unreadableUnsent = 0;
  /** Past the kept-lines bound: lines go to the attached clients only. */
  private liveOnly = false;
  private liveSent = 0;
  private counted = 0;
  private rotate = 0;
  private readonly buf: Buffer;
  private noted = new Set<string>();

  private constructor(
    private readonly logsDir: string,
    private readonly sink: TraceSink,
    private readonly bounds: TraceTailBounds,
  ) {
    this.order = new TraceOrder(bounds.orderWindowMs, bounds.markHoldMs);
    this.buf = Buffer.allocUnsafe(Math.max(1, Math.min(CHUNK, bounds.readBytesPerPoll)));
  }

  /** Records sent so far. */
  get sentLines(): number {
    return this.sent;
  }

  /** Records read past the kept bound while no client was attached: counted, not sent to anyone. */
  get countedLines(): number {
    return this.counted;
  }

  /**
   * Starts tailing `<workDir>/logs` (what its logs hold now is not this run's: only bytes added
   * from now on are sent). Call before the run starts; never throws.
   */
  static async start(workDir: string, sink: TraceSink, bounds: TraceTailBounds = TRACE_TAIL_BOUNDS): Promise<TraceTail> {
    const tail = new TraceTail(join(workDir, LOG_DIR), sink, bounds);
    await tail.guard(async () => {
      if (!(await tail.openDir())) return;
      for (const name of await tail.list()) {
        const st = await fsp.lstat(join(tail.dirPath(), name)).catch(() => null);
        if (st?.isFile()) tail.before.set(name, st.size);
      }
    });
    tail.schedule();
    return tail;
  }

  /**
   * The run has ended (every process of it is gone): reads every log to its end, sends every
   * record held, closes the files. Never throws.
   */
  async finish(): Promise<void> {
    this.ending = true;
    this.clearTimer();
    await this.polling;
    if (!this.stopped) {
      await this.guard(async () => {
        // a bounded read per round, as many rounds as it takes: every file ends (the run is over)
        // (a file read to its end is closed: it no longer holds the watermark, so what is held
        // is sent round by round and memory stays bounded by the rounds' reads)
        while (!this.stopped) {
          const more = await this.readRound(Date.now(), true);
          if (!this.stopped) this.emit(this.order.release(Date.now(), { all: !more, drain: true }));
          if (!more) break;
        }
        if (!this.stopped && this.order.late > 0) {
          this.sink.system(`trace: ${this.order.late} record(s) reached the service more than ${this.bounds.orderWindowMs} ms after newer records of other modules were sent: they were sent late, out of mono_ns order (the collected logs are in order)`);
        }
      });
    }
    await this.close();
  }

  /**
   * A client follows the job's events (or none does any more): asks every module, through its flush
   * mark's second word, to write its log after watchedFlushMs instead of its own 50 ms (0: its own).
   */
  setWatched(watched: boolean): void {
    if (watched === this.watched) return;
    this.watched = watched;
    for (const f of this.files.values()) this.askFlush(f);
  }

  private askFlush(f: Tailed): void {
    if (!f.mark || !f.markWritable || this.stopped) return;
    const b = Buffer.alloc(8);
    const ns = this.watched ? BigInt(this.bounds.watchedFlushMs) * 1_000_000n : 0n;
    if (endianness() === 'LE') b.writeBigUInt64LE(ns);
    else b.writeBigUInt64BE(ns);
    try {
      writeSync(f.mark.fd, b, 0, 8, 8);
    } catch {
      f.markWritable = false; // the module's own delay stands
    }
  }

  /** Stops without reading further (a cancelled or failed job). Never throws. */
  async stop(): Promise<void> {
    this.ending = true;
    this.clearTimer();
    this.stopped = true;
    await this.polling;
    await this.close();
  }

  private dirPath(): string {
    return openedDirPath(this.dir!);
  }

  /** The next read in `ms` (pollMs by default; wakeMs after a change of logs/). */
  private schedule(ms = this.bounds.pollMs): void {
    if (this.stopped || this.ending) return;
    this.clearTimer();
    this.timerDue = Date.now() + ms;
    this.timer = setTimeout(() => {
      this.timer = null;
      this.reading = true;
      this.readAt = Date.now();
      this.polling = this.guard(() => this.poll()).then(() => {
        this.reading = false;
        const again = this.changedMeanwhile;
        this.changedMeanwhile = false;
        this.schedule(again ? this.wakeDelay() : this.bounds.pollMs);
      });
    }, ms);
    this.timer.unref();
  }

  /** logs/ changed (a log grew, a log was created): read soon. */
  private changed(): void {
    if (this.stopped || this.ending) return;
    if (this.reading) {
      this.changedMeanwhile = true;
      return;
    }
    const ms = this.wakeDelay();
    if (this.timerDue > Date.now() + ms) this.schedule(ms);
  }

  /**
   * How long after a change of logs/ to read it: at once when every log has been written for the
   * last flush boundary (nothing more will come before the next one), else wakeMs, so that the
   * modules writing at the same boundary are read together. Never sooner than wakeMs after the
   * last read began: a sandboxed program that writes without end, its mark saying it holds
   * nothing, gets no more reads than before (one per wakeMs).
   */
  private wakeDelay(): number {
    if (!this.writtenForBoundary()) return this.bounds.wakeMs;
    return Math.max(0, this.readAt + this.bounds.wakeMs - Date.now());
  }

  /**
   * While a client watches, the modules write their logs at the boundaries of the delay asked
   * (its multiples on the shared CLOCK_MONOTONIC: runtime/src/csvlog.c ContractLogFlushDue). A log
   * is written for the last boundary when its mark says that its module holds nothing, or only
   * records logged since that boundary. True when every log read is; false whenever it cannot be
   * known (not watched, a log without a mark its module takes the delay from, a record being logged).
   */
  private writtenForBoundary(): boolean {
    if (!this.watched || this.files.size === 0) return false;
    const delay = BigInt(this.bounds.watchedFlushMs) * 1_000_000n;
    if (delay <= 0n) return false;
    const now = process.hrtime.bigint();
    const boundary = (now / delay) * delay;
    for (const f of this.files.values()) {
      if (f.done || f.dormantUntil > 0) continue;
      if (!f.mark || !f.markWritable) return false;
      const word = this.markWord(f);
      if (word === null || word === 1n) return false;
      if (word !== 0n && word < boundary) return false;
    }
    return true;
  }

  /** Watches logs/ (through its descriptor: the folder opened, never a name replaced later); polls only when it cannot. */
  private watchDir(): void {
    if (this.watcher || this.bounds.wakeMs <= 0 || !this.dir) return;
    try {
      this.watcher = watch(this.dirPath(), { persistent: false }, () => this.changed());
      this.watcher.on('error', () => this.unwatch());
    } catch {
      this.watcher = null; // no inotify watch left (fs.inotify.max_user_watches): the poll reads on
    }
  }

  private unwatch(): void {
    try {
      this.watcher?.close();
    } catch {
      /* closed already */
    }
    this.watcher = null;
  }

  private clearTimer(): void {
    if (this.timer) clearTimeout(this.timer);
    this.timer = null;
  }

  /** Runs a step; an exception stops the channel with one system line (never the job). */
  private async guard(fn: () => Promise<void>): Promise<void> {
    try {
      await fn();
    } catch (e) {
      if (this.stopped) return;
      this.stopped = true;
      this.clearTimer();
      this.safeSystem(`trace: the live trace channel stopped (${(e as Error)?.message?.split('\n')[0] ?? String(e)}); the whole trace is in the run's collected logs`);
    }
  }

  private safeSystem(line: string): void {
    try {
      this.sink.system(line);
    } catch {
      /* the job's log is closed */
    }
  }

  private noteOnce(key: string, line: string): void {
    if (this.noted.has(key)) return;
    this.noted.add(key);
    this.safeSystem(line);
  }

  /** Opens logs/ once it exists; false while it does not (or when it is not a directory). */
  private async openDir(): Promise<boolean> {
    if (this.dir) return true;
    try {
      this.dir = await openDirNoFollow(this.logsDir);
      if (!this.ending) this.watchDir();
      return true;
    } catch (e) {
      const code = (e as NodeJS.ErrnoException).code;
      if (code === 'ENOENT') return false;
      // a link or a file where the folder should be: the collector leaves it out too
      this.noteOnce('dir', `trace: ${LOG_DIR}/ is not a directory (${code ?? 'error'}): no live trace`);
      this.stopped = true;
      return false;
    }
  }

  /** The names in logs/ (at most `entries` of them), read through the folder's descriptor. */
  private async list(): Promise<string[]> {
    const names: string[] = [];
    const handle = await fsp.opendir(this.dirPath(), { bufferSize: 64 }).catch(() => null);
    if (!handle) return names;
    try {
      for await (const d of handle) {
        if (names.length >= this.bounds.entries) break; // leaving the loop closes the handle
        names.push(d.name);
      }
    } catch {
      /* the folder changed while it was read: what was read is listed */
    }
    return names;
  }

  private async poll(): Promise<void> {
    if (this.stopped) return;
    this.behind = await this.readRound(Date.now(), false);
    if (!this.stopped) this.emit(this.order.release(Date.now(), { behind: this.behind, nowMono: process.hrtime.bigint(), ...(this.listedAt !== null ? { listedAt: this.listedAt } : {}) }));
  }

  /** Looks for new logs, reads up to the per-poll bound; true when some file has more bytes. */
  private async readRound(now: number, final: boolean): Promise<boolean> {
    if (!(await this.openDir())) return false;
    const listedAt = process.hrtime.bigint();
    // a run that keeps making new names must not grow this set without end (a name forgotten is
    // only looked at again: the listing is bounded per poll)
    if (this.ignored.size > 4 * this.bounds.entries) this.ignored.clear();
    for (const name of await this.list()) {
      if (this.files.has(name) || this.ignored.has(name)) continue;
      if (!name.endsWith('.csv') || !SAFE_NAME.test(name)) {
        this.ignored.add(name);
        continue;
      }
      await this.open(name);
    }
    const all = [...this.files.values()].filter((f) => !f.done);
    let budget = this.bounds.readBytesPerPoll;
    let more = false;
    const start = all.length ? this.rotate++ % all.length : 0;
    for (let i = 0; i < all.length; i++) {
      const f = all[(start + i) % all.length]!;
      const left = await this.readFile(f, budget, now);
      budget -= left.read;
      if (left.more) more = true;
      if (this.stopped) return false;
      if (final && !left.more && !f.done) {
        // the run is over: this file is whole; its last line may lack its newline
        this.order.add(f.name, f.splitter.end(), now);
        f.done = true;
        this.order.close(f.name);
      }
    }
    this.listedAt = listedAt;
    return more;
  }

  private async open(name: string): Promise<void> {
    if (this.files.size >= this.bounds.files) {
      this.ignored.add(name);
      this.noteOnce('files', `trace: more than ${this.bounds.files} logs: the others are only in the collected logs`);
      return;
    }
    let opened: Awaited<ReturnType<typeof openRegularFileIn>>;
    try {
      opened = await openRegularFileIn(this.dir!, name, constants.O_RDONLY);
    } catch {
      this.ignored.add(name); // a link (ELOOP), gone, not readable
      return;
    }
    if (!opened) {
      this.ignored.add(name); // a FIFO, a socket, a device, a folder
      return;
    }
    const fh = opened.fh;
    const before = this.before.get(name) ?? 0;
    const f: Tailed = { name, fh, splitter: new TraceLineSplitter(name, before), done: false, dormantUntil: before, mark: null, markTries: MARK_TRIES, markWritable: false };
    this.files.set(name, f);
    if (before === 0) this.order.track(name);
    await this.openMark(f);
  }

  /** Opens a log's flush mark, as the logs are opened (no link, no FIFO, a regular file of at least one word). */
  private async openMark(f: Tailed): Promise<void> {
    if (f.mark || f.markTries <= 0) return;
    f.markTries--;
    const name = f.name + MARK_SUFFIX;
    let opened: Awaited<ReturnType<typeof openRegularFileIn>>;
    try {
      opened = await openRegularFileIn(this.dir!, name, constants.O_RDWR);
      f.markWritable = true;
    } catch (e) {
      if ((e as NodeJS.ErrnoException).code !== 'EACCES') return; // none (a runtime without marks, CONTRACT_LOG_MARK unset): the order window applies
      try {
        opened = await openRegularFileIn(this.dir!, name, constants.O_RDONLY); // read only: the order, not the sooner flush
      } catch {
        return;
      }
    }
    if (!opened || opened.size < 16) {
      f.markTries = 0;
      f.markWritable = false;
      await opened?.fh.close().catch(() => {});
      return;
    }
    f.mark = opened.fh;
    if (this.watched) this.askFlush(f);
  }

  /**
   * Up to when the log is whole, from its mark read now (before the file is read): the host's
   * CLOCK_MONOTONIC before the read when the module holds nothing, just before its oldest held
   * record otherwise; null when unknown (no mark, a record being logged, a read fault).
   */
  private wholeUpTo(f: Tailed): bigint | null {
    if (!f.mark) return null;
    const before = process.hrtime.bigint();
    const word = this.markWord(f);
    if (word === null) return null;
    if (word === 0n) return before;
    if (word === 1n) return null;
    // the module's own word: a time in the future is not believed beyond now
    return word - 1n < before ? word - 1n : before;
  }

  /** The first word of a log's flush mark (0: nothing held, 1: a record being logged, else the mono_ns of the oldest record held); null when it cannot be read. */
  private markWord(f: Tailed): bigint | null {
    if (!f.mark) return null;
    try {
      // one 8-byte read of a regular file's page: synchronous, no thread-pool round trip per log
      if (readSync(f.mark.fd, this.word, 0, 8, 0) !== 8) return null;
      return readWord(this.word);
    } catch {
      return null;
    }
  }

  /**
   * Reads at most `budget` new bytes of one log. The fstat and the reads stay asynchronous (thread
   * pool round trips) on purpose: synchronous ones cost the service less CPU but raised the 1 kHz
   * benchmark's release lateness p99 with a client attached from about 370 to 900 us on the dev
   * machine (docs/monitor-performance.md, "What watching costs the run").
   */
  private async readFile(f: Tailed, budget: number, now: number): Promise<{ read: number; more: boolean }> {
    if (!f.mark && f.markTries > 0) await this.openMark(f);
    const whole = this.wholeUpTo(f);
    // no further than the collector keeps of a log: a sparse file of terabytes (a truncate in the
    // sandbox) must not keep finish() reading zeros after the run
    const size = Math.min((await f.fh.stat()).size, this.bounds.fileBytes);
    if (f.dormantUntil > 0) {
      if (size <= f.dormantUntil) return { read: 0, more: false };
      f.dormantUntil = 0; // it grew: this run writes to it too (a module restarted within the same second)
      this.order.track(f.name);
    }
    if (size < f.splitter.offset) {
      // the runtime only appends (O_APPEND): a log that shrank was rewritten by the sandboxed code
      f.done = true;
      this.order.close(f.name);
      this.safeSystem(`trace: ${f.name} shrank while it was read (${f.splitter.offset} -> ${size} bytes): its live trace stops there; the collected log is what the run left`);
      try {
        this.sink.tampered?.(f.name, `it shrank while the run went on (${f.splitter.offset} -> ${size} bytes; the runtime only appends to a log)`);
      } catch {
        /* the job's sink: nothing to do here */
      }
      return { read: 0, more: false };
    }
    let read = 0;
    while (read < budget && f.splitter.offset < size) {
      const want = Math.min(this.buf.length, budget - read, size - f.splitter.offset);
      const { bytesRead } = await f.fh.read(this.buf, 0, want, f.splitter.offset);
      if (bytesRead === 0) break;
      read += bytesRead;
      const chunk = this.buf.subarray(0, bytesRead);
      if (this.liveOnly && !this.watched) {
        // past the kept bound with no client attached: no record would reach anyone; the lines
        // are only counted (their numbers) and the order told how far the file was read
        const lineNo = f.splitter.nextLine;
        const last = f.splitter.count(chunk);
        this.counted += f.splitter.nextLine - lineNo;
        if (last >= 0) this.order.skipped(f.name, monoOf(chunk.toString('latin1', last, Math.min(chunk.length, last + 22))), endsItsLog(chunk));
      } else this.order.add(f.name, f.splitter.push(chunk), now);
    }
    const more = f.splitter.offset < size;
    // read to the size seen after the mark: every record the mark said was written is added
    if (!more && whole !== null && f.dormantUntil === 0) this.order.mark(f.name, whole);
    return { read, more };
  }

  /**
   * Sends lines as trace events, kept for replay up to the kept-lines bound; past it they still go
   * to the clients attached now (a 1 kHz schema passes the bound in seconds, and a live monitor
   * must follow the whole run), but are not kept: a later client replays them from the collected logs.
   */
  private emit(read: TraceLine[]): void {
    if (this.stopped || read.length === 0) return;
    const lines = this.unsentPastBound(read);
    const room = Math.max(0, this.bounds.linesKept - this.sent);
    const take = lines.length > room ? lines.slice(0, room) : lines;
    for (let i = 0; i < take.length; i += this.bounds.linesPerEvent) this.sink.trace(take.slice(i, i + this.bounds.linesPerEvent));
    this.sent += take.length;
    if (lines.length > room) {
      if (!this.liveOnly) {
        this.liveOnly = true;
        this.safeSystem(`trace: ${this.bounds.linesKept} records kept for replay (the build service's traceLinesKept bound); later records go live to the clients attached now only, and the whole trace is in the run's collected logs`);
      }
      const rest = lines.slice(take.length);
      for (let i = 0; i < rest.length; i += this.bounds.linesPerEvent) this.sink.live(rest.slice(i, i + this.bounds.linesPerEvent));
      this.liveSent += rest.length;
    }
  }

  /**
   * The lines with those that are no record past the unreadableKept bound replaced: a stretch of
   * them in one log, one after the other, by one `unsent` entry counting them (trace/wire.ts). A
   * record line begins with its `mono_ns`, digits then a comma; anything else cannot be one.
   */
  private unsentPastBound(lines: TraceLine[]): TraceLine[] {
    let out: TraceLine[] | undefined;
    for (let i = 0; i < lines.length; i++) {
      const l = lines[i]!;
      const record = monoDigits(l.text) > 0;
      if (record || this.unreadableSent < this.bounds.unreadableKept) {
        if (!record) this.unreadableSent++;
        out?.push(l);
        continue;
      }
      out ??= lines.slice(0, i);
      if (this.unreadableUnsent++ === 0) {
        this.safeSystem(`trace: more than ${this.bounds.unreadableKept} lines of the logs are no record (junk written into logs/?): the later ones are counted, not sent (the build service's traceUnreadableKept bound); they are in the run's collected logs`);
      }
      const last = out[out.length - 1];
      if (last?.unsent && last.file === l.file && last.line + last.unsent === l.line) last.unsent++;
      else out.push({ file: l.file, line: l.line, text: '', unsent: 1 });
    }
    return out ?? lines;
  }

  private async close(): Promise<void> {
    this.unwatch();
    for (const f of this.files.values()) {
      await f.fh.close().catch(() => {});
      await f.mark?.close().catch(() => {});
    }
    this.files.clear();
    // the run is over: a mark its module could not remove (it was killed) is no record of the run
    if (this.dir) {
      for (const name of await this.list().catch(() => [])) {
        if (name.endsWith(`.csv${MARK_SUFFIX}`) && SAFE_NAME.test(name)) await fsp.unlink(join(this.dirPath(), name)).catch(() => {});
      }
    }
    await this.dir?.close().catch(() => {});
    this.dir = null;
  }
}
