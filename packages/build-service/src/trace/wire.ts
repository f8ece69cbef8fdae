/**
 * The trace event's wire form (docs/build-service-api.md "Trace channel"): how a batch of record
 * lines travels on the job's SSE and WebSocket streams. A 1 kHz schema writes about 15,000 records
 * a second; sent as one JSON object per record ({"file","line","text"}), the service's
 * serializing, the socket traffic and above all the client's JSON.parse of that many objects cost
 * the machine enough to be seen in the modules' release lateness (docs/monitor-performance.md, "What
 * watching costs the run"). The wire form is therefore columnar:
 *
 *   files  the log files named in this batch, each once
 *   runs   [fileIndex, firstLine, count, ...]: consecutive records of one file (lines firstLine,
 *          firstLine + 1, ...), in the batch's order
 *   text   the records' lines joined with "\n" (a record line holds no newline)
 *   cut    (optional) the indexes of the records that were their log's last line, with no line end
 *   unsent (optional) [index, count, ...]: the entry at that index stands for `count` lines of its
 *          file, from its line on, that are no record and that the service did not send (past
 *          its bound of such lines, SERVICE_BOUNDS.traceUnreadableKept); its text is empty
 *
 * so that a client parses one string and splits it. Browser-safe (no Node imports): the IDE's
 * Monitor's live-run worker (web-ide monitor/live-follower.ts) decodes with it too.
 */

/** One whole record line of a module's CSV log (docs/runtime-api.md "Trace records"), as the run wrote it. */
export interface TraceLine {
  /** The log file's name (`<MODULE>_<date>.csv`). */
  file: string;
  /** 1-based line number in that file (the header is line 1). */
  line: number;
  /** The CSV line without its newline; readers parse it with the trace reader's parseRecordLine. */
  text: string;
  /**
   * The line was its log's last and had no line end when the run was over (its module was killed
   * while writing it): the record may have lost its end (TraceRecordBase.cut).
   */
  cut?: true;
  /**
   * This entry is no line but stands for `unsent` lines of its file, from `line` on, that are no
   * record (they do not begin with a `mono_ns`) and were not sent: the service sends a run's first
   * SERVICE_BOUNDS.traceUnreadableKept such lines and counts the others (a module writing junk into
   * `logs/` must not fill the stream, nor the records kept for replay). Its text is empty.
   */
  unsent?: number;
}

/** A batch of record lines on the wire. */
export interface TraceWire {
  files: string[];
  runs: number[];
  text: string;
  /** Indexes (0-based, ascending) of the batch's records that are `cut`; absent when none is. */
  cut?: number[];
  /** [index, count, ...] (indexes ascending): the entries that stand for `count` unsent lines (TraceLine.unsent); absent when none does. */
  unsent?: number[];
}

/** The wire form of a batch (its records' order is kept exactly). */
export function encodeTraceRecords(records: readonly TraceLine[]): TraceWire {
  const files: string[] = [];
  const index = new Map<string, number>();
  const runs: number[] = [];
  const texts = new Array<string>(records.length);
  const cut: number[] = [];
  const unsent: number[] = [];
  let runFile = -1;
  let nextLine = -1;
  let countAt = -1;
  for (let i = 0; i < records.length; i++) {
    const r = records[i]!;
    texts[i] = r.unsent ? '' : r.text;
    if (r.cut) cut.push(i);
    let fi = index.get(r.file);
    if (fi === undefined) {
      fi = files.length;
      files.push(r.file);
      index.set(r.file, fi);
    }
    if (fi === runFile && r.line === nextLine) {
      runs[countAt]!++;
    } else {
      runs.push(fi, r.line, 1);
      countAt = runs.length - 1;
      runFile = fi;
    }
    // the line after an unsent stretch starts a run of its own: its number is written, not counted
    if (r.unsent) {
      unsent.push(i, r.unsent);
      nextLine = -1;
    } else nextLine = r.line + 1;
  }
  const wire: TraceWire = { files, runs, text: texts.join('\n') };
  if (cut.length) wire.cut = cut;
  if (unsent.length) wire.unsent = unsent;
  return wire;
}

/** A trace event's payload that is not a well-formed wire batch. */
export class TraceWireError extends Error {
  constructor(message: string) {
    super(`trace event: ${message}`);
    this.name = 'TraceWireError';
  }
}

/**
 * Calls `fn` for each record of a wire batch, in order, with the batch's text and the record's
 * range in it (`text.slice(from, to)` is the line): a reader that checks the line in place cuts
 * nothing out of the batch. Returns how many records there were. Checks the whole shape first
 * (files are strings, runs are triples of whole numbers naming a listed file, the text holds
 * exactly as many lines as the runs count) and throws TraceWireError otherwise, before any call.
 */
export function forEachTraceLine(wire: unknown, fn: (file: string, line: number, text: string, from: number, to: number, cut: boolean, unsent: number) => void): number {
  const w = wire as Partial<TraceWire> | null;
  if (!w || typeof w !== 'object') throw new TraceWireError('not an object');
  const { files, runs, text, cut, unsent } = w;
  if (!Array.isArray(files) || !files.every((f) => typeof f === 'string')) throw new TraceWireError('"files" is not a list of file names');
  if (!Array.isArray(runs) || runs.length % 3 !== 0) throw new TraceWireError('"runs" is not a list of [file, first line, count] triples');
  if (typeof text !== 'string') throw new TraceWireError('"text" is not a string');
  let total = 0;
  for (let i = 0; i < runs.length; i += 3) {
    const fi = runs[i];
    const first = runs[i + 1];
    const count = runs[i + 2];
    if (!Number.isSafeInteger(fi) || fi! < 0 || fi! >= files.length) throw new TraceWireError(`run ${i / 3} names no listed file (${String(fi)})`);
    if (!Number.isSafeInteger(first) || first! < 1) throw new TraceWireError(`run ${i / 3} starts at line ${String(first)}`);
    if (!Number.isSafeInteger(count) || count! < 1) throw new TraceWireError(`run ${i / 3} counts ${String(count)} records`);
    total += count!;
  }
  if (total === 0) {
    if (text !== '') throw new TraceWireError('text without records');
    return 0;
  }
  let lines = 1;
  for (let nl = text.indexOf('\n'); nl >= 0; nl = text.indexOf('\n', nl + 1)) lines++;
  if (lines !== total) throw new TraceWireError(`the runs count ${total} records, the text holds ${lines} lines`);
  if (cut !== undefined && (!Array.isArray(cut) || cut.length > total || cut.some((c, i) => !Number.isSafeInteger(c) || c < 0 || c >= total || (i > 0 && c <= cut[i - 1]!)))) {
    throw new TraceWireError('"cut" is not an ascending list of the batch\'s record indexes');
  }
  if (unsent !== undefined && (!Array.isArray(unsent) || unsent.length % 2 !== 0 || unsent.length > total * 2
    || unsent.some((v, i) => !Number.isSafeInteger(v) || (i % 2 === 0 ? v < 0 || v >= total || (i > 0 && v <= unsent[i - 2]!) : v < 1)))) {
    throw new TraceWireError('"unsent" is not a list of [entry index, line count] pairs, ascending');
  }
  let from = 0;
  let record = 0;
  let nextCut = 0;
  let nextUnsent = 0;
  for (let i = 0; i < runs.length; i += 3) {
    const file = files[runs[i]!]!;
    const first = runs[i + 1]!;
    const count = runs[i + 2]!;
    for (let j = 0; j < count; j++, record++) {
      let to = text.indexOf('\n', from);
      if (to < 0) to = text.length;
      const isCut = cut !== undefined && cut[nextCut] === record;
      if (isCut) nextCut++;
      let lines = 0;
      if (unsent !== undefined && unsent[nextUnsent] === record) {
        lines = unsent[nextUnsent + 1]!;
        nextUnsent += 2;
      }
      fn(file, first + j, text, from, to, isCut, lines);
      from = to + 1;
    }
  }
  return total;
}

/** forEachTraceRecord with each record's line cut out of the batch (same checks, same order). */
export function forEachTraceRecord(wire: unknown, fn: (file: string, line: number, text: string, cut: boolean, unsent: number) => void): number {
  return forEachTraceLine(wire, (file, line, text, from, to, cut, unsent) => fn(file, line, text.slice(from, to), cut, unsent));
}

/** The records of a wire batch, in order (throws TraceWireError on a malformed batch). */
export function decodeTraceRecords(wire: unknown): TraceLine[] {
  const out: TraceLine[] = [];
  forEachTraceRecord(wire, (file, line, text, cut, unsent) => {
    const l: TraceLine = { file, line, text };
    if (cut) l.cut = true;
    if (unsent) l.unsent = unsent;
    out.push(l);
  });
  return out;
}
