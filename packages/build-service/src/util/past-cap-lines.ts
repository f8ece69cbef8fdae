/**
 * The lines of a stream past its kept-output cap (LineSplitter's maxBytes) that are still read,
 * though kept nowhere: those whose first LONG_LINE_HEAD_BYTES bytes `wanted` takes (a build's gcc
 * JSON diagnostics and make's directory lines, which tell where gcc ran), each given whole up to
 * its own bound (`boundOf`: a longer one is given as its head, the rest of it dropped). Every other
 * line is dropped as it streams by: nothing of it is held. The cap bounds what the log keeps, not
 * what the diagnostics reader sees (docs/build-service-api.md, the build step's output).
 */
export interface PastCapOptions {
  /** Bytes of a line's beginning that `wanted` and `boundOf` are given. */
  headBytes: number;
  wanted(head: string): boolean;
  /** The bytes of a wanted line given at most. */
  boundOf(head: string): number;
  onLine(line: string): void;
}

export class PastCapLines {
  private pending: Buffer[] = [];
  private pendingBytes = 0;
  /** The current line: undecided (its head not whole yet), wanted up to `bound` bytes, or dropped to its end. */
  private state: 'head' | 'wanted' | 'dropped' = 'head';
  private bound = 0;

  constructor(private readonly options: PastCapOptions) {}

  /** Bytes of the line in progress when the cap was reached (its beginning, already read). */
  startWith(parts: readonly Buffer[]): void {
    for (const p of parts) this.take(p);
  }

  push(chunk: Buffer): void {
    let start = 0;
    for (let i = chunk.indexOf(10); i !== -1; i = chunk.indexOf(10, start)) {
      this.take(chunk.subarray(start, i));
      this.endLine();
      start = i + 1;
    }
    if (start < chunk.length) this.take(chunk.subarray(start));
  }

  /** End of stream: a last wanted line without its newline is given. */
  end(): void {
    this.endLine();
  }

  private take(part: Buffer): void {
    let rest = part;
    if (this.state === 'head') {
      const room = this.options.headBytes - this.pendingBytes;
      this.hold(rest.subarray(0, room));
      if (this.pendingBytes < this.options.headBytes) return;
      this.decide();
      rest = rest.subarray(room);
    }
    if (this.state === 'wanted') this.hold(rest.subarray(0, Math.max(0, this.bound - this.pendingBytes)));
  }

  private decide(): void {
    const head = Buffer.concat(this.pending, this.pendingBytes).subarray(0, this.options.headBytes).toString('utf8');
    if (this.options.wanted(head)) {
      this.state = 'wanted';
      this.bound = this.options.boundOf(head);
    } else {
      this.state = 'dropped';
      this.pending = [];
      this.pendingBytes = 0;
    }
  }

  private hold(part: Buffer): void {
    if (!part.length) return;
    this.pending.push(part);
    this.pendingBytes += part.length;
  }

  private endLine(): void {
    if (this.state === 'head' && this.pendingBytes > 0) this.decide();
    if (this.state === 'wanted') {
      let text = Buffer.concat(this.pending, this.pendingBytes).subarray(0, this.bound).toString('utf8');
      if (text.endsWith('\r')) text = text.slice(0, -1);
      this.options.onLine(text);
    }
    this.pending = [];
    this.pendingBytes = 0;
    this.state = 'head';
    this.bound = 0;
  }
}
