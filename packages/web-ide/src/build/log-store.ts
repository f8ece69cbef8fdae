/**
 * Log lines of a build/run, kept in a bounded buffer with an incrementally maintained filtered
 * index (filter by source = module/build/service, and by stream). Appending is O(1) amortised,
 * so 10k lines/s cost nothing noticeable; the view renders only the visible rows. Past `capacity`
 * (a quarter more, then back to it) the oldest lines are let go and counted (`dropped`): the
 * panel says how many, with the job's whole log to download (build-panel.ts).
 */
export interface LogLine {
  t: number;
  step: string;
  source: string;
  stream: 'stdout' | 'stderr' | 'system';
  line: string;
}

export interface LogFilter {
  /** Sources hidden (empty = show all). */
  hiddenSources: Set<string>;
  hiddenStreams: Set<string>;
  text: string;
}

export class LogStore {
  private lines: LogLine[] = [];
  private offset = 0; // number of lines dropped from the front
  private visible: number[] = []; // absolute indexes of lines passing the filter
  readonly sources = new Map<string, number>();
  filter: LogFilter = { hiddenSources: new Set(), hiddenStreams: new Set(), text: '' };
  version = 0;
  /** Changes when visible line n may no longer be the line it was (clear, filter, the oldest lines
   *  dropped); between two changes the visible lines only grow at the end. */
  renumbered = 0;

  constructor(readonly capacity = 200_000) {}

  get total(): number {
    return this.lines.length;
  }

  /** Lines let go from the front since the last clear (the bound), oldest first. */
  get dropped(): number {
    return this.offset;
  }

  get visibleCount(): number {
    return this.visible.length;
  }

  clear(): void {
    this.lines = [];
    this.offset = 0;
    this.visible = [];
    this.sources.clear();
    this.version++;
    this.renumbered++;
  }

  private passes(l: LogLine): boolean {
    const f = this.filter;
    if (f.hiddenSources.has(l.source) || f.hiddenStreams.has(l.stream)) return false;
    return !f.text || l.line.toLowerCase().includes(f.text);
  }

  push(l: LogLine): void {
    const abs = this.offset + this.lines.length;
    this.lines.push(l);
    this.sources.set(l.source, (this.sources.get(l.source) ?? 0) + 1);
    if (this.passes(l)) this.visible.push(abs);
    if (this.lines.length > this.capacity * 1.25) this.compact();
    this.version++;
  }

  private compact(): void {
    const drop = this.lines.length - this.capacity;
    this.lines = this.lines.slice(drop);
    this.offset += drop;
    const firstKept = this.offset;
    let i = 0;
    while (i < this.visible.length && this.visible[i]! < firstKept) i++;
    this.visible = this.visible.slice(i);
    this.renumbered++;
  }

  setFilter(filter: Partial<LogFilter>): void {
    this.filter = { ...this.filter, ...filter, text: (filter.text ?? this.filter.text).toLowerCase() };
    this.visible = [];
    for (let i = 0; i < this.lines.length; i++) if (this.passes(this.lines[i]!)) this.visible.push(this.offset + i);
    this.version++;
    this.renumbered++;
  }

  /** The n-th visible line. */
  visibleAt(n: number): LogLine | undefined {
    const abs = this.visible[n];
    return abs === undefined ? undefined : this.lines[abs - this.offset];
  }
}
