/**
 * The bytes of one growing CSV log -> its whole record lines, numbered as in the file, for the
 * live trace channel (docs/build-service-api.md "Trace channel"). The bytes come from a sandbox:
 * memory stays bounded whatever they are (a partial last line is kept only up to MAX_LINE_CHARS
 * bytes; a longer line is sent cut, with a marker, once, and the rest of it is skipped up to its
 * newline), and nothing here throws on them.
 *
 * The same lines as the trace reader's parseLogFile (trace/parse.ts) reads from the whole file:
 * the header (line 1) and empty lines are counted, not sent; a trailing `\r` is dropped. A file
 * whose line 1 is not the runtime's header is no log (a module's code made it): its line 1 is
 * sent (the readers take a line 1 for that: trace/parse.ts notALogRecord) and none after it.
 */
import { CSV_HEADER, MAX_LINE_CHARS } from '../trace/parse.js';
import type { TraceLine } from './job-events.js';

/** Appended to a line cut at MAX_LINE_CHARS bytes (the reader then sees more than MAX_LINE_CHARS characters). */
export const CUT_MARK = `…[line cut by the build service: longer than ${MAX_LINE_CHARS} bytes]`;

export class TraceLineSplitter {
  /** Number of the line being read (1-based). */
  private lineNo = 1;
  private partial: Buffer[] = [];
  private partialBytes = 0;
  /** The current line was already sent cut: its bytes are skipped up to its newline. */
  private skipping = false;
  /** Its line 1 is not the runtime's header: no line after it is sent. */
  private refused = false;
  /** Line 1 of a refused file that count() consumed (nobody was receiving): sent by the next push(). */
  private refusedLine: string | undefined;

  /**
   * @param file     the log's name, carried by every line
   * @param quietUntil byte offset of the file up to which lines are counted but not sent (what
   *                 the file held before this run started)
   */
  constructor(
    readonly file: string,
    private quietUntil = 0,
  ) {}

  /** Number of the line being read (1-based). */
  get nextLine(): number {
    return this.lineNo;
  }

  /** Bytes consumed so far (the file offset of the next byte). */
  offset = 0;

  /** Feeds the next bytes of the file; returns the lines they complete (and a cut one, if any). */
  push(chunk: Buffer): TraceLine[] {
    const out: TraceLine[] = [];
    if (this.refusedLine !== undefined) {
      out.push({ file: this.file, line: 1, text: this.refusedLine });
      this.refusedLine = undefined;
    }
    let start = 0;
    while (start < chunk.length) {
      const nl = chunk.indexOf(10, start);
      const end = nl < 0 ? chunk.length : nl;
      if (nl >= 0 && !this.skipping && this.partialBytes === 0 && end - start <= MAX_LINE_CHARS) {
        // the whole line is in this chunk (the common case): decoded from it, no copy
        this.offset += end - start + 1;
        this.line(out, chunk, start, end);
        this.lineNo++;
        start = nl + 1;
        continue;
      }
      const piece = chunk.subarray(start, end);
      if (!this.skipping) {
        if (this.partialBytes + piece.length > MAX_LINE_CHARS) {
          // over-long: sent now, cut (a line of 10 MB, or one that never ends, is never held whole)
          const head = Buffer.concat([...this.partial, piece.subarray(0, MAX_LINE_CHARS - this.partialBytes)]);
          this.emit(out, head.toString('utf8') + CUT_MARK, this.offset + (end - start));
          this.partial = [];
          this.partialBytes = 0;
          this.skipping = true;
        } else if (piece.length) {
          this.partial.push(Buffer.from(piece)); // a copy: the caller reuses its read buffer
          this.partialBytes += piece.length;
        }
      }
      this.offset += end - start;
      if (nl < 0) break;
      this.offset += 1;
      if (!this.skipping) this.line(out, this.partial.length === 1 ? this.partial[0]! : Buffer.concat(this.partial));
      this.partial = [];
      this.partialBytes = 0;
      this.skipping = false;
      this.lineNo++;
      start = nl + 1;
    }
    return out;
  }

  /**
   * Consumes the next bytes of the file without making lines of them (nobody would receive them:
   * trace-tail.ts): counts their lines, so that the lines pushed later carry their numbers in the
   * file. A line begun before or left unfinished here is not sent (the rest of it is skipped up to
   * its newline). Returns the index in `chunk` where its last whole line starts, -1 when none.
   */
  count(chunk: Buffer): number {
    if (this.partialBytes > 0) {
      this.partial = [];
      this.partialBytes = 0;
      this.skipping = true;
    }
    let last = -1;
    let start = 0;
    if (this.lineNo === 1 && this.offset === 0 && !this.refused) this.countFirstLine(chunk);
    for (;;) {
      const nl = chunk.indexOf(10, start);
      if (nl < 0) {
        if (start < chunk.length) this.skipping = true;
        this.offset += chunk.length - start;
        return last;
      }
      if (!this.skipping) last = start;
      this.offset += nl + 1 - start;
      this.skipping = false;
      this.lineNo++;
      start = nl + 1;
    }
  }

  /**
   * The file ended (the run is over): a last line without its newline is a line too (as
   * parseLogFile reads it), marked `cut` (its writer was killed inside it).
   */
  end(): TraceLine[] {
    const out: TraceLine[] = [];
    if (!this.skipping && this.partialBytes > 0) {
      this.line(out, Buffer.concat(this.partial));
      const last = out[out.length - 1];
      if (last) last.cut = true;
    }
    this.partial = [];
    this.partialBytes = 0;
    this.skipping = true;
    return out;
  }

  /**
   * count() reads the file's first bytes (nobody receiving): its line 1 is checked all the same,
   * and a refused one kept (200 characters) for the next push(): a client attached later learns
   * that the file is no log. A line 1 not whole in the chunk is refused when its bytes so far are
   * not the beginning of the header.
   */
  private countFirstLine(chunk: Buffer): void {
    const nl = chunk.indexOf(10);
    let to = nl < 0 ? chunk.length : nl;
    if (nl >= 0 && to > 0 && chunk[to - 1] === 13) to--;
    const text = chunk.toString('utf8', 0, Math.min(to, MAX_LINE_CHARS));
    if (nl >= 0 ? text === CSV_HEADER : CSV_HEADER.startsWith(text)) return;
    this.refused = true;
    if ((nl < 0 ? chunk.length : nl + 1) > this.quietUntil) this.refusedLine = text.slice(0, 200);
  }

  /** The line in bytes [from, to) of `bytes` ends at this.offset: sent unless empty or the header (a trailing \r dropped). */
  private line(out: TraceLine[], bytes: Buffer, from = 0, to = bytes.length): void {
    if (this.refused) return;
    if (to > from && bytes[to - 1] === 13) to--;
    if (this.lineNo === 1) {
      // a log begins with the runtime's header: anything else refuses the file (its line 1 is sent, no later one)
      const header = to - from === CSV_HEADER.length && bytes.toString('latin1', from, to) === CSV_HEADER;
      if (header) return;
      this.refused = true;
    }
    // (an empty line 1 is sent too: the readers say the file is no log)
    if ((to === from && this.lineNo !== 1) || this.offset <= this.quietUntil) return;
    out.push({ file: this.file, line: this.lineNo, text: bytes.toString('utf8', from, to) });
  }

  private emit(out: TraceLine[], text: string, endOffset: number): void {
    if (this.refused) return;
    if (this.lineNo === 1) this.refused = true; // line 1 longer than any header: no log
    if (endOffset <= this.quietUntil) return;
    out.push({ file: this.file, line: this.lineNo, text });
  }
}
