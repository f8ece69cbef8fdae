/**
 * The monitor model: the trace records of one run (live, fed as they come, or a whole recorded
 * run) folded into the architecture's state (monitor-state.ts), with a time cursor.
 *
 * - `live` is the state after the last record; feeding a record costs one applyRecord (a live
 *   line is read in place: one of a kind the fold does not use is not even parsed, line-scan.ts;
 *   the kinds of every periodic cycle are folded from their fields, hot-line.ts).
 * - `stateAt(t)` is the state at any earlier time: the nearest checkpoint (a copy of the state
 *   taken every `checkpointEvery` records) plus the records after it, so scrubbing back costs at
 *   most one copy and `checkpointEvery` folds, whatever the run's length.
 * - Raw records are kept in chunks (one per checkpoint) up to `keepRecords`; on a longer run the
 *   oldest chunks go (their arrays are reused for the next stretch), except their notable records
 *   (rules, functions, schemas, holds, misses), so a state far back is exact for those and
 *   approximate (to the checkpoint) for counters.
 * - `marks` lists what the timeline marks (rule changes, schema (de)activations, deadline misses,
 *   overruns, function starts/stops), bounded.
 * Memory per record is therefore bounded by keepRecords, not by the run's length (a 1 kHz schema
 * for 60 s is about 1.5 million records).
 */
import { parseRecordLine, isRule, type KnownRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { FOLDED_KINDS, applyRecord, applyUnfolded } from './apply-record.js';
import { scanLine, scanned } from './line-scan.js';
import { HOT_KINDS, applyHotLine } from './hot-line.js';
import { cloneState, emptyState, type MonitorState, type Ns } from './monitor-state.js';
import { marksIn, type MonitorView } from './model-view.js';

export interface MonitorModelOptions {
  checkpointEvery?: number;
  keepRecords?: number;
  maxMarks?: number;
}

export interface Mark {
  t: Ns;
  kind: 'rule' | 'schema' | 'miss' | 'overrun' | 'function';
  /** Where: the supervisor or schema. */
  where: string;
  label: string;
  /** Rule marks: active (true) or inactive. */
  on?: boolean;
}

/** Texts a chunk looks back through for the one a record's line is in. */
const RECENT_TEXTS = 8;

interface Timed {
  t: Ns;
  r: TraceRecord;
}

/**
 * The raw records between two checkpoints (at most `capacity`). A live line is kept as a range of
 * the text it came in (the trace event's, usually shared by hundreds of lines), and parsed again
 * when a scrub back replays it: keeping it cuts nothing out, copies nothing, and leaves the
 * collector a few typed arrays per chunk instead of an object per record.
 */
class Chunk {
  private n = 0;
  private readonly times: Float64Array;
  /** Index in `sources` of the text a record's line is in, or -1: the record is in `records`. */
  private readonly source: Int32Array;
  private readonly from: Int32Array;
  private readonly to: Int32Array;
  private readonly sources: string[] = [];
  /** The caller's id of each text in `sources` (texts are told apart by id: comparing two long texts could read them whole). */
  private readonly sourceIds: number[] = [];
  private records: Array<TraceRecord | undefined> | undefined;

  constructor(capacity: number) {
    this.times = new Float64Array(capacity);
    this.source = new Int32Array(capacity);
    this.from = new Int32Array(capacity);
    this.to = new Int32Array(capacity);
  }

  get length(): number {
    return this.n;
  }

  /** Empties the chunk for the records of another stretch (its arrays are reused: no new garbage per chunk). */
  reset(): this {
    this.n = 0;
    this.sources.length = 0;
    this.sourceIds.length = 0;
    this.records = undefined;
    return this;
  }

  /** A record kept as text.slice(from, to); `textId` names `text` (recent texts are looked up by it). */
  pushLine(t: Ns, text: string, from: number, to: number, textId: number): void {
    const i = this.n++;
    const ids = this.sourceIds;
    // the text is one of the last few (a recorded run's lines come from a few logs in turn)
    let k = ids.length - 1;
    const stop = Math.max(0, k - (RECENT_TEXTS - 1));
    while (k >= stop && ids[k] !== textId) k--;
    if (k < stop) {
      k = this.sources.push(text) - 1;
      ids.push(textId);
    }
    this.times[i] = t;
    this.source[i] = k;
    this.from[i] = from;
    this.to[i] = to;
  }

  push(t: Ns, r: TraceRecord): void {
    const i = this.n++;
    this.times[i] = t;
    this.source[i] = -1;
    (this.records ??= [])[i] = r;
  }

  /** The records with time <= t, in order. */
  *upTo(t: Ns): Generator<{ t: Ns; r: TraceRecord }> {
    for (let i = 0; i < this.n; i++) {
      const at = this.times[i]!;
      if (at > t) return;
      const k = this.source[i]!;
      yield { t: at, r: k < 0 ? this.records![i]! : parseRecordLine('', 0, this.sources[k]!.slice(this.from[i], this.to[i])) };
    }
  }
}

interface Checkpoint {
  /** Index of the first record not folded into `state`. */
  index: number;
  t: Ns;
  state: MonitorState;
}

const NOTABLE = new Set(['sup_rule', 'supervisor', 'scheduler', 'ord_deadline_miss', 'module_hold', 'flow_hold', 'module_started', 'module_exit']);

export class MonitorModel implements MonitorView {
  readonly live: MonitorState = emptyState();
  readonly marks: Mark[] = [];
  /** mono_ns of the first record: time 0. */
  t0: number | undefined;
  private readonly every: number;
  private readonly keep: number;
  private readonly maxMarks: number;
  private readonly checkpoints: Checkpoint[] = [];
  /** chunks[i] holds records [firstChunk + i) * every ...; dropped chunks leave their notable records. */
  private chunks: Chunk[] = [];
  private firstChunk = 0;
  private kept = 0;
  private readonly notable: Timed[] = [];
  private count = 0;
  /** Bumped on every change, so a view redraws only when something happened. */
  version = 0;
  /** Ids of the texts fed without one (each a text of its own: negative, the callers' ids are not). */
  private anonymousText = 0;

  constructor(opts: MonitorModelOptions = {}) {
    this.every = Math.max(16, opts.checkpointEvery ?? 1024);
    this.keep = Math.max(this.every * 2, opts.keepRecords ?? 200_000);
    this.maxMarks = opts.maxMarks ?? 20_000;
    this.checkpoints.push({ index: 0, t: 0, state: emptyState() });
    this.chunks.push(new Chunk(this.every));
  }

  get recordCount(): number {
    return this.count;
  }

  /** Time of the last record (ns since the first). */
  get end(): Ns {
    return this.live.t;
  }

  /** Whether states before `t` are approximate (their raw records were dropped). */
  exactAt(t: Ns): boolean {
    const cp = this.checkpointBefore(t);
    return cp.index / this.every >= this.firstChunk;
  }

  /** One CSV line of the live trace channel (job-events.ts TraceLine). */
  pushLine(file: string, line: number, text: string): void {
    this.pushLineIn(file, line, text, 0, text.length);
  }

  /**
   * The line text.slice(from, to) of the live trace channel, read in place (line-scan.ts): a
   * line of a kind the fold does not use is not parsed (its time is read off it), one of the
   * kinds a periodic schema writes at every cycle is folded from its fields in place
   * (hot-line.ts); any other line, and any the quick readers do not accept, is parsed.
   * `textId` (a whole number) names `text` when several lines are ranges of one text: the model
   * keeps each text once per chunk (a trace event's, a recorded log's); without it the text is
   * taken as one of its own.
   */
  pushLineIn(file: string, line: number, text: string, from: number, to: number, textId = --this.anonymousText): void {
    if (scanLine(text, from, to) && this.pushScanned(text, from, to, textId)) return;
    const r = parseRecordLine(file, line, text.slice(from, to));
    const t = this.timeOfRecord(r);
    this.keepLine(t, text, from, to, textId);
    this.fold(t, r);
  }

  /**
   * The line text.slice(from, to) that scanLine has accepted, `scanned` holding what it read:
   * folded (and true) when it is of a kind read in place; false, and nothing done, when it is of
   * a kind that is parsed (pushLineIn then parses it).
   */
  pushScanned(text: string, from: number, to: number, textId: number): boolean {
    const kind = scanned.kind;
    if (!FOLDED_KINDS.has(kind)) {
      const t = this.timeOf(scanned.mono);
      this.keepLine(t, text, from, to, textId);
      applyUnfolded(this.live, t);
      return true;
    }
    if (HOT_KINDS.has(kind)) {
      const t = this.timeOf(scanned.mono);
      this.keepLine(t, text, from, to, textId);
      applyHotLine(this.live, text, t, this.t0 ?? 0);
      return true;
    }
    return false;
  }

  /** A parsed record (kept as it is). */
  push(r: TraceRecord): void {
    const t = this.timeOfRecord(r);
    this.beforeKeep();
    this.chunks[this.chunks.length - 1]!.push(t, r);
    this.fold(t, r);
  }

  private timeOfRecord(r: TraceRecord): Ns {
    return r.kind === 'unknown' ? this.live.t : this.timeOf(Number((r as KnownRecord).monoNs));
  }

  /** The time (ns since the first record) of a record written at `mono`. */
  private timeOf(mono: number): Ns {
    if (!Number.isFinite(mono)) return this.live.t;
    this.t0 ??= mono;
    // records come in mono_ns order; one that does not (hostile input) is held at the last time
    return Math.max(this.live.t, mono - this.t0);
  }

  /** Counts a record about to be kept (a checkpoint first when a chunk is full). */
  private beforeKeep(): void {
    if (this.count > 0 && this.count % this.every === 0) this.checkpoint();
    this.kept++;
    this.count++;
    this.version++;
  }

  private keepLine(t: Ns, text: string, from: number, to: number, textId: number): void {
    this.beforeKeep();
    this.chunks[this.chunks.length - 1]!.pushLine(t, text, from, to, textId);
  }

  /** Folds a parsed record into `live` (and the notable ones into marks). */
  private fold(t: Ns, r: TraceRecord): void {
    if (NOTABLE.has(r.kind)) this.notableRecord({ t, r });
    applyRecord(this.live, r, t, this.t0 ?? 0);
  }

  pushAll(records: Iterable<TraceRecord>): void {
    for (const r of records) this.push(r);
  }

  /**
   * The state at time t (ns since the first record): every record with time <= t folded in.
   * Returns `live` itself when t is at or after the end (do not mutate it).
   */
  stateAt(t: Ns): MonitorState {
    if (t >= this.live.t) return this.live;
    const cp = this.checkpointBefore(t);
    const s = cloneState(cp.state);
    const chunk = cp.index / this.every - this.firstChunk;
    const t0 = this.t0 ?? 0;
    if (chunk >= 0) {
      for (const x of this.chunks[chunk]?.upTo(t) ?? []) applyRecord(s, x.r, x.t, t0);
    } else {
      // raw records gone: the notable ones of that stretch still count
      for (let i = this.notableFrom(cp.t); i < this.notable.length; i++) {
        const x = this.notable[i]!;
        if (x.t > t) break;
        applyRecord(s, x.r, x.t, t0);
      }
      s.t = t;
    }
    return s;
  }

  /** Marks with lo <= t <= hi (binary search: marks are in time order). */
  marksBetween(lo: Ns, hi: Ns): Mark[] {
    return marksIn(this.marks, lo, hi);
  }

  private checkpoint(): void {
    // the state before this record; its time is the last record's
    this.checkpoints.push({ index: this.count, t: this.live.t, state: cloneState(this.live) });
    // past the bound the oldest chunk goes, and is reused for the next stretch (never the last:
    // keep is at least two chunks)
    let spare: Chunk | undefined;
    while (this.kept > this.keep && this.chunks.length > 1) {
      spare = this.chunks.shift()!;
      this.kept -= spare.length;
      this.firstChunk++;
    }
    this.chunks.push(spare?.reset() ?? new Chunk(this.every));
  }

  private checkpointBefore(t: Ns): Checkpoint {
    let a = 0;
    let b = this.checkpoints.length - 1;
    while (a < b) {
      const m = (a + b + 1) >> 1;
      if (this.checkpoints[m]!.t <= t) a = m;
      else b = m - 1;
    }
    return this.checkpoints[a]!;
  }

  private notableFrom(t: Ns): number {
    let a = 0;
    let b = this.notable.length;
    while (a < b) {
      const m = (a + b) >> 1;
      if (this.notable[m]!.t <= t) a = m + 1;
      else b = m;
    }
    return a;
  }

  private notableRecord(x: Timed): void {
    if (this.notable.length < this.keep) this.notable.push(x);
    const mark = markOf(x);
    if (mark && this.marks.length < this.maxMarks) this.marks.push(mark);
  }
}

function markOf({ t, r }: Timed): Mark | undefined {
  if (isRule(r)) return { t, kind: 'rule', where: r.module, label: `${r.function}.${r.rule} ${r.active ? 'active' : 'inactive'} ← ${r.cause.slice(0, 80)}`, on: r.active };
  if (r.kind === 'unknown') return undefined;
  const k = r as KnownRecord;
  const what = k.fields?.['what'];
  if (k.kind === 'ord_deadline_miss') return { t, kind: 'miss', where: String(k.fields['schema'] ?? '?'), label: `deadline miss (ORD:0) cycle ${k.fields['cycle'] ?? '?'}` };
  if (k.kind === 'scheduler' && (what === 'activate' || what === 'deactivate' || what === 'conflict')) return { t, kind: 'schema', where: String(k.fields['schema'] ?? '?'), label: k.detail.slice(0, 120) };
  if (k.kind === 'scheduler' && what === 'overrun') return { t, kind: 'overrun', where: String(k.fields['schema'] ?? '?'), label: k.detail.slice(0, 120) };
  if (k.kind === 'supervisor' && (what === 'function_started' || what === 'function_stopped' || what === 'function_refused')) return { t, kind: 'function', where: k.module, label: k.detail.slice(0, 120) };
  return undefined;
}
