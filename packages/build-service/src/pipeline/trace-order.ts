/**
 * Puts the record lines read from several growing CSV logs in mono_ns order across the files
 * (docs/build-service-api.md "Trace channel", "Ordering").
 *
 * Why a hold-back: a module writes its records in bursts (runtime/src/csvlog.c buffers them and
 * writes them when the module waits and the oldest is older than LOG_FLUSH_NS = 10 ms, or its
 * 64 KiB buffer fills), so when the service reads a record of module A at time t, module B may
 * still hold records older than t in its buffer. A record is therefore released only when
 *   - every other log is known whole past its time (the watermark: the smallest, over the logs
 *     still written, of the last time read and of the time up to which the log's flush mark said
 *     it was whole — `mark()`: the module's own word, 0 = nothing buffered, else the mono_ns of
 *     its oldest buffered record, read before the file, so exact: a module that holds its records
 *     for long holds the others back, it is not overtaken; a log whose module wrote `module_exit`
 *     or `module_crashed` (its last record: endsItsLog) no longer counts; never past the time the folder was listed, for the logs of modules started
 *     since), or
 *   - it is `windowMs` old — `markedWindowMs` when every log has its mark: then only a module
 *     that holds its records that long (or died holding them) is overtaken — (now - its mono_ns,
 *     on the host's CLOCK_MONOTONIC, which the modules
 *     of bwrap and none share), or has been held that long since it was read (a clock that would
 *     not be shared); BEHIND_FACTOR times that while some log has bytes the service has not read
 *     yet: a quiet module (one that logs
 *     nothing for seconds) must not stop the channel. With a window of LOG_FLUSH_NS plus the poll
 *     interval and a margin, an idle module's buffered records reach the service before newer
 *     records of other modules are released.
 * A module that computes longer than the window without waiting flushes late: its records then
 * come after newer ones (never lost, never doubled; `late` counts them). The live order is the
 * order of their keys: a record's key is its mono_ns, or the key of the line before it in its
 * file when it has no readable time (garbage stays right after the record it followed, as in
 * the trace reader's parseTrace), and never less than that key (a file's lines keep their order).
 */
import type { TraceLine } from './job-events.js';

/**
 * Whether a record line (or a chunk of them) holds a module's last record: `module_exit`, or the
 * `module_crashed` record its crash handler writes before the process dies (runtime/src/csvlog.c);
 * a Buffer is searched as it is (no string made).
 */
export function endsItsLog(text: string | Buffer): boolean {
    return text.includes(',module_exit,') || text.includes(',module_crashed,');
}

interface Held {
  key: bigint;
  readAt: number;
  line: TraceLine;
}

interface Source {
  queue: Held[];
  /** Key of the last line read (-1 while none). */
  lastKey: bigint;
  /** Its module wrote module_exit or module_crashed, or the log is no longer read: it does not hold the watermark. */
  closed: boolean;
  /** Time up to which the log is known whole from its flush mark (-1 while none was read). */
  whole: bigint;
}

/**
 * While some log has bytes the service has not read yet (its per-poll read bound), records wait up
 * to this many windows: the unread bytes may hold older records (a 10 MB line takes ten polls).
 */
export const BEHIND_FACTOR = 10;

/** When TraceOrder.release may let lines go. */
export interface ReleaseWhen {
  /** Everything (the run has ended and every log was read to its end). */
  all?: boolean;
  /** Some log has bytes not read yet (the per-poll read bound): the window is BEHIND_FACTOR times longer. */
  behind?: boolean;
  /** The run has ended and the logs are read to their end (a log at its end is closed): the watermark only. */
  drain?: boolean;
  /** CLOCK_MONOTONIC (ns, the modules' mono_ns clock under bwrap and none) when logs/ was last listed. */
  listedAt?: bigint;
  /** CLOCK_MONOTONIC now (ns): a record whose mono_ns is the window old goes (also when held the window). */
  nowMono?: bigint;
}

/**
 * The line's mono_ns: its leading 1 to 20 digits, followed by a comma; -1 when it has none (what
 * /^(\d{1,20}),/ reads, without a match object per record).
 */
export function monoOf(text: string): bigint {
  const i = monoDigits(text);
  if (i === 0) return -1n;
  if (i > 15) return BigInt(text.slice(0, i)); // up to 15 digits are exact in a double; more are read from the text
  let n = 0;
  for (let k = 0; k < i; k++) n = n * 10 + (text.charCodeAt(k) - 48);
  return BigInt(n);
}

/**
 * How many digits the line's mono_ns has: its leading 1 to 20 digits, followed by a comma; 0 when
 * it has none (the line cannot be a record). No allocation: what the trace tail asks of every line.
 */
export function monoDigits(text: string): number {
  let i = 0;
  for (; i < text.length && i <= 20; i++) {
    const c = text.charCodeAt(i);
    if (c === 44) break; // ','
    if (c < 48 || c > 57) return 0;
  }
  return i === 0 || i > 20 || i === text.length ? 0 : i;
}

export class TraceOrder {
  private readonly sources = new Map<string, Source>();
  private lastReleased = -1n;
  /** Lines released with a key below one already released (they came later than the window). */
  late = 0;
  /** Lines held now. */
  held = 0;

  constructor(
    private readonly windowMs: number,
    private readonly markedWindowMs = windowMs,
  ) {}

  /** A log the service reads (before its first line, so that it holds the watermark). */
  track(file: string): void {
    if (!this.sources.has(file)) this.sources.set(file, { queue: [], lastKey: -1n, closed: false, whole: -1n });
  }

  /**
   * The log's flush mark said, and the file was then read to its end: every record of it with a
   * mono_ns up to `upTo` has been added. Never moves back.
   */
  mark(file: string, upTo: bigint): void {
    this.track(file);
    const s = this.sources.get(file)!;
    if (upTo > s.whole) s.whole = upTo;
  }

  /** A log no longer read (gone, truncated, left out): it stops holding the watermark. */
  close(file: string): void {
    const s = this.sources.get(file);
    if (s) s.closed = true;
  }

  /** Lines of one file, in file order, read at host time `now` (ms). */
  add(file: string, lines: TraceLine[], now: number): void {
    this.track(file);
    const s = this.sources.get(file)!;
    for (const line of lines) {
      const mono = monoOf(line.text);
      if (mono > s.lastKey) s.lastKey = mono;
      s.queue.push({ key: s.lastKey, readAt: now, line });
      this.held++;
      if (endsItsLog(line.text)) s.closed = true;
    }
  }

  /**
   * Lines of one file read and not added (nobody would receive them): the file is known read up to
   * `lastMono` (the mono_ns of the last of them, -1 when unreadable); `exited`: its module wrote
   * module_exit or module_crashed among them.
   */
  skipped(file: string, lastMono: bigint, exited: boolean): void {
    this.track(file);
    const s = this.sources.get(file)!;
    if (lastMono > s.lastKey) s.lastKey = lastMono;
    if (exited) s.closed = true;
  }

  /**
   * The lines that may go now, in key order (ties: file name order, then file order).
   * `now`: host time (ms) for the held time.
   */
  release(now: number, when: ReleaseWhen = {}): TraceLine[] {
    const factor = when.behind ? BEHIND_FACTOR : 1;
    let marked = true;
    for (const s of this.sources.values()) if (!s.closed && s.whole < 0n) marked = false;
    const windowMs = factor * (marked ? this.markedWindowMs : this.windowMs);
    const windowNs = BigInt(windowMs) * 1_000_000n;
    let threshold: bigint;
    if (when.all) threshold = BigInt('0x7fffffffffffffff') * 4n;
    else {
      let watermark: bigint | null = null;
      // a log whose mark has said for markedWindowMs (BEHIND_FACTOR times that while some log has
      // bytes not read yet) that its module holds the same old record
      // (a module blocked that long, or killed holding records: they are lost with it) stops
      // holding the others back, until its mark moves again
      const stuckBefore = when.nowMono !== undefined ? when.nowMono - BigInt(factor * this.markedWindowMs) * 1_000_000n : null;
      for (const s of this.sources.values()) {
        if (s.closed) continue;
        const known = s.whole > s.lastKey ? s.whole : s.lastKey;
        if (stuckBefore !== null && s.whole >= 0n && known < stuckBefore) continue;
        if (watermark === null || known < watermark) watermark = known;
      }
      threshold = watermark ?? -1n;
      // a log not listed yet was created after the listing: its records are younger than it
      if (when.listedAt !== undefined && !when.drain && threshold > when.listedAt) threshold = when.listedAt;
      // what is old enough goes, and with it what is older (the order is kept)
      for (const s of when.drain ? [] : this.sources.values()) {
        for (const h of s.queue) {
          // a queue is in read order and in key order: the first one too young ends the scan
          const aged = when.nowMono !== undefined && h.key >= 0n && when.nowMono - h.key >= windowNs;
          if (!aged && now - h.readAt < windowMs) break;
          if (h.key > threshold) threshold = h.key;
        }
      }
      if (this.sources.size > 0 && [...this.sources.values()].every((s) => s.closed)) threshold = BigInt('0x7fffffffffffffff') * 4n;
    }
    // a merge of the queues (each in key order), ties in file name order, then file order
    const queues = [...this.sources.keys()].sort().map((n) => this.sources.get(n)!.queue);
    const heads = queues.map(() => 0);
    const out: TraceLine[] = [];
    for (;;) {
      let best = -1;
      let bestKey = 0n;
      for (let q = 0; q < queues.length; q++) {
        const queue = queues[q]!;
        const i = heads[q]!;
        if (i >= queue.length) continue;
        const k = queue[i]!.key;
        if (k > threshold) continue;
        if (best < 0 || k < bestKey) {
          best = q;
          bestKey = k;
        }
      }
      if (best < 0) break;
      const h = queues[best]![heads[best]!]!;
      heads[best]!++;
      if (h.key < this.lastReleased) {
        if (h.key >= 0n) this.late++;
      }
      else this.lastReleased = h.key;
      out.push(h.line);
    }
    for (let q = 0; q < queues.length; q++) if (heads[q]) queues[q]!.splice(0, heads[q]);
    this.held -= out.length;
    return out;
  }
}
