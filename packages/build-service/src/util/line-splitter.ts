import { SERVICE_BOUNDS } from '../limits.js';
import { PastCapLines, type PastCapOptions } from './past-cap-lines.js';

/**
 * Splits a byte stream into text lines, keeps at most `maxBytes` bytes of it (then reports the
 * truncation once and drops the rest while still draining the stream, so the writer never blocks;
 * the line the bound cuts ends with CUT_LINE).
 * A line is emitted without its newline; a line longer than `maxLineBytes` is split, or than
 * `longLine.maxBytes` when its beginning is one `longLine.begins` takes (gcc's JSON diagnostics).
 */
export interface LineSplitterOptions {
  maxBytes: number;
  maxLineBytes?: number;
  /** Lines allowed a bound of their own, told by their first LONG_LINE_HEAD_BYTES bytes. */
  longLine?: { maxBytes: number; begins(head: string): boolean };
  onLine(line: string): void;
  onTruncated(keptBytes: number): void;
  /**
   * Past `maxBytes`, the lines still read though not kept (past-cap-lines.ts: a build's gcc
   * diagnostics), given to `pastCap.onLine`; the line the cap cuts goes there whole when `wanted`
   * takes its beginning, not to `onLine`.
   */
  pastCap?: Omit<PastCapOptions, 'headBytes'>;
}

/** What ends the line that the byte bound cut (its first part, kept). */
export const CUT_LINE = ' [cut here: the output limit]';

/** Bytes of a line's beginning that `longLine.begins` is given. */
export const LONG_LINE_HEAD_BYTES = 64;

export class LineSplitter {
  private pending: Buffer[] = [];
  private pendingBytes = 0;
  private keptBytes = 0;
  private droppedBytes = 0;
  private truncated = false;
  private readonly maxLineBytes: number;
  /** The bound of the line being read, once it went past maxLineBytes (0: not decided yet). */
  private lineBound = 0;
  private readonly pastCap: PastCapLines | null;

  constructor(private readonly options: LineSplitterOptions) {
    this.maxLineBytes = options.maxLineBytes ?? SERVICE_BOUNDS.outputLineBytes;
    this.pastCap = options.pastCap ? new PastCapLines({ ...options.pastCap, headBytes: LONG_LINE_HEAD_BYTES }) : null;
  }

  get wasTruncated(): boolean {
    return this.truncated;
  }

  get dropped(): number {
    return this.droppedBytes;
  }

  push(chunk: Buffer): void {
    if (this.truncated) {
      this.droppedBytes += chunk.length;
      this.pastCap?.push(chunk);
      return;
    }
    const room = this.options.maxBytes - this.keptBytes;
    let data = chunk;
    if (chunk.length > room) {
      data = chunk.subarray(0, room);
      this.droppedBytes += chunk.length - room;
    }
    this.keptBytes += data.length;
    let start = 0;
    for (let i = data.indexOf(10); i !== -1; i = data.indexOf(10, start)) {
      this.appendPending(data.subarray(start, i));
      this.flushPending();
      start = i + 1;
    }
    if (start < data.length) this.appendPending(data.subarray(start));
    if (data.length < chunk.length) {
      // the line the bound cuts is emitted as far as it goes, said cut (it must not read as a whole
      // line), unless it is one read past the cap: then it is read whole there
      if (this.pendingBytes > 0) {
        const head = Buffer.concat(this.pending, this.pendingBytes).subarray(0, LONG_LINE_HEAD_BYTES).toString('utf8');
        if (this.pastCap && this.options.pastCap!.wanted(head)) {
          this.pastCap.startWith(this.pending);
          this.pending = [];
          this.pendingBytes = 0;
          this.lineBound = 0;
        } else {
          this.flushPending(CUT_LINE);
        }
      }
      this.truncated = true;
      this.options.onTruncated(this.keptBytes);
      this.pastCap?.push(chunk.subarray(data.length));
    }
  }

  /** End of stream: emits a last line that had no newline. */
  end(): void {
    if (this.pendingBytes > 0) this.flushPending();
    this.pastCap?.end();
  }

  private appendPending(part: Buffer): void {
    let rest = part;
    while (this.pendingBytes + rest.length > (this.lineBound || this.maxLineBytes)) {
      if (!this.lineBound) {
        // decided once per line, when it first goes past the common bound
        const long = this.options.longLine;
        const head = Buffer.concat([...this.pending, rest.subarray(0, LONG_LINE_HEAD_BYTES)]).subarray(0, LONG_LINE_HEAD_BYTES).toString('utf8');
        this.lineBound = long && long.maxBytes > this.maxLineBytes && long.begins(head) ? long.maxBytes : this.maxLineBytes;
        continue;
      }
      const take = this.lineBound - this.pendingBytes;
      this.pending.push(rest.subarray(0, take));
      this.pendingBytes += take;
      this.flushPending();
      rest = rest.subarray(take);
    }
    if (rest.length) {
      this.pending.push(rest);
      this.pendingBytes += rest.length;
    }
  }

  private flushPending(suffix = ''): void {
    const buf = Buffer.concat(this.pending, this.pendingBytes);
    this.pending = [];
    this.pendingBytes = 0;
    this.lineBound = 0;
    let text = buf.toString('utf8');
    if (text.endsWith('\r')) text = text.slice(0, -1);
    this.options.onLine(text + suffix);
  }
}
