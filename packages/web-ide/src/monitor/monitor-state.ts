/**
 * The state of a running architecture at one instant, as the monitor folds it out of the
 * run-time trace (docs/runtime-api.md "Trace records"). Plain data (Maps of small objects,
 * fixed-size histograms; every name read from a trace keys a Map, never an object's properties, so
 * a supervisor function `constructor` or a rule `__proto__` is a name like any other) so that a checkpoint is a cheap deep copy and its size does not grow
 * with the number of records: counters and histograms aggregate, only the last few items are
 * kept in lists.
 */

import { quantileBin } from '@contract-studio/conventions';

/** Times are ns since the first record of the run (its mono_ns), so live and replay agree. */
export type Ns = number;

export interface RuleState {
  function: string;
  rule: string;
  active: boolean;
  /** When it last changed. */
  since: Ns;
  /** The cause of the last change, as logged (`MAA:2 value="disconnected"`, `elapsed=1000000ns`, `ORD:0 ...`). */
  cause: string;
  /** How many times it became active. */
  activations: number;
  /** Schemas and modules its last activation started (ORD activations and supervisor holds). */
  started: string[];
}

export interface FunctionState {
  state: 'running' | 'stopped' | 'refused';
  since: Ns;
}

export interface SupervisorState {
  functions: Map<string, FunctionState>;
  /** Keyed `F.R`. */
  rules: Map<string, RuleState>;
  /**
   * Actions done and undone (`undo: …`), as its log lists them: one per action line. A log of an
   * older version, without lines for the modules started and stopped, the flows connected and the
   * priorities claimed, counts those by their hold and priority records instead.
   */
  actionsDone: number;
  actionsUndone: number;
  /** Its log writes a line for each module start, flow connect and priority claim (field `action`): their records are not counted again. */
  actionLines?: boolean;
  /** The rule (`F.R`) that became active last: holds and event schemas that follow belong to it. */
  lastRule?: string;
  /**
   * Its requests to ORD not answered yet, keyed by its activation number (`N` of its `activate
   * schema S() (activation #N, to ORD)` line): the schema and the rule (`F.R`, '' when none) that
   * became active last when it logged the line. ORD's `activate S (activation #N from SUP)` takes
   * its rule from here (ORD may receive the request after the supervisor's next rule became active,
   * and a refused request's START comes like any other); the entry goes when ORD activates it or
   * the supervisor undoes it (a refused one: `undo: deactivate schema S (activation #N, to ORD)`).
   */
  toOrd?: Map<string, { schema: string; rule: string }>;
  /**
   * The event schemas it runs now (`activate schema S() (event schema)` until its `undo:
   * deactivate schema S (event schema)`), with the rule (`F.R`, '' when none) whose action it was:
   * the Monitor shows an active event schema with that rule, not with another supervisor that
   * holds one of its modules.
   */
  eventSchemas?: Map<string, string>;
  /** Modules and event flows this supervisor holds (an event schema it activated), with the rule. */
  heldModules: Map<string, string>;
  heldFlows: Map<string, string>;
  /**
   * Receivers whose full mailbox makes it keep its requests (a `requests_kept` record, until its
   * `requests_kept_end`), keyed by the receiver module's name.
   */
  keptFor: Map<string, KeptRequests>;
}

/** A streak of requests a supervisor keeps for one receiver's full mailbox (docs/runtime-api.md, queued sends). */
export interface KeptRequests {
  /** When the supervisor began to keep them (its `requests_kept` record). */
  since: Ns;
  /** The first request kept (`STOP`, `SETPARAM`, ...), '' when the record names none. */
  request: string;
}

export interface SchemaActivation {
  active: boolean;
  since: Ns;
  /** `SUP.F.R` whose activation ORD serves (its `activate` line), when known. */
  by?: string;
  /**
   * The START ORD received last for it and has not answered yet (activated or refused): its
   * supervisor and the rule (`F.R`) it is taken for, for an ORD line that does not say whose
   * activation it serves (a log of an older version).
   */
  asked?: { sup: string; rule?: string; activation?: string };
  activations: number;
  conflicts: number;
}

/**
 * The schema that ended last (the Active schemas' `none` says which, when and why: a schema that
 * ended is not just gone from the list). `how`: `deactivated` (ORD's `deactivate` line of a periodic
 * schema), `undone` (a supervisor's `undo: deactivate schema S (event schema)`), `ord-exit` (ORD's
 * exit or crash record ended its periodic schemas), `ord-gone` (ORD's log ends with no exit record:
 * shown ended at its last record, MonitorModel's ordGone).
 */
export interface EndedSchema {
  name: string;
  kind: 'periodic' | 'event';
  t: Ns;
  how: 'deactivated' | 'undone' | 'ord-exit' | 'ord-gone';
  /** `SUP.F.R` that had activated it, when known. */
  by?: string;
}

/** Response-time histogram buckets: 8 per decade from 1 µs to 10 s, plus under/overflow. */
export const HIST_BUCKETS = 58;
export const HIST_MIN_NS = 1e3;
export const HIST_PER_DECADE = 8;

export interface MissMark {
  t: Ns;
  cycle: number;
}

export interface PeriodicState {
  releases: number;
  /** The modules ORD released in it (MAX_NAMES at most), in the order of their first release: the schema's block shows their CPU per release (moduleCpuText). */
  modules: string[];
  lastCycle: number;
  /** Release time of the last release, ns since the start. */
  lastRelease: Ns;
  completions: number;
  lastResponseNs: number;
  maxResponseNs: number;
  sumResponseNs: number;
  histogram: number[];
  /**
   * How late ORD released its cycles (`release_ns - tick_ns` of each cycle's first release), in
   * the response histogram's buckets, and the largest: `contract trace` tells the same in its
   * schema line (finer: 64 bins a decade); none in a simulation, released on its ticks.
   */
  lateHistogram: number[];
  lateCycles: number;
  maxLateNs: number;
  deadlineMisses: number;
  /** Every release ORD skipped (as ORD counts them: its lines tell a cycle's first skip, and the rest when the cycle ends). */
  overruns: number;
  /** The current cycle has skipped a release and has not ended: `overruns` counts 1 for it until it does. */
  overrunning: boolean;
  missedTicks: number;
  /**
   * Cycles ORD itself released at or past their CRITICAL_DELAY (its `late release: ...` line): missed,
   * but no ORD:0 and no ord_deadline_miss (so not in `deadlineMisses`), counted as `contract trace`
   * counts them (`lateReleases`).
   */
  lateReleases: number;
  /** The last misses, overruns and late releases (bounded), for the timeline marks. */
  recentMisses: MissMark[];
  recentOverruns: MissMark[];
  recentLateReleases: MissMark[];
}

export interface ModuleState {
  /** Between run_started and run_finished (a release or a START). */
  running: boolean;
  /** The process is up (module_started seen, no module_exit). */
  alive: boolean;
  runs: number;
  since: Ns;
  /** The CPU time of its last finished run, and the largest (run_finished's `cpu_ns`: its own thread's CPU during the run; absent in logs of older versions and while no run reported one above 0; never ORD's nor a supervisor's, whose run is their whole life). */
  lastCpuNs?: number;
  maxCpuNs?: number;
  /** Its code crashed (its `module_crashed` record: the runtime's signal handler wrote it as the module died), in `contract trace`'s words: `crashed: signal 11 (SIGSEGV)`; gone when it is started again. */
  crashed?: string;
  /**
   * It wrote no end, yet another module's record says it is no longer running (killed from
   * outside: gone-signs.ts): `gone: ORD: START request to SRT: module not running ...`; gone when
   * its end or a start is read.
   */
  gone?: string;
}

export interface FlowCount {
  count: number;
  last: Ns;
  /** Values the flow dropped (data_dropped: the consumer's queue full, ...), and the last one's reason. */
  dropped?: number;
  dropReason?: string;
  /**
   * An event flow's posts that waited for room in its subscriber's full mailbox, over all its
   * `event_waited` records (one per streak) so far: how many, their time in all, the longest
   * (panel-text.ts flowWaitText, flowWaitTitle: the story's closing line for the flow).
   */
  waits?: number;
  waitNs?: number;
  maxWaitNs?: number;
  /** An event flow's deliveries' longest latency (`event_received`'s `latency_ns`): the closing line of a flow that waited names it. */
  maxLatencyNs?: number;
  /** A supervisor's event flow: the last value it received (its `event_received` record's, cut at MAX_VALUE_CHARS), and how many of its events changed no rule (`rules=0`). */
  lastValue?: string;
  unmatched?: number;
}

export interface MonitorState {
  /** Time of the last record folded in. */
  t: Ns;
  /** Records folded in: readable ones (a line that is no record counts in unknownLines instead, as `contract trace` counts them). */
  records: number;
  supervisors: Map<string, SupervisorState>;
  /** How many records changed `supervisors` so far: a view redraws them only when it moved. */
  supervisorChanges: number;
  schemas: Map<string, SchemaActivation>;
  periodic: Map<string, PeriodicState>;
  modules: Map<string, ModuleState>;
  /** Keyed `PRODUCER:port->CONSUMER:port`. */
  dataFlows: Map<string, FlowCount>;
  eventFlows: Map<string, FlowCount>;
  /**
   * Events no one received (`event_posted` with `no subscriber`: the supervisor that waited for it had
   * unsubscribed, or none ever subscribed), keyed by the event port `MODULE:port`.
   */
  unheardEvents: Map<string, FlowCount>;
  /** Lines that are no record (unreadable). */
  unknownLines: number;
  /**
   * The data flows ORD connected that delivered nothing or far less than their reader read, and the
   * event flows a supervisor connected that delivered nothing, in `contract trace`'s words
   * (DataFlowUse): told once the records are over (MonitorModel.recordsEnded), empty before.
   */
  quietDataFlows: string[];
  /**
   * Distinct names folded (supervisors, their functions, rules and holds, schemas, modules, flows),
   * and the receivers a supervisor keeps requests for now (counted down when it no longer does): at
   * most MAX_NAMES.
   */
  names: number;
  /** Records whose name would have gone past MAX_NAMES: not folded (a forged log; a run has far fewer). */
  namesPastBound: number;
  /** ORD's `priority` record (`SCHED_FIFO 90`, `nice 1 (priority 90)`): whether the run was real-time; '' before it. */
  ordPriority: string;
  /** The schema that ended last, if any did (EndedSchema). */
  lastEnded?: EndedSchema;
}

/**
 * Distinct names a state folds at most: a run of 31 modules and 8 supervisors with 43 rules names
 * about 200. A log a module's code wrote with a new name on each line (anything in the sandbox may
 * write its own log) would otherwise grow the state, and each checkpoint's copy of it, with every
 * line: 300,000 such lines ran a recorded run out of memory.
 */
export const MAX_NAMES = 1024;

export const RECENT_MARKS = 64;

export function emptyState(): MonitorState {
  return { t: 0, records: 0, supervisors: new Map(), supervisorChanges: 0, schemas: new Map(), periodic: new Map(), modules: new Map(), dataFlows: new Map(), eventFlows: new Map(), unheardEvents: new Map(), unknownLines: 0, quietDataFlows: [], names: 0, namesPastBound: 0, ordPriority: '' };
}

/** A deep copy (the state is plain data: objects, arrays and Maps, which structuredClone and postMessage keep). */
export function cloneState(s: MonitorState): MonitorState {
  return structuredClone(s);
}

export function histogramBucket(ns: number): number {
  if (!(ns > 0) || ns < HIST_MIN_NS) return 0;
  const b = 1 + Math.floor(Math.log10(ns / HIST_MIN_NS) * HIST_PER_DECADE);
  return Math.min(HIST_BUCKETS - 1, b);
}

/** Lower bound (ns) of a bucket (bucket 0: below 1 µs). */
export function bucketStartNs(b: number): number {
  return b <= 0 ? 0 : HIST_MIN_NS * 10 ** ((b - 1) / HIST_PER_DECADE);
}

/**
 * The upper bound (ns) of the bucket that holds the q-quantile (0 < q < 1) of a histogram of
 * `total` counts: the quantile is below it (a bucket is an eighth of a decade); `max` bounds it.
 */
export function quantileBoundNs(histogram: readonly number[], total: number, q: number, max: number): number {
  const b = quantileBin(histogram, total, q);
  return b < 0 ? max : Math.min(max, bucketStartNs(b + 1));
}
