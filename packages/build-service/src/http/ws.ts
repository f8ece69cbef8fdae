/**
 * GET /api/jobs/:id/ws: the same events as the SSE stream as WebSocket JSON text frames
 * ({type, seq, t, ...}), replay included; the client may send {"type":"cancel"}. A client that
 * falls behind by more than SERVICE_BOUNDS.streamBufferedBytes of live events is dropped.
 * `?trace=all|none|only` chooses the events (traceFilter): all, all but `trace`, or `trace` and
 * `end` only; the ones sent keep their seq, so `?after=` resumes a filtered stream as any other.
 */
import type { IncomingMessage } from 'node:http';
import type { Duplex } from 'node:stream';
import { WebSocketServer } from 'ws';
import type { JobService } from '../job-service.js';
import { SERVICE_BOUNDS } from '../limits.js';
import { LiveBacklog } from './live-backlog.js';
import type { StreamBudget } from './stream-budget.js';
import { wsFrame } from './event-wire.js';
import type { JobEvent } from '../pipeline/job-events.js';

/** Which events a socket gets (`?trace=`): every one, all but `trace` ones, `trace` ones and `end`. */
export type TraceFilter = 'all' | 'none' | 'only';
const TRACE_FILTERS: readonly TraceFilter[] = ['all', 'none', 'only'];

/** The refusal of a bad `?trace=`, the body of its 400. */
export const TRACE_FILTER_ERROR = 'trace must be one of: all, none, only (default all)';

/** The `?trace=` of an upgrade URL: 'all' when absent; null for any other value (or several). */
export function traceFilter(url: URL): TraceFilter | null {
  const values = url.searchParams.getAll('trace');
  if (values.length === 0) return 'all';
  const v = values[0] as TraceFilter;
  return TRACE_FILTERS.includes(v) && values.every((x) => x === v) ? v : null;
}

function wanted(filter: TraceFilter, e: JobEvent): boolean {
  if (filter === 'none') return e.type !== 'trace';
  if (filter === 'only') return e.type === 'trace' || e.type === 'end';
  return true;
}

export class JobWebSockets {
  // clients only send {"type":"cancel"}: a bounded frame size (SERVICE_BOUNDS.wsMessageBytes)
  private readonly wss = new WebSocketServer({ noServer: true, maxPayload: SERVICE_BOUNDS.wsMessageBytes });

  constructor(
    private readonly service: Pick<JobService, 'get' | 'cancel'>,
    private readonly budget?: StreamBudget,
    private readonly streamBufferedBytes = SERVICE_BOUNDS.streamBufferedBytes,
  ) {}

  /** Handles an upgrade for a job id; returns false when the job does not exist. */
  upgrade(id: string, after: number, req: IncomingMessage, socket: Duplex, head: Buffer, trace: TraceFilter = 'all'): boolean {
    const job = this.service.get(id);
    if (!job) return false;
    this.wss.handleUpgrade(req, socket, head, (ws) => {
      // a protocol error of the client (bad frame, frame above maxPayload) is emitted as 'error':
      // without a listener it would be thrown and end the whole service
      let unsubscribe: () => void = () => {};
      ws.on('error', () => {
        unsubscribe();
        ws.terminate();
      });
      // a client that leaves more than streamBufferedBytes of live events unread (beyond its
      // replay) is dropped, as on SSE (http/sse.ts)
      const backlog = new LiveBacklog(this.streamBufferedBytes);
      // the server's budget for all its streaming clients may drop this one too (stream-budget.ts)
      let dropped = false;
      const drop = (): void => {
        if (dropped) return;
        dropped = true;
        share?.leave();
        unsubscribe();
        ws.terminate();
      };
      const share = this.budget?.join(drop);
      unsubscribe = job.events.subscribe(after, (e) => {
        // a filtered event is not sent, nor counted in the backlog (the end always passes)
        if (dropped || !wanted(trace, e)) return;
        const text = wsFrame(e);
        backlog.sent(Buffer.byteLength(text));
        ws.send(text, () => {}); // a send on a closing socket reports here, not thrown
        if (backlog.tooFarBehind(ws.bufferedAmount)) {
          drop();
          return;
        }
        share?.holds(ws.bufferedAmount);
        if (e.type === 'end') setImmediate(() => ws.close(1000, 'job ended'));
      });
      backlog.replayDone();
      ws.on('message', (data) => {
        try {
          const msg = JSON.parse(String(data)) as { type?: string };
          if (msg?.type === 'cancel') this.service.cancel(id).catch(() => {});
        } catch {
          /* ignore malformed client frames */
        }
      });
      ws.on('close', () => {
        share?.leave();
        unsubscribe();
      });
      if (job.events.isEnded) setImmediate(() => ws.close(1000, 'job ended'));
    });
    return true;
  }

  close(): void {
    for (const c of this.wss.clients) c.terminate();
    this.wss.close();
  }
}
