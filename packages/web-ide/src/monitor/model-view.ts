/**
 * What the Monitor panel reads of a run (monitor-panel.ts): the same for a model folded on the
 * page (MonitorModel: a recorded run, a simulation) and for a live run folded in a Web Worker
 * (RemoteMonitorModel, remote-model.ts), whose states far back arrive a moment after they are asked for.
 */
import type { MonitorState, Ns } from './monitor-state.js';

/** One thing the timeline marks at its time. */
export interface Mark {
  t: Ns;
  kind: 'rule' | 'schema' | 'miss' | 'late' | 'overrun' | 'function' | 'user' | 'error' | 'kept' | 'crash' | 'unheard' | 'waited';
  /** Where: the supervisor or schema (a crash, an event no one received: the module). */
  where: string;
  label: string;
  /** Rule marks: active (true) or inactive. */
  on?: boolean;
}

export interface MonitorView {
  /** Bumped on every change the panel may draw (it redraws only when this or its cursor moved). */
  readonly version: number;
  /** Time of the last record (ns since the first). */
  readonly end: Ns;
  /** Lines folded (records and unreadable lines): the model's size. What a label counts is in `live` (record-counts.ts). */
  readonly recordCount: number;
  /** The state after the last record. */
  readonly live: MonitorState;
  /** What the timeline marks, in time order (bounded). */
  readonly marks: readonly Mark[];
  /**
   * The state at t (every record with time <= t folded in); undefined while it is being computed
   * elsewhere (the view then bumps `version` when it has it). Do not mutate it.
   */
  stateAt(t: Ns): MonitorState | undefined;
  /** Whether states before t are exact (their raw records are still kept). */
  exactAt(t: Ns): boolean;
  /** Marks with lo <= t <= hi. */
  marksBetween(lo: Ns, hi: Ns): Mark[];
  /**
   * A live run's own clock at `nowMs` (performance.now()): ns since its first record, estimated
   * from when its records arrived, never before the last record; undefined before the first record
   * (and for a run that is not live: absent).
   */
  runClock?(nowMs: number): Ns | undefined;
}

/** Marks with lo <= t <= hi of a time-ordered list (binary search). */
export function marksIn(marks: readonly Mark[], lo: Ns, hi: Ns): Mark[] {
  let a = 0;
  let b = marks.length;
  while (a < b) {
    const m = (a + b) >> 1;
    if (marks[m]!.t < lo) a = m + 1;
    else b = m;
  }
  const out: Mark[] = [];
  for (let i = a; i < marks.length && marks[i]!.t <= hi; i++) out.push(marks[i]!);
  return out;
}
