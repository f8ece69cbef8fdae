/**
 * A recorded run's model (the CSV logs of a finished job, or of a workspace folder), built from
 * the logs' text read in place: each record line is folded as a range of its file's text
 * (MonitorModel.pushLineIn, as the live run's worker folds a trace event), in the order the trace
 * reader gives a run's records (parseTrace: mono_ns, then file name, then line; a line with no
 * readable time right after the line before it in its file), or, for the logs of a trace file, in
 * the file's own order (the order `contract trace FILE` tells them in).
 *
 * Parsing a 60 s run of a 1 kHz schema (some 840,000 records) into record objects first, then
 * sorting them on BigInt keys, made the page's heap grow by hundreds of MB and its collector stop
 * frames for up to 200 ms while the replay was built (docs/monitor-performance.md "Replaying a
 * recorded run"). Here the only per-line cost kept until the merge is a few typed-array slots.
 *
 * Built in steps (a generator that yields every `every` lines) so that its caller can let the
 * page draw between slices.
 */
import { LogClock, MinHeap, NOT_A_LOG_WHY, TRACE_KINDS, TWIN_LOGS_WHY, isLogHeaderIn, notALogRecord, parseRecordLine, recordLineEnd, twinLogs, type KnownRecord, type UnknownRecord } from '@contract-studio/build-service/trace';
import { piecesLength, type LogFile } from '../views/run-logs.js';
import { MonitorModel, type MonitorModelOptions } from './monitor-model.js';
import { digitsValue, scanLine, scanned } from './line-scan.js';

/**
 * The record lines of one log, in file order: ranges of its pieces and their sort keys. A log read
 * from its text is one piece; a download is in pieces of whole lines (views/run-logs.ts piecedLog),
 * read piece by piece and never joined (joining a 100 MB log held the page's frames).
 */
interface LogLines {
  name: string;
  /** Its first line is not the runtime's header: no log, none of its lines read (trace/parse.ts NOT_A_LOG_WHY). */
  notALog?: true;
  /** Its text in pieces, each ending at a line end (the last one: where the file ends). */
  pieces: readonly string[];
  n: number;
  /** The piece each line is in; from and to are offsets in it. */
  piece: Int32Array;
  from: Int32Array;
  to: Int32Array;
  /** 1-based line number in the file. */
  line: Int32Array;
  /**
   * A line's key is its mono_ns as two exact numbers, hi * 1e9 + lo (a mono_ns has up to 20
   * digits, more than a double holds), or the key of the line before it in the file when the
   * trace reader reads no time off it (the first lines' key is 0).
   */
  hi: Float64Array;
  lo: Float64Array;
  /**
   * What scanLine read of each line it accepted: the index of its kind in KINDS (0: not accepted,
   * or a sup_rule line, which is parsed), and its seven commas (as offsets from the line's start:
   * a line the scan accepts is at most MAX_LINE_CHARS long); the fold does not scan the line again.
   */
  kind: Uint8Array;
  commas: Uint16Array;
  /** The lines the trace reader reads no record of (by index): what it made of them, pushed as that. */
  refused: Map<number, UnknownRecord>;
  /** The order of its lines by key (stable), when they are not in key order already. */
  order: Int32Array | undefined;
  /** The index of its last line when the file ends inside it (no line end: its module was killed while writing it), else -1. */
  cutAt: number;
}

/** The trace table's kinds, from 1 (LogLines.kind). */
const KINDS = ['', ...TRACE_KINDS.map((k) => k.kind)];
const KIND_INDEX = new Map(KINDS.map((k, i) => [k, i]));

/**
 * Lines the trace reader cannot read in one log before the rest of it is left out (and said): a
 * run's log has none, but each line costs a few typed-array slots here, and a log of hundreds of
 * MB of short garbage lines would take the page's memory.
 */
export const MAX_UNREADABLE_LINES = 100_000;

/** Digits of mono_ns below the split: lo holds up to 9 of them, hi the rest (at most 11). */
const LO_DIGITS = 9;

/** Key of a line, set by keyOf: [hi, lo], or nothing read (the line is no known record). */
const key = { hi: 0, lo: 0 };

/** Reads the mono_ns digits text[from, to) into `key`. */
function setKey(text: string, from: number, to: number): void {
  const split = Math.max(from, to - LO_DIGITS);
  key.hi = split > from ? digitsValue(text, from, split) : 0;
  key.lo = digitsValue(text, split, to);
}

/** What keyOf found of a line. */
const enum Read {
  /** The trace reader reads no time off it (an unknown record). */
  None,
  /** A known record, parsed: its time is in `key`. */
  Parsed,
  /** A known record read by scanLine, which `scanned` holds: its time is in `key`. */
  Scanned,
}

/**
 * Whether the trace reader reads line text[from, to) as a known record (not `unknown`), and how it
 * was found out. The quick scan makes the reader's own checks of a line without a quoted field; a
 * `sup_rule` line (its detail has a form of its own) and any line the scan does not accept are
 * parsed.
 */
function keyOf(file: string, lineNo: number, text: string, from: number, to: number, clock: LogClock, refused: Map<number, UnknownRecord>, k: number): Read {
  if (scanLine(text, from, to, file) && scanned.kind !== 'sup_rule') {
    // the log's time check (log-clock.ts): a time it does not believe makes the line unreadable
    const why = clock.check(scanned.mono, text, scanned.comma[0]! + 1, scanned.comma[1]!);
    if (why !== undefined) {
      refused.set(k, { kind: 'unknown', file, line: lineNo, reason: why, text: text.slice(from, Math.min(to, from + 200)) });
      return Read.None;
    }
    setKey(text, from, scanned.comma[0]!);
    return Read.Scanned;
  }
  const r = parseRecordLine(file, lineNo, text.slice(from, to), clock);
  if (r.kind === 'unknown') {
    refused.set(k, r as UnknownRecord);
    return Read.None;
  }
  const mono = (r as KnownRecord).monoNs;
  setKey(mono, 0, mono.length);
  return Read.Parsed;
}

function grow<A extends Int32Array | Float64Array | Uint8Array | Uint16Array>(a: A): A {
  const b = new (a.constructor as new (n: number) => A)(a.length * 2);
  b.set(a);
  return b;
}

/** The record lines of a log (the trace reader's rule, recordLineEnd: header and empty lines are not records; a `\r` before a newline is not the line's). */
function* logLines(file: LogFile, every: number, maxUnreadable: number, leftOut: string[]): Generator<void, LogLines> {
  const name = file.name;
  const pieces = file.pieces ?? [file.text];
  const size = Math.max(16, Math.ceil(piecesLength(pieces) / 64));
  const l: LogLines = { name, pieces, n: 0, piece: new Int32Array(size), from: new Int32Array(size), to: new Int32Array(size), line: new Int32Array(size), hi: new Float64Array(size), lo: new Float64Array(size), kind: new Uint8Array(size), commas: new Uint16Array(size * 7), refused: new Map(), order: undefined, cutAt: -1 };
  const clock = new LogClock();
  let hi = 0;
  let lo = 0;
  let sorted = true;
  let unreadable = 0;
  let i = 0; // the line's index in the file
  lines: for (let p = 0; p < pieces.length; p++) {
    const text = pieces[p]!;
    const last = p === pieces.length - 1;
    for (let pos = 0; pos < text.length; i++) {
      let nl = text.indexOf('\n', pos);
      if (nl < 0) nl = text.length;
      const from = pos;
      if (i === 0 && !isLogHeaderIn(text, from, nl)) {
        // no log (a module's code made it): none of its lines is read, said first (recordedRunSteps);
        // its line 1 is its one unreadable line, as the trace reader reads it (parse.ts notALogRecord)
        l.notALog = true;
        l.refused.set(0, notALogRecord(name, text.slice(from, Math.min(nl, from + 200))));
        l.piece[0] = p;
        l.from[0] = from;
        l.to[0] = nl;
        l.line[0] = 1;
        l.n = 1;
        break lines;
      }
      const to = recordLineEnd(text, i, from, nl);
      pos = nl + 1;
      if (to < 0) continue;
      const read = keyOf(name, i + 1, text, from, to, clock, l.refused, l.n);
      if (read === Read.None && ++unreadable > maxUnreadable) {
        leftOut.push(`${name}: more than ${maxUnreadable} lines that are not trace records, the rest of it from line ${i + 1} left out`);
        break lines;
      }
      if (read !== Read.None) {
        if (key.hi < hi || (key.hi === hi && key.lo < lo)) sorted = false;
        hi = key.hi;
        lo = key.lo;
      }
      if (l.n === l.from.length) {
        l.piece = grow(l.piece);
        l.from = grow(l.from);
        l.to = grow(l.to);
        l.line = grow(l.line);
        l.hi = grow(l.hi);
        l.lo = grow(l.lo);
        l.kind = grow(l.kind);
        l.commas = grow(l.commas);
      }
      const k = l.n++;
      if (read === Read.Scanned) {
        l.kind[k] = KIND_INDEX.get(scanned.kind)!;
        for (let j = 0; j < 7; j++) l.commas[k * 7 + j] = scanned.comma[j]! - from;
      }
      if (last && nl === text.length) l.cutAt = k; // the file's last line, with no line end
      l.piece[k] = p;
      l.from[k] = from;
      l.to[k] = to;
      l.line[k] = i + 1;
      l.hi[k] = hi;
      l.lo[k] = lo;
      if (l.n % every === 0) yield;
    }
  }
  // a log is in time order but for hostile or clock-stepped lines
  if (!sorted) l.order = Int32Array.from(Array.from({ length: l.n }, (_, k) => k).sort((a, b) => l.hi[a]! - l.hi[b]! || l.lo[a]! - l.lo[b]! || a - b));
  return l;
}

/** A recorded run's model, and what of its logs was left out (said in the run's label). */
export interface RecordedRun {
  model: MonitorModel;
  leftOut: string[];
}

/**
 * Builds the model of a recorded run from its logs, yielding every `every` lines read or folded.
 * Gives the same model as parseTrace's records pushed in order, but for a log with more than
 * `maxUnreadable` lines that are not records, whose rest is left out (and said). The model is
 * made with `options`. `fileOrder`: the logs of a trace file (build-service trace/jsonl.ts
 * TraceFileLogs.order: the log of each record line, an index in `files`, in the file's order):
 * their lines are folded in that order, the order `contract trace FILE` tells them in, not merged
 * by time (at one time, a simulation's causes come before their effects in the file, whatever
 * their logs' names). `whole` false: a log was read in part (the replay's bound), so the records'
 * end is not the run's: what only the run's end says (ORD gone, undos it never served:
 * MonitorModel.recordsEnded) is not said.
 */
export function* recordedRunSteps(files: readonly LogFile[], every = 2000, options?: MonitorModelOptions, maxUnreadable = MAX_UNREADABLE_LINES, fileOrder?: Uint16Array, whole = true): Generator<void, RecordedRun> {
  const byName = files.map((_, i) => i).sort((a, b) => (files[a]!.name < files[b]!.name ? -1 : files[a]!.name > files[b]!.name ? 1 : 0));
  const sorted = byName.map((i) => files[i]!);
  const logs: LogLines[] = [];
  const notes: string[] = [];
  for (const file of sorted) logs.push(yield* logLines(file, every, maxUnreadable, notes));
  // what matters first: the files that are no log, and two logs of one module (the files that are logs)
  const notLogs = logs.filter((l) => l.notALog).map((l) => `${l.name}: ${NOT_A_LOG_WHY}`);
  const leftOut: string[] = [...notLogs, ...twinLogNotes(logs.filter((l) => !l.notALog).map((l) => l.name)), ...notes];
  // each piece of each log is a text of its own to the model (its textId)
  const firstTextId: number[] = [];
  logs.reduce((id, l, f) => ((firstTextId[f] = id), id + l.pieces.length), 0);
  const model = new MonitorModel(options);
  /** Folds line i (an index in file order) of log f. */
  const fold = (f: number, i: number): void => {
    const l = logs[f]!;
    const piece = l.piece[i]!;
    const text = l.pieces[piece]!;
    const textId = firstTextId[f]! + piece;
    const from = l.from[i]!, to = l.to[i]!;
    const kind = l.kind[i]!;
    if (kind) {
      // what keyOf's scan read, put back: the line is not scanned again
      for (let j = 0; j < 7; j++) scanned.comma[j] = from + l.commas[i * 7 + j]!;
      scanned.kind = KINDS[kind]!;
      scanned.mono = digitsValue(text, from, scanned.comma[0]!);
      scanned.to = to;
    }
    const cut = i === l.cutAt;
    // a cut line goes the way that marks it (pushLineIn scans it again: it is one line of a run)
    const refused = l.refused.get(i);
    if (refused) model.push(refused);
    else if (cut || !kind || !model.pushScanned(text, from, to, textId)) model.pushLineIn(l.name, l.line[i]!, text, from, to, textId, cut, true);
  };
  const at = logs.map(() => 0);
  let folded = 0;
  if (fileOrder) {
    // a trace file: its order, each log's lines in their own order (a log left out past its bound of unreadable lines: its rest skipped)
    const logOf = new Int32Array(files.length);
    byName.forEach((i, f) => (logOf[i] = f));
    for (let k = 0; k < fileOrder.length; k++) {
      const f = fileOrder[k]! < files.length ? logOf[fileOrder[k]!]! : -1;
      if (f < 0 || at[f]! >= logs[f]!.n) continue;
      fold(f, at[f]!++);
      if (++folded % every === 0) yield;
    }
    // (lines the order does not name: none when it is the file's; folded after, each log's in its order)
    for (let f = 0; f < logs.length; f++) {
      while (at[f]! < logs[f]!.n) {
        fold(f, at[f]!++);
        if (++folded % every === 0) yield;
      }
    }
    if (whole) model.recordsEnded(); // (logs read in part: their ends are not the run's)
    return { model, leftOut };
  }
  // merge: a heap of the logs by their next line (key, then file order)
  const index = (f: number): number => logs[f]!.order?.[at[f]!] ?? at[f]!;
  const heap = new MinHeap<number>((f, g) => {
    const a = logs[f]!, i = index(f);
    const b = logs[g]!, j = index(g);
    const ah = a.hi[i]!, bh = b.hi[j]!;
    if (ah !== bh) return ah < bh;
    const al = a.lo[i]!, bl = b.lo[j]!;
    return al < bl || (al === bl && f < g);
  });
  logs.forEach((l, f) => l.n && heap.push(f));
  while (heap.size) {
    const f = heap.peek()!;
    fold(f, index(f));
    if (++at[f]! >= logs[f]!.n) heap.pop();
    else heap.topChanged();
    if (++folded % every === 0) yield;
  }
  if (whole) model.recordsEnded();
  return { model, leftOut };
}

/**
 * A module with more than one log among `names` (named as the runtime names a log): said, as
 * `contract trace` says it — a run writes one log per module, so the others are another run's, or
 * a file a module's code wrote under another module's name (forged deadline misses, rule changes).
 */
export function twinLogNotes(names: readonly string[]): string[] {
  return [...twinLogs(names)].map(([m, files]) => `${m}: ${files.length} logs of it (${files.slice(0, 3).join(', ')}${files.length > 3 ? ', ...' : ''}), read as one: ${TWIN_LOGS_WHY}`);
}
