/**
 * The monitor model: the trace records of one run (live, fed as they come, or a whole recorded
 * run) folded into the architecture's state (monitor-state.ts), with a time cursor.
 *
 * - `live` is the state after the last record; feeding a record costs one applyRecord (a live
 *   line of a kind it does not fold is not even parsed: unfolded-line.ts).
 * - `stateAt(t)` is the state at any earlier time: the nearest checkpoint (a copy of the state
 *   taken every `checkpointEvery` records) plus the records after it, so scrubbing back costs at
 *   most one copy and `checkpointEvery` folds, whatever the run's length.
 * - Raw records are kept in chunks (one per checkpoint) up to `keepRecords`; on a longer run the
 *   oldest chunks go, except their notable records (rules, functions, schemas, holds, misses), so a
 *   state far back is exact for those and approximate (to the checkpoint) for counters.
 * - `marks` lists what the timeline marks (rule changes, schema (de)activations, deadline misses,
 *   overruns, function starts/stops), bounded.
 * Memory per record is therefore bounded by keepRecords, not by the run's length (a 1 kHz schema
 * for 60 s is about 1.5 million records).
 */
import { parseRecordLine, isRule, type KnownRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { applyRecord, applyUnfolded } from './apply-record.js';
import { unfoldedLineTime } from './unfolded-line.js';
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

interface Timed {
  t: Ns;
  r: TraceRecord;
}

/**
 * The raw records between two checkpoints. A live line is kept as its text (about a fifth of the
 * parsed record's memory) and parsed again when a scrub back replays it. Once the chunk is full,
 * its texts are packed into one string and its times into one Float64Array: a minute of a 1 kHz
 * schema is then a few hundred objects instead of a million, which keeps the collector's full
 * passes (and the frames they stall) short.
 */
class Chunk {
  private times: number[] | Float64Array = [];
  private items: Array<TraceRecord | string> | undefined = [];
  private packed: string | undefined;

  get length(): number {
    return this.times.length;
  }

  push(t: Ns, r: TraceRecord | string): void {
    (this.times as number[]).push(t);
    this.items!.push(r);
  }

  seal(): void {
    const items = this.items!;
    this.times = Float64Array.from(this.times);
    if (items.every((x) => typeof x === 'string' && !x.includes(SEP))) {
      this.packed = items.join(SEP);
      this.items = undefined;
    }
  }

  /** The records with time <= t, in order. */
  *upTo(t: Ns): Generator<{ t: Ns; r: TraceRecord }> {
    const items = this.items ?? (this.packed ?? '').split(SEP);
    for (let i = 0; i < this.times.length; i++) {
      const at = this.times[i]!;
      if (at > t) return;
      const x = items[i]!;
      yield { t: at, r: typeof x === 'string' ? parseRecordLine('', 0, x) : x };
    }
  }
}

const SEP = '\u0000';

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

  constructor(opts: MonitorModelOptions = {}) {
    this.every = Math.max(16, opts.checkpointEvery ?? 1024);
    this.keep = Math.max(this.every * 2, opts.keepRecords ?? 200_000);
    this.maxMarks = opts.maxMarks ?? 20_000;
    this.checkpoints.push({ index: 0, t: 0, state: emptyState() });
    this.chunks.push(new Chunk());
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

  /**
   * One CSV line of the live trace channel (job-events.ts TraceLine). A line of a kind the fold
   * does not use is not parsed: its time is read off it (unfolded-line.ts).
   */
  pushLine(file: string, line: number, text: string): void {
    const mono = unfoldedLineTime(text);
    if (mono === undefined) this.push(parseRecordLine(file, line, text), text);
    else this.append(this.timeOf(mono), text, undefined);
  }

  /** `text`: the record's CSV line, kept instead of the record when given. */
  push(r: TraceRecord, text?: string): void {
    const t = r.kind === 'unknown' ? this.live.t : this.timeOf(Number((r as KnownRecord).monoNs));
    this.append(t, text ?? r, r);
  }

  /** The time (ns since the first record) of a record written at `mono`. */
  private timeOf(mono: number): Ns {
    if (!Number.isFinite(mono)) return this.live.t;
    this.t0 ??= mono;
    // records come in mono_ns order; one that does not (hostile input) is held at the last time
    return Math.max(this.live.t, mono - this.t0);
  }

  /** Keeps a record (`r`, or undefined for a line of an unfolded kind) and folds it into `live`. */
  private append(t: Ns, kept: TraceRecord | string, r: TraceRecord | undefined): void {
    if (this.count > 0 && this.count % this.every === 0) this.checkpoint();
    this.chunks[this.chunks.length - 1]!.push(t, kept);
    this.kept++;
    this.count++;
    if (!r) applyUnfolded(this.live, t);
    else {
      if (NOTABLE.has(r.kind)) this.notableRecord({ t, r });
      applyRecord(this.live, r, t, this.t0 ?? 0);
    }
    this.version++;
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
    this.chunks[this.chunks.length - 1]!.seal();
    this.chunks.push(new Chunk());
    while (this.kept > this.keep && this.chunks.length > 1) {
      this.kept -= this.chunks.shift()!.length;
      this.firstChunk++;
    }
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
