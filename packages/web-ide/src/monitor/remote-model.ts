/**
 * The page's side of a live run folded in a Web Worker (live-follower.ts): a MonitorView that
 * mirrors the worker's last snapshot (the live state, the end, the count, every mark) and asks
 * the worker for the state at an earlier time when the cursor is put there. The panel draws
 * from it as from a MonitorModel; a state asked for is drawn in the frame after it arrives.
 */
import type { TraceLine } from '@contract-studio/build-service/trace';
import type { Mark } from './model-view.js';
import { emptyState, type MonitorState, type Ns } from './monitor-state.js';
import { marksIn, type MonitorView } from './model-view.js';
import type { FromFollower, Snapshot, ToFollower } from './live-follow-protocol.js';

/** What the model needs of a Worker (a MessagePort-like pair in tests). */
export interface FollowerPort {
  postMessage(m: ToFollower): void;
  onmessage: ((e: MessageEvent<FromFollower>) => void) | null;
  terminate?(): void;
}

export class RemoteMonitorModel implements MonitorView {
  live: MonitorState = emptyState();
  readonly marks: Mark[] = [];
  end: Ns = 0;
  recordCount = 0;
  /** Lines of the run's logs the stream did not bring (records the build service did not keep: live-follower.ts). */
  missed = 0;
  version = 0;
  /** The stream ended: nothing more comes (see problems). */
  ended = false;
  /** With `ended`: how the job ended (`succeeded`, `cancelled`, `failed: …`), or why the stream stopped. */
  outcome: string | undefined;
  /** Why the trace is not whole, when it is not. */
  readonly problems: string[] = [];
  /** The worker's time spent folding (ms). */
  foldMs = 0;
  /** Called after each change (a snapshot, an answered state): the panel schedules a frame. */
  onChange: (() => void) | undefined;
  /** Called with each snapshot and the version it became (the benchmark's latency hook). */
  onSnapshot: ((s: Snapshot, version: number) => void) | undefined;
  /** Resolves once the stream has ended and every record it brought is in `recordCount`. */
  readonly settled: Promise<void>;
  private settle!: () => void;
  private at: { t: Ns; state: MonitorState; exact: boolean } | undefined;
  private asked: Ns | undefined;
  /**
   * The run's clock minus the page's (performance.now() in ns), at its largest: a record of time
   * `end` was written at the latest when the snapshot bringing it came, so the run's clock was at
   * least `end` then. One subtraction per snapshot, none per record.
   */
  private clockOffset = -Infinity;
  private readonly now: () => number;

  constructor(private readonly port: FollowerPort, url: string | null, opts: { measure?: boolean; now?: () => number } = {}) {
    this.now = opts.now ?? (() => performance.now());
    this.settled = new Promise((r) => (this.settle = r));
    port.onmessage = (e) => this.receive(e.data);
    port.postMessage({ type: 'follow', url, measure: opts.measure });
  }

  /** Trace lines handed over by the page, folded as if they came on the stream (tests). */
  feed(records: TraceLine[]): void {
    this.port.postMessage({ type: 'feed', records });
  }

  stateAt(t: Ns): MonitorState | undefined {
    if (t >= this.end) return this.live;
    if (this.at?.t === t) return this.at.state;
    if (this.asked !== t) {
      this.asked = t;
      this.port.postMessage({ type: 'stateAt', t });
    }
    return undefined;
  }

  exactAt(t: Ns): boolean {
    return t >= this.end || this.at?.t !== t || this.at.exact;
  }

  marksBetween(lo: Ns, hi: Ns): Mark[] {
    return marksIn(this.marks, lo, hi);
  }

  /**
   * The run's clock at `nowMs` (ns since its first record): the page's clock plus the largest
   * offset seen (so it never runs backwards, and shows the least delay of the stream), never
   * before the last record. Through a quiet stretch of the run it goes on (the time since the
   * last record came); undefined before the first record.
   */
  runClock(nowMs: number): Ns | undefined {
    if (!this.recordCount || this.clockOffset === -Infinity) return undefined;
    return Math.max(this.end, nowMs * 1e6 + this.clockOffset);
  }

  /** The worker failed (it could not load, or threw): the live trace stops here, and says why. */
  fail(why: string): void {
    if (this.ended) return;
    this.ended = true;
    this.problems.push(why);
    this.version++;
    this.onChange?.();
    this.settle();
  }

  /** Stops the worker (the run is forgotten). */
  dispose(): void {
    this.port.postMessage({ type: 'stop' });
    this.port.terminate?.();
    this.settle();
  }

  private receive(m: FromFollower): void {
    if (m.type === 'state') {
      // kept even when the cursor moved on meanwhile (it may come back to it: a scrub)
      if (m.t === this.asked) this.asked = undefined;
      this.at = { t: m.t, state: m.state, exact: m.exact };
    } else {
      this.live = m.live;
      this.end = m.end;
      this.recordCount = m.count;
      if (m.count > 0) this.clockOffset = Math.max(this.clockOffset, m.end - this.now() * 1e6);
      this.missed = Number.isSafeInteger(m.missed) ? m.missed : 0;
      for (const k of m.marks) this.marks.push(k);
      for (const p of m.problems) this.problems.push(p);
      this.foldMs = m.foldMs;
      if (m.ended) {
        this.ended = true;
        if (typeof m.outcome === 'string') this.outcome ??= m.outcome;
      }
    }
    this.version++;
    if (m.type === 'snapshot') this.onSnapshot?.(m, this.version);
    this.onChange?.();
    if (this.ended) this.settle();
  }
}
