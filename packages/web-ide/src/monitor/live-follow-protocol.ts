/**
 * The messages between the page (RemoteMonitorModel, remote-model.ts) and the Web Worker that
 * follows a live run's trace (LiveFollower, live-follower.ts). Plain data: they cross by
 * structured clone.
 */
import { shortAtWord } from '../util/short-text.js';
import type { TraceLine } from '@contract-studio/build-service/trace';
import type { Mark } from './model-view.js';
import type { MonitorState, Ns } from './monitor-state.js';

export type ToFollower =
  /** Follow the job's trace: `url` is its WebSocket stream with `trace=launcher` (the trace and the launcher's own lines), or null (fed by `feed`). */
  | { type: 'follow'; url: string | null; measure?: boolean }
  /** Trace lines handed over by the page (tests), folded as if they came on the stream. */
  | { type: 'feed'; records: TraceLine[] }
  /** The state at t (ns since the run's first record): answered by a `state`. */
  | { type: 'stateAt'; t: Ns }
  /** Stop following (the run is forgotten). */
  | { type: 'stop' };

export interface Snapshot {
  type: 'snapshot';
  /** The state after the last record folded in. */
  live: MonitorState;
  end: Ns;
  count: number;
  /** Lines of the run's logs that did not come on the stream (gaps in a log's line numbers: records the service did not keep for this stream). */
  missed: number;
  /** Marks made since the last snapshot. */
  marks: Mark[];
  /** The stream ended (its `end` event, or it broke for good): nothing more will come from it. */
  ended: boolean;
  /** With `ended`: how the job ended (jobOutcome), or why the stream stopped. */
  outcome?: string;
  /** Why the trace is not whole, when it is not (a batch that could not be read, the connection lost). */
  problems: string[];
  /** The worker's time spent folding so far (ms). */
  foldMs: number;
  /** With `measure`: each record folded since the last snapshot, its wall_time and its arrival (Date.now() ms). */
  walls?: Float64Array;
  arrived?: Float64Array;
}

export type FromFollower = Snapshot | { type: 'state'; t: Ns; state: MonitorState; exact: boolean };

/** A live run's outcome when its trace stream broke for good (the job's own end not known then). */
export const CONNECTION_LOST = 'connection to the build service lost';
/** Why its trace is not whole then. */
export const LOST_TRACE = 'lost the connection to the build service: the trace stops here (if the build service is still there when the job ends, the Monitor shows the run from its CSV logs)';

/** The longest job message an outcome keeps (a hostile one could be megabytes): the run list shortens its entries further (monitor-panel.ts). */
const MAX_OUTCOME_MESSAGE = 1000;

/**
 * How a job ended, from its `end` event's result (build-service JobResult: `ok`, `message`;
 * hostile like any stream data): `succeeded`, `cancelled`, or `failed: <message>` (a message past
 * MAX_OUTCOME_MESSAGE ended at a word with `…`).
 */
export function jobOutcome(result: unknown): string {
  const r = result && typeof result === 'object' ? (result as { ok?: unknown; message?: unknown }) : {};
  if (r.ok === true) return 'succeeded';
  const message = typeof r.message === 'string' ? shortAtWord(r.message.slice(0, 4 * MAX_OUTCOME_MESSAGE).replace(/\s+/g, ' ').trim(), MAX_OUTCOME_MESSAGE) : '';
  if (message === 'cancelled') return 'cancelled';
  return message ? `failed: ${message}` : 'failed';
}
