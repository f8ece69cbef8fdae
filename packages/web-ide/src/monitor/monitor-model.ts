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
 *   overruns, function starts/stops, the modules' own records, errors, the requests a supervisor
 *   kept for a full mailbox), bounded. A deadline miss's mark names what its cycle was
 *   still waiting for, as `contract trace` does (`(not finished: ARM)`, `(held: nothing released,
 *   GRP still runs an earlier release)`): per periodic schema, the modules released in its current
 *   and previous cycle and not finished yet are followed (CycleWaits, no allocation per record).
 * Memory per record is therefore bounded by keepRecords, not by the run's length (a 1 kHz schema
 * for 60 s is about 1.5 million records).
 */
import { LogClocks, UndosToOrd, type UnservedUndos, parseRecordLine, isRule, askedToStopText, crashText, unheardEventText, ignoredUndo, keptRequestsText, missCriticalDelayNs, missWaitText, earlyFinish, type EarlyAck, readableCause, stuckSaysGone, userRecordText, type KnownRecord, type TraceRecord, hasWordIn } from '@contract-studio/build-service/trace';
import { FOLDED_KINDS, applyRecord, endOrdSchemas, foldGone, applyUnfolded, isUnheardEvent, unheardPort } from './apply-record.js';
import { nameIn, scanLine, scanned } from './line-scan.js';
import { HOT_KINDS, applyHotLine, cycleLine, hotRelease, readCycleLine } from './hot-line.js';
import { cloneState, emptyState, type MonitorState, type Ns } from './monitor-state.js';
import { marksIn, type Mark, type MonitorView } from './model-view.js';
import { goneModuleSign, launcherGoneSign, type GoneSign } from './gone-signs.js';
import { FlowFindings } from './flow-findings.js';

export interface MonitorModelOptions {
  checkpointEvery?: number;
  keepRecords?: number;
  maxMarks?: number;
  /**
   * The records are a simulation's (a trace file headed by `sim_start`, which its reader skips):
   * its modules ran no code, so no flow is told as having delivered nothing (FlowFindings.simulated).
   * A `sim_start` record pushed says the same.
   */
  simulation?: boolean;
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

/** Periodic schemas and modules a cycle's wait is followed for (a hostile trace could name thousands). */
const MAX_WAIT_SCHEMAS = 64;
const MAX_WAIT_MODULES = 32;
/** Modules known to be no longer running, followed at most (a real run names a few dozen). */
const MAX_GONE = 1024;
/** Marks the modules' own records may take (the first ones; the rest are counted as records). */
export const MAX_USER_MARKS = 2000;
/** Marks the run's errors may take, likewise (a request failing at 100 Hz must not take them all). */
export const MAX_ERROR_MARKS = 2000;
/** Marks the requests kept for full mailboxes may take, likewise (a module slow at every cycle begins a streak each time). */
export const MAX_KEPT_MARKS = 2000;
/** The mark kinds taken by records a module or a supervisor may write at every cycle, each capped at its first ones. */
type CappedMarkKind = 'user' | 'error' | 'kept';
const MARK_CAPS: Readonly<Record<CappedMarkKind, number>> = { user: MAX_USER_MARKS, error: MAX_ERROR_MARKS, kept: MAX_KEPT_MARKS };

/**
 * An error of the run, for its mark: an `error` record (a request not sent, a datagram dropped), a
 * supervisor's `error: not sent: ...`, a kept STOP's `stop failed: ...`. Its label, else undefined.
 */
function errorLabel(k: KnownRecord): string | undefined {
  if (k.kind === 'error') return `error: ${k.detail}`;
  if (k.kind === 'supervisor' && k.detail.startsWith('error: ')) return k.detail;
  if (k.kind === 'module_hold' && k.detail.startsWith('stop failed')) return `${k.peer}: ${k.detail}`;
  return undefined;
}

/** Longest list of modules a miss's label names. */
const MAX_WAIT_TEXT = 160;

/**
 * The modules released in one cycle of a periodic schema and not finished yet. Read off the live
 * lines in place: a module is matched by its place in the line, and its name kept in a slot of
 * the list (slots past `n` keep the names that left, for the next cycles), so following a cycle
 * makes no string nor array once its modules were seen.
 */
class CycleModules {
  cycle = -1;
  n = 0;
  /** release_ns - tick_ns of the cycle's first release (ORD woke late: missWaitText says so). */
  firstLateNs = 0;
  /** The cycle's tick, on the Monitor's time line (its first release's time less its lateness). */
  tickT = 0;
  /** Modules released and not finished by ORD's count whose own records say they finished (an ack ORD had not read). */
  readonly acks = new Map<string, EarlyAck>();
  private readonly names: string[] = [];

  reset(cycle: number, firstLateNs = 0, tickT = 0): this {
    this.cycle = cycle;
    this.n = 0;
    this.firstLateNs = firstLateNs;
    this.tickT = tickT;
    if (this.acks.size) this.acks.clear();
    return this;
  }

  /** Whether module `name` is released in the cycle and not finished by ORD's count. */
  has(name: string): boolean {
    return this.slotOf(name, 0, name.length, this.n) >= 0;
  }

  /** The modules waited for, sorted (made only for a miss). */
  sortedNames(): string[] {
    return this.names.slice(0, this.n).sort();
  }

  /** The slot among the first `end` that holds the name text[from, to), or -1 (matched in place: no string made). */
  private slotOf(text: string, from: number, to: number, end: number): number {
    const names = this.names;
    const len = to - from;
    for (let i = 0; i < end; i++) {
      const s = names[i]!;
      if (s.length === len && text.startsWith(s, from)) return i;
    }
    return -1;
  }

  /** Module text[from, to) released. */
  addIn(text: string, from: number, to: number): void {
    const names = this.names;
    const i = this.slotOf(text, from, to, names.length);
    if (i >= 0) {
      if (i < this.n || this.n >= MAX_WAIT_MODULES) return; // waited for already, or the list is full
      const s = names[i]!;
      names[i] = names[this.n]!; // a name it held before: back in the list
      names[this.n++] = s;
      return;
    }
    if (this.n >= MAX_WAIT_MODULES) return;
    if (this.n < names.length && names.length < 2 * MAX_WAIT_MODULES) names.push(names[this.n]!);
    names[this.n++] = nameIn(text, from, to);
  }

  /** Module text[from, to) finished. */
  removeIn(text: string, from: number, to: number): void {
    const i = this.slotOf(text, from, to, this.n);
    if (i < 0) return;
    const names = this.names;
    const s = names[i]!;
    names[i] = names[--this.n]!;
    names[this.n] = s; // kept past n for the next cycles
  }

  /** `ARM, GRP` (sorted), cut to MAX_WAIT_TEXT. */
  text(): string {
    const s = this.names.slice(0, this.n).sort().join(', ');
    return s.length > MAX_WAIT_TEXT ? `${s.slice(0, MAX_WAIT_TEXT)}…` : s;
  }
}

/**
 * What a periodic schema's cycles wait for: the modules released in its current and previous
 * cycle (a miss may come after the next cycle's releases when CRITICAL_DELAY = PERIOD) and not
 * finished, and the module its held cycle waits for (ORD's `cycle of S held: M still runs ...`).
 */
class CycleWaits {
  current = new CycleModules();
  previous = new CycleModules();
  held: string | undefined;

  /** Module text[from, to) released in `cycle`, `lateNs` after its tick, at `t`. */
  released(cycle: number, text: string, from: number, to: number, lateNs: number, t: Ns): void {
    this.held = undefined;
    if (this.current.cycle !== cycle) {
      const p = this.previous;
      this.previous = this.current;
      this.current = p.reset(cycle, lateNs, t - lateNs);
    }
    this.current.addIn(text, from, to);
  }

  /** Module `module`'s own ack to ORD (or the end of its run, `how`) at `t`: noted on the cycle it is released in, if any. */
  acked(module: string, t: Ns, how: EarlyAck['how']): void {
    if (!CycleWaits.ack(this.current, module, t, how)) CycleWaits.ack(this.previous, module, t, how);
  }

  /** The ack noted on cycle `c` if `module` is released in it and not finished (no array made: acks come at every release). */
  private static ack(c: CycleModules, module: string, t: Ns, how: EarlyAck['how']): boolean {
    if (c.cycle < 0 || !c.has(module)) return false;
    if (how === 'its ack sent' || !c.acks.has(module)) c.acks.set(module, { module, sinceTickNs: t - c.tickT, how });
    return true;
  }

  /** Module text[from, to) finished its release of `cycle`. */
  finished(cycle: number, text: string, from: number, to: number): void {
    this.held = undefined;
    if (this.current.cycle === cycle) this.current.removeIn(text, from, to);
    else if (this.previous.cycle === cycle) this.previous.removeIn(text, from, to);
  }

  /** A new activation (cycles count from 0 again), or the schema stopped. */
  restart(): void {
    this.current.reset(-1);
    this.previous.reset(-1);
  }

  /**
   * What the miss of `cycle` waited for, in contract trace's words (missWaitText); `gone`: the modules known to be no
   * longer running; `criticalDelayNs`: the miss record's CRITICAL_DELAY (a cycle ORD released with less than a tenth of
   * it left blames ORD, not its modules).
   */
  lateOf(cycle: number, gone: ReadonlySet<string>, criticalDelayNs: number | undefined, missT: Ns): string {
    const c = this.current.cycle === cycle ? this.current : this.previous.cycle === cycle ? this.previous : undefined;
    // modules whose own ack came by the deadline (tick + CRITICAL_DELAY, or when ORD told the miss) are not blamed
    const early = c?.n && c.acks.size ? earlyFinish(c.sortedNames(), c.acks, criticalDelayNs ?? missT - c.tickT) : undefined;
    return missWaitText(this.held, c?.n ? c.text() : '', c?.firstLateNs, this.held !== undefined && gone.has(this.held), criticalDelayNs, early);
  }
}

const NOTABLE = new Set(['sup_rule', 'supervisor', 'scheduler', 'ord_deadline_miss', 'module_hold', 'flow_hold', 'module_started', 'module_exit', 'module_crashed',
  'requests_kept', 'requests_kept_end']);

export class MonitorModel implements MonitorView {
  readonly live: MonitorState = emptyState();
  readonly marks: Mark[] = [];
  /** mono_ns of the first record: time 0. */
  t0: number | undefined;
  private readonly every: number;
  private readonly keep: number;
  private readonly maxMarks: number;
  /** Marks of each capped kind so far (cappedMark). */
  private readonly cappedMarks: Record<CappedMarkKind, number> = { user: 0, error: 0, kept: 0 };
  private readonly checkpoints: Checkpoint[] = [];
  /** chunks[i] holds records [firstChunk + i) * every ...; dropped chunks leave their notable records. */
  private chunks: Chunk[] = [];
  private firstChunk = 0;
  private kept = 0;
  private readonly notable: Timed[] = [];
  private count = 0;
  /** Bumped on every change, so a view redraws only when something happened. */
  version = 0;
  /** Each log's time check (log-clock.ts), for the lines pushed with pushLineIn. */
  private readonly clocks = new LogClocks();
  /** Ids of the texts fed without one (each a text of its own: negative, the callers' ids are not). */
  private anonymousText = 0;
  /** Per periodic schema, what its cycles wait for (a deadline miss's mark names it). */
  private readonly waits = new Map<string, CycleWaits>();
  /**
   * Modules known to be no longer running (ORD's stuck record said so, or their exit was read), at
   * most MAX_GONE: a miss of a cycle held for one says it "never finished" its release, not that it
   * "still runs" it, as contract trace says.
   */
  private readonly gone = new Set<string>();
  /** The run's stop was marked (askedToStopText: the first module's KILL saying why). */
  private stopMarked = false;
  /** The supervisors' undos to ORD until ORD serves them: those its end left unserved are marked on their schema's row, as `contract trace` tells them. */
  private readonly undos = new UndosToOrd();
  /** What the flows did, as `contract trace` tells it: event flows that waited for room (marked), data flows that delivered nothing (at the end). */
  private readonly flows = new FlowFindings();
  /** The run's end was marked (recordsEnded: once). */
  private endMarked = false;
  /**
   * The records are a simulation's (the option, or a `sim_start` pushed): its engines write no exit
   * records, and its records end where the simulation stopped (its `until`, the session's time),
   * not where ORD did: recordsEnded does not show ORD ended there.
   */
  private simulation = false;
  /** The schema a release or completion line named last, and its waits (a line naming it again is matched in place). */
  private lastWaits: CycleWaits | undefined;
  private lastWaitsName = '';
  /** Time of ORD's last record so far (undefined before its first). */
  private ordLastT: Ns | undefined;
  /** ORD's exit or crash record was read: its end is told by it. */
  private ordExited = false;
  /**
   * ORD's log ended with no exit record (a SIGKILL, a stop that terminated it), as a reliable sign
   * told (another module's record saying ORD has ended, or the records' end): its periodic schemas
   * are shown ended at ORD's last record, in every state from then on (stateAt applies it to the
   * states scrubbed back to, which the records alone do not end).
   */
  private ordEnd: Ns | undefined;
  /** Each module's pid, from its last `module_started` record (at most MAX_GONE modules): a launcher's end line must name it. */
  private readonly pids = new Map<string, number>();
  /** The launcher's end lines taken (launcherLine), at the time each came: no record holds them, so stateAt applies them. */
  private readonly launcherSigns: { t: Ns; sign: GoneSign; count: number }[] = [];

  constructor(opts: MonitorModelOptions = {}) {
    this.every = Math.max(16, opts.checkpointEvery ?? 1024);
    this.keep = Math.max(this.every * 2, opts.keepRecords ?? 200_000);
    this.maxMarks = opts.maxMarks ?? 20_000;
    this.checkpoints.push({ index: 0, t: 0, state: emptyState() });
    this.chunks.push(new Chunk(this.every));
    if (opts.simulation) this.simulated();
  }

  /** The records are a simulation's (FlowFindings.simulated; recordsEnded leaves ORD running). */
  private simulated(): void {
    this.simulation = true;
    this.flows.simulated();
  }

  get recordCount(): number {
    return this.count;
  }

  /** Time of the last record (ns since the first). */
  get end(): Ns {
    return this.live.t;
  }

  /**
   * Nothing happened after the last record up to `t` (ns since the first record): the run's end
   * moves there, the state unchanged (a simulation's session stands at a virtual time past its
   * last record). Only for a run that is over: a later record would be held at that time.
   */
  holdUntil(t: Ns): void {
    if (!(t > this.live.t)) return;
    this.live.t = t;
    this.version++;
  }

  /** Whether states before `t` are approximate (their raw records were dropped). */
  exactAt(t: Ns): boolean {
    const cp = this.checkpointBefore(t);
    return cp.index / this.every >= this.firstChunk;
  }

  /**
   * `n` lines of a log that are no record, which the build service counted without sending them
   * (past its bound of such lines: trace/wire.ts `unsent`): counted unreadable, as a replay of the
   * logs counts them (not in the states scrubbed back to).
   */
  countUnsent(n: number): void {
    if (Number.isSafeInteger(n) && n > 0) this.live.unknownLines = Math.min(Number.MAX_SAFE_INTEGER, this.live.unknownLines + n);
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
   * taken as one of its own. `cut`: the line was its log's last, with no line end (markCut).
   */
  pushLineIn(file: string, line: number, text: string, from: number, to: number, textId = --this.anonymousText, cut = false, timeChecked = false): void {
    // each log's time check (log-clock.ts), its lines in file order (a recorded run checks them itself: timeChecked)
    let clock = timeChecked ? undefined : this.clocks.of(file);
    if (scanLine(text, from, to, file)) {
      const why = clock?.check(scanned.mono, text, scanned.comma[0]! + 1, scanned.comma[1]!);
      if (why !== undefined) {
        this.push({ kind: 'unknown', file, line, reason: why, text: text.slice(from, Math.min(to, from + 200)) });
        return;
      }
      const module = cut ? text.slice(scanned.comma[1]! + 1, scanned.comma[2]!) : '';
      if (this.pushScanned(text, from, to, textId)) {
        if (cut) this.markCut(module);
        return;
      }
      clock = undefined; // checked above
    }
    const r = parseRecordLine(file, line, text.slice(from, to), clock);
    const t = this.timeOfRecord(r);
    // a line that is no record is kept as what the reader made of it: read again without its
    // log's name (a scrub back), a record of another module than its log's would be taken for one
    if (r.kind === 'unknown') {
      this.beforeKeep();
      this.chunks[this.chunks.length - 1]!.push(t, r);
    } else this.keepLine(t, text, from, to, textId);
    this.fold(t, r);
    if (cut && r.kind !== 'unknown') this.markCut((r as KnownRecord).module);
  }

  /**
   * The record just folded was its log's last line, with no line end (`cut`: its module was killed
   * while it wrote it), so it may have lost its end: marked on the strip among the error marks, in
   * `contract trace`'s words (its story's `[cut: ...]`). A line that is no record is not (it is
   * counted unreadable).
   */
  private markCut(module: string): void {
    if (this.cappedMarks.error >= MARK_CAPS.error || this.marks.length >= this.maxMarks) return;
    this.cappedMarks.error++;
    this.marks.push({ t: this.live.t, kind: 'error', where: module.slice(0, 64), label: 'cut: its log ends inside this record, with no line end; the record may have lost its end (its module was killed while writing it)' });
  }

  /**
   * The line text.slice(from, to) that scanLine has accepted, `scanned` holding what it read:
   * folded (and true) when it is of a kind read in place; false, and nothing done, when it is of
   * a kind that is parsed (pushLineIn then parses it).
   */
  pushScanned(text: string, from: number, to: number, textId: number): boolean {
    const kind = scanned.kind;
    if (kind === 'user' || kind === 'error') return false; // parsed, for its mark (userMark, errorMark)
    // an event a subscriber received (its peer) folds nothing: only one no one received is parsed
    const delivered = kind === 'event_posted' && scanned.comma[4]! > scanned.comma[3]! + 1;
    const ord = scanned.comma[2]! - scanned.comma[1]! === 4 && text.startsWith('ORD', scanned.comma[1]! + 1);
    if (delivered || !FOLDED_KINDS.has(kind)) {
      if (kind === 'ord_finished') this.finishedLine(text);
      this.flows.seeScanned(text, from, to);
      const t = this.timeOf(scanned.mono);
      if (kind === 'ack_sent') this.ackLine(text, to, t, 'its ack sent');
      if (ord) this.ordLastT = t;
      this.keepLine(t, text, from, to, textId);
      applyUnfolded(this.live, t);
      return true;
    }
    if (HOT_KINDS.has(kind)) {
      const t = this.timeOf(scanned.mono);
      if (ord) this.ordLastT = t;
      this.keepLine(t, text, from, to, textId);
      applyHotLine(this.live, text, t, this.t0 ?? 0);
      this.flows.seeScanned(text, from, to);
      // a release: its module waited for in its cycle (the schema and cycle as applyHotLine read them)
      if (kind === 'ord_release') this.releaseLine(text, t);
      else if (kind === 'run_finished') this.ackLine(text, to, t, 'its run finished');
      return true;
    }
    return false;
  }

  /**
   * One of the launcher's own lines of the job's output (a `line` event of source `launcher`, its
   * stderr; without its `contract-launch: ` prefix): one that says a module ended (`module SRT (pid
   * 41) died by signal 9 (Killed)`, `... exited with status 3`), naming the pid of that module's
   * own start record, shows it gone from the time of the last record folded (`at`: from that time,
   * in a replay of a job's logs: the line's wall time on the run's time line), as another module's
   * record saying so does (gone-signs.ts): the alert line, the strip mark, `Running now … · gone:
   * SRT`. A module whose end was read (its exit or crash record), or that is already shown gone,
   * is left as it is. True when it was taken.
   */
  launcherLine(line: string, at?: Ns): boolean {
    const sign = launcherGoneSign(line, (m) => this.pids.get(m));
    if (!sign) return false;
    // a replay of a job's logs: at the line's own time (`at`, from its wall clock), within the run
    const t = at === undefined || !Number.isFinite(at) ? this.live.t : Math.min(Math.max(0, at), this.live.t);
    const wasGone = this.live.modules.get(sign.module)?.gone;
    foldGone(this.live, sign, t);
    if (wasGone !== undefined || this.live.modules.get(sign.module)?.gone === undefined) return false;
    if (this.launcherSigns.length < MAX_GONE) this.launcherSigns.push({ t, sign, count: this.count });
    if (t < this.live.t) {
      // before the last record (a replay): its mark in time order (ORD's schemas ended as for a record's sign)
      if (this.marks.length < this.maxMarks) insertMark(this.marks, { t, kind: 'crash', where: sign.module.slice(0, 64), label: `${sign.module} ${this.live.modules.get(sign.module)!.gone}`.slice(0, 200) });
      if (sign.module === 'ORD') this.ordGone();
    } else this.goneSign(t, sign.module, wasGone);
    this.version++;
    return true;
  }

  /**
   * One of the launcher's end lines with its time on the records' clock (`monoNs`: a logs folder's
   * contract-launch.log, written by the launcher alone), applied as launcherLine at that time on the
   * run's time line; false when no record was read (no time line) or it is not taken.
   */
  launcherLineAtMono(line: string, monoNs: number): boolean {
    if (this.t0 === undefined || !Number.isFinite(monoNs)) return false;
    return this.launcherLine(line, monoNs - this.t0);
  }

  /** A parsed record (kept as it is). */
  push(r: TraceRecord): void {
    // a simulation's trace (stepsToTrace) starts with it: its modules ran no code (FlowFindings.simulated)
    if (r.kind === 'sim_start') this.simulated();
    const t = this.timeOfRecord(r);
    this.beforeKeep();
    this.chunks[this.chunks.length - 1]!.push(t, r);
    this.fold(t, r);
    if (r.kind !== 'unknown' && (r as KnownRecord).cut) this.markCut((r as KnownRecord).module);
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
    if (r.kind !== 'unknown' && (r as KnownRecord).module === 'ORD') this.ordLastT = t;
    if (r.kind === 'ord_release' || r.kind === 'ord_finished' || r.kind === 'scheduler') this.followCycles(r as KnownRecord, t);
    if (r.kind === 'ack_sent' || r.kind === 'run_finished') this.followParsedAck(r as KnownRecord, t);
    if (r.kind === 'module_exit' || r.kind === 'module_crashed' || r.kind === 'module_started' || r.kind === 'scheduler') this.followGone(r as KnownRecord);
    if (r.kind === 'module_started') this.notePid(r as KnownRecord);
    if (NOTABLE.has(r.kind)) this.notableRecord({ t, r });
    // a module's own record: its detail cut so that the peer, port and size after it show
    else if (r.kind === 'user') this.cappedMark(t, 'user', r as KnownRecord, (k) => userRecordText(k, 80));
    if (r.kind !== 'unknown') this.cappedMark(t, 'error', r as KnownRecord, errorLabel);
    if (r.kind === 'requests_kept' || r.kind === 'requests_kept_end') this.cappedMark(t, 'kept', r as KnownRecord, keptRequestsText);
    // why the build service stopped the run (a limit, its run time limit, a cancel): the first KILL saying it, marked once
    if (r.kind === 'request_received' && !this.stopMarked && askedToStopText(r as KnownRecord)) {
      this.stopMarked = true;
      this.cappedMark(t, 'error', r as KnownRecord, askedToStopText);
    }
    if (r.kind !== 'unknown' && !isRule(r)) {
      this.followUndoToOrd(t, r as KnownRecord);
      this.followFlows(t, r as KnownRecord);
    }
    const sign = r.kind === 'error' || r.kind === 'scheduler' ? goneModuleSign(r as KnownRecord) : undefined;
    const wasGone = sign && this.live.modules.get(sign.module)?.gone;
    applyRecord(this.live, r, t, this.t0 ?? 0);
    if (r.kind === 'event_posted') this.markUnheard(t, r as KnownRecord);
    if (sign) this.goneSign(t, sign.module, wasGone);
  }

  /**
   * A record just folded said module `module` is gone (gone-signs.ts): marked on the strip as a
   * crash is, when it is newly shown gone; ORD gone, its schemas are ended at its last record.
   */
  private goneSign(t: Ns, module: string, wasGone: string | undefined): void {
    const gone = this.live.modules.get(module)?.gone;
    if (gone !== undefined && wasGone === undefined && this.marks.length < this.maxMarks) {
      this.marks.push({ t, kind: 'crash', where: module.slice(0, 64), label: `${module} ${gone}`.slice(0, 200) });
    }
    if (module === 'ORD') this.ordGone();
  }

  /**
   * ORD ended with no exit record (ordEnd): its periodic schemas still shown active are ended at
   * its last record, each with a mark on its row there saying why. Once; not when ORD's exit was read.
   */
  private ordGone(): void {
    const at = this.ordLastT;
    if (this.ordEnd !== undefined || this.ordExited || at === undefined) return;
    this.ordEnd = at;
    const ended = [...this.live.schemas].filter(([, sc]) => sc.active).map(([name]) => name);
    endOrdSchemas(this.live, at);
    for (const schema of ended) {
      if (this.marks.length >= this.maxMarks) break;
      insertMark(this.marks, { t: at, kind: 'schema', where: schema, label: `ORD gone: its log ends at this record with no exit record (killed?): ${schema} is shown ended here; whether it ran on is unknown`.slice(0, 300) });
    }
    this.version++;
  }

  /**
   * An event no one received, just folded: its port's first is marked on the functions' row, in
   * `contract trace`'s words (its story tells the port's first too); Deliveries counts them all.
   */
  private markUnheard(t: Ns, k: KnownRecord): void {
    if (!isUnheardEvent(k) || this.marks.length >= this.maxMarks) return;
    const port = unheardPort(k);
    if (this.live.unheardEvents.get(port)?.count !== 1) return;
    this.marks.push({ t, kind: 'unheard', where: k.module, label: `${unheardEventText(port)}; Deliveries counts its later ones`.slice(0, 300) });
  }

  /**
   * A parsed record's share of what the flows did (FlowFindings): an event flow's first streak of
   * posts that waited for room is marked on the functions' row, in `contract trace`'s words
   * (Deliveries says it on the flow's row).
   */
  private followFlows(t: Ns, k: KnownRecord): void {
    const waited = this.flows.see(k);
    if (waited === undefined || this.marks.length >= this.maxMarks) return;
    this.marks.push({ t, kind: 'waited', where: k.module, label: waited.slice(0, 400) });
  }

  /** A record's share of the undos to ORD: ORD's exit or crash record marks those it never served (UndosToOrd.atOrdEnd). */
  private followUndoToOrd(t: Ns, k: KnownRecord): void {
    this.undos.see(k);
    if ((k.kind === 'module_exit' || k.kind === 'module_crashed') && k.module === 'ORD') {
      this.ordExited = true;
      this.markUnserved(t, this.undos.atOrdEnd());
    }
  }

  /** One mark per schema the undos left active, on its row, with the sentence `contract trace` tells. */
  private markUnserved(t: Ns, left: UnservedUndos | undefined): void {
    for (const schema of left?.schemas ?? []) {
      if (this.marks.length >= this.maxMarks) return;
      this.marks.push({ t, kind: 'schema', where: schema, label: left!.text.slice(0, 600) });
      this.version++;
    }
  }

  /**
   * The records are over (a recorded run read whole, a live run's job ended, a simulation run to its
   * end): the undos ORD's log never answered when it wrote no exit record (killed, terminated at
   * the stop) are marked at the last record, as `contract trace` tells them after its last
   * (UndosToOrd.atRecordsEnd: none while the run may still go on), and ORD's periodic schemas are
   * shown ended there (ordGone); the flows' closing lines are told (quietDataFlows). Once. A
   * simulation's ORD writes no exit record and did not end: its records stop at the simulation's
   * end with its schemas still active, so they stay shown active (only the flows' lines are told).
   */
  recordsEnded(): void {
    if (this.endMarked) return;
    this.endMarked = true;
    if (!this.simulation) {
      this.markUnserved(this.live.t, this.undos.atRecordsEnd());
      this.ordGone();
    }
    this.live.quietDataFlows = this.flows.endLines().map((l) => l.slice(0, 600));
    this.version++;
  }

  /** The `ord_release` line applyHotLine just folded (hotRelease: its schema and cycle): its module (its peer) waited for in that cycle. */
  private releaseLine(text: string, t: Ns): void {
    const { schema, cycle } = hotRelease;
    const c = scanned.comma;
    if (schema === undefined || cycle === undefined || c[4]! === c[3]! + 1) return;
    this.waitsOf(schema)?.released(cycle, text, c[3]! + 1, c[4]!, hotRelease.lateNs, t);
  }

  /**
   * An `ack_sent` or `run_finished` line that scanLine accepted (its end at `to`): a module's own
   * ACK_FINISHED to ORD, or the end of its run with one, noted on the cycle it is released in
   * (followAck). Read in place; the module's name made only when it acks ORD.
   */
  private ackLine(text: string, to: number, t: Ns, how: EarlyAck['how']): void {
    const c = scanned.comma;
    const detail = c[6]! + 1;
    if (how === 'its ack sent'
      ? !(c[4]! - c[3]! === 4 && text.startsWith('ORD', c[3]! + 1) && hasWordIn(text, 'ACK_FINISHED', detail, to))
      : !hasWordIn(text, 'ACK_FINISHED', detail, to)) return;
    this.followAck(nameIn(text, c[1]! + 1, c[2]!), t, how);
  }

  /** Module `module`'s own ack to ORD at `t`: noted on the cycle of each followed schema it is released in. */
  private followAck(module: string, t: Ns, how: EarlyAck['how']): void {
    if (!this.waits.size) return;
    for (const w of this.waits.values()) w.acked(module, t, how);
  }

  /**
   * An `ord_finished` line that scanLine accepted, read in place (readCycleLine): its module done
   * with its schema's cycle. The schema named by the line before is matched in place; no string
   * is made once the names were seen.
   */
  private finishedLine(text: string): void {
    if (!readCycleLine(text)) return;
    const { schemaFrom: from, schemaTo: to } = cycleLine;
    let w = this.lastWaits;
    const last = this.lastWaitsName;
    if (!w || to - from !== last.length || !text.startsWith(last, from)) {
      const schema = nameIn(text, from, to);
      w = this.waitsOf(schema);
      if (!w) return;
      this.lastWaits = w;
      this.lastWaitsName = schema;
    }
    w.finished(cycleLine.cycle, text, cycleLine.moduleFrom, cycleLine.moduleTo);
  }

  /** The waits of periodic schema `schema` (made on first use, up to MAX_WAIT_SCHEMAS schemas). */
  private waitsOf(schema: string): CycleWaits | undefined {
    let w = this.waits.get(schema);
    if (!w && this.waits.size < MAX_WAIT_SCHEMAS) this.waits.set(schema, (w = new CycleWaits()));
    return w;
  }

  /** What the cycle of deadline miss `k`, told at `t`, was still waiting for (CycleWaits.lateOf), or ''. */
  private lateOf(k: KnownRecord, t: Ns): string {
    const schema = k.fields?.['schema'];
    const cycle = k.fields?.['cycle'];
    if (typeof schema !== 'string' || typeof cycle !== 'number') return '';
    return this.waits.get(schema)?.lateOf(cycle, this.gone, missCriticalDelayNs(k.fields), t) ?? '';
  }

  /** Which modules are no longer running: a stuck record saying so, an exit; started again, or finished at last, it runs. */
  private followGone(k: KnownRecord): void {
    if (k.kind === 'module_exit' || k.kind === 'module_crashed') {
      if (this.gone.size < MAX_GONE) this.gone.add(k.module);
      return;
    }
    if (k.kind === 'module_started') {
      this.gone.delete(k.module);
      return;
    }
    const what = k.fields?.['what'];
    const module = k.fields?.['module'];
    if (typeof module !== 'string') return;
    if (what === 'stuck' && stuckSaysGone(k.detail) && this.gone.size < MAX_GONE) this.gone.add(module);
    else if (what === 'unstuck' || what === 'late_ack') this.gone.delete(module);
  }

  /** A module's pid from its `module_started` record (`pid=41 priority=40`): the one its launcher's end line must name. */
  private notePid(k: KnownRecord): void {
    const pid = Number(k.fields?.['pid']);
    if (!Number.isSafeInteger(pid) || pid <= 0) return;
    if (this.pids.has(k.module) || this.pids.size < MAX_GONE) this.pids.set(k.module, pid);
  }

  /** A parsed release, completion of a module's release, or ORD scheduler line: what the schema's cycles wait for. */
  private followCycles(k: KnownRecord, t: Ns): void {
    const f = k.fields ?? {};
    const schema = f['schema'];
    if (typeof schema !== 'string' || !schema) return;
    if (k.kind === 'scheduler') {
      const what = f['what'];
      const w = what === 'held' ? this.waitsOf(schema) : this.waits.get(schema);
      if (!w) return;
      if (what === 'held') w.held = typeof f['module'] === 'string' && f['module'] ? f['module'] : '?';
      else if (what === 'resumed') w.held = undefined;
      else if (what === 'activate') w.restart();
      else if (what === 'deactivate') {
        w.held = undefined;
        w.restart();
      }
      return;
    }
    const cycle = f['cycle'];
    if (typeof cycle !== 'number' || !Number.isFinite(cycle) || !k.peer) return;
    const w = this.waitsOf(schema);
    if (k.kind === 'ord_release') {
      const late = Number(f['release_ns']) - Number(f['tick_ns']);
      w?.released(cycle, k.peer, 0, k.peer.length, Number.isFinite(late) ? late : 0, t);
    }
    else w?.finished(cycle, k.peer, 0, k.peer.length);
  }

  /** A parsed `ack_sent` (ACK_FINISHED to ORD) or `run_finished` (with ACK_FINISHED): followAck. */
  private followParsedAck(k: KnownRecord, t: Ns): void {
    if ((k.kind !== 'ack_sent' || k.peer === 'ORD') && hasWordIn(k.detail, 'ACK_FINISHED')) {
      this.followAck(k.module, t, k.kind === 'ack_sent' ? 'its ack sent' : 'its run finished');
    }
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
    // the launcher's end lines taken after the checkpoint (no record holds them)
    for (const x of this.launcherSigns) if (x.count > cp.index && x.t <= t) foldGone(s, x.sign, x.t);
    if (this.ordEnd !== undefined && t >= this.ordEnd) endOrdSchemas(s, this.ordEnd);
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

  /**
   * A mark of a record that changes no state but is worth seeing, in its kind's colour on the row
   * of the functions, labelled by `label` (undefined: no mark): a module's own record (ContractLog
   * under a name of its own: `gripper_closed: force=12.5 N (peer MAB, port 2, 16 bytes)`, the
   * story's words), an error of the run (errorLabel), a supervisor's requests kept for a full
   * mailbox, when that began and ended (keptRequestsText). Each kind takes its first
   * MARK_CAPS[kind] marks only, so that a record written at every cycle cannot take the marks the
   * supervisors' and ORD's records need; the label is made only for a mark that is kept.
   */
  private cappedMark(t: Ns, kind: CappedMarkKind, k: KnownRecord, label: (k: KnownRecord) => string | undefined): void {
    if (this.cappedMarks[kind] >= MARK_CAPS[kind] || this.marks.length >= this.maxMarks) return;
    const text = label(k);
    if (text === undefined) return;
    this.cappedMarks[kind]++;
    this.marks.push({ t, kind, where: k.module, label: text.slice(0, 200) });
  }

  private notableRecord(x: Timed): void {
    if (this.notable.length < this.keep) this.notable.push(x);
    const mark = markOf(x, x.r.kind === 'ord_deadline_miss' ? this.lateOf(x.r as KnownRecord, x.t) : '');
    if (mark && this.marks.length < this.maxMarks) this.marks.push(mark);
  }
}

/** `m` put among `marks` (in time order) after those of its time: a mark of a time already passed (ORD's last record, told later). */
function insertMark(marks: Mark[], m: Mark): void {
  let i = marks.length;
  while (i > 0 && marks[i - 1]!.t > m.t) i--;
  marks.splice(i, 0, m);
}

/** Longest ORD line an overrun's mark says (a log's line is cut at 4 KiB: a forged one must not fill the tooltip). */
const MAX_ORD_MARK_CHARS = 400;

function markOf({ t, r }: Timed, late: string): Mark | undefined {
  if (isRule(r)) return { t, kind: 'rule', where: r.module, label: `${r.function}.${r.rule} ${r.active ? 'active' : 'inactive'} ← ${readableCause(r.cause).slice(0, 80)}`, on: r.active };
  if (r.kind === 'unknown') return undefined;
  const k = r as KnownRecord;
  const what = k.fields?.['what'];
  // a module's code crashed (the runtime's signal handler wrote the record as it died), in contract trace's words
  if (k.kind === 'module_crashed') return { t, kind: 'crash', where: k.module, label: crashText(k.detail).slice(0, 160) };
  if (k.kind === 'ord_deadline_miss') return { t, kind: 'miss', where: String(k.fields['schema'] ?? '?'), label: `deadline miss (ORD:0) cycle ${k.fields['cycle'] ?? '?'}${late}` };
  // ORD's answers to a supervisor's requests for a periodic schema, its ignored undo of an activation it does not serve included (ignoredUndo: as `contract trace` tells it)
  if (k.kind === 'scheduler' && (what === 'activate' || what === 'deactivate' || what === 'conflict' || ignoredUndo(k))) return { t, kind: 'schema', where: String(k.fields['schema'] ?? '?'), label: k.detail.slice(0, 120) };
  // an overrun's first skipped release, and, when the cycle skipped more, its count at its end: whatever ORD's line says
  // (the module its cycle still waits for, when it names one), within the bound of a line a log holds
  // a cycle ORD itself released past its CRITICAL_DELAY (no ORD:0): ORD's line, as `contract trace` tells it
  if (k.kind === 'scheduler' && what === 'late_release') return { t, kind: 'late', where: String(k.fields['schema'] ?? '?'), label: k.detail.slice(0, MAX_ORD_MARK_CHARS) };
  if (k.kind === 'scheduler' && (what === 'overrun' || what === 'overrun_ended')) return { t, kind: 'overrun', where: String(k.fields['schema'] ?? '?'), label: k.detail.slice(0, MAX_ORD_MARK_CHARS) };
  if (k.kind === 'supervisor' && (what === 'function_started' || what === 'function_stopped' || what === 'function_refused')) return { t, kind: 'function', where: k.module, label: k.detail.slice(0, 120) };
  return undefined;
}
