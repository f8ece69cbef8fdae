/**
 * GET /api/jobs/:id/ws: the same events as the SSE stream as WebSocket JSON text frames
 * ({type, seq, t, ...}), replay included; the client may send {"type":"cancel"}, any other frame
 * is answered with an error frame (ws-client-frames.ts). A client that
 * falls behind by more than SERVICE_BOUNDS.streamBufferedBytes of live events is dropped.
 * `?trace=all|none|only` chooses the events (traceFilter): all, all but `trace`, or `trace` and
 * `end` only; the ones sent keep their seq, so `?after=` resumes a filtered stream as any other.
 * `?batch=1` (batchParam): the events go several to a frame, a JSON array of them in order, at
 * most one frame every BATCH_MS while they stream (the first after a quiet spell at once). A module
 * printing 10,000 lines a second was 10,000 frames a second, each a task of the page's main
 * thread: the page fell seconds behind the run and stopped answering (docs/build-service-api.md).
 */
import type { IncomingMessage } from 'node:http';
import type { Duplex } from 'node:stream';
import { WebSocket, WebSocketServer } from 'ws';
import type { JobService } from '../job-service.js';
import { SERVICE_BOUNDS } from '../limits.js';
import { LiveBacklog } from './live-backlog.js';
import type { StreamBudget } from './stream-budget.js';
import { wsFrame } from './event-wire.js';
import { clientErrorFrame, readClientFrame } from './ws-client-frames.js';
import type { JobEvent } from '../pipeline/job-events.js';

/**
 * Which events a socket gets (`?trace=`): every one, all but `trace` ones, `trace` ones and `end`;
 * `launcher`: those of `only` and the launcher's own output lines (source `launcher`: its
 * `contract-launch:` lines, which say how each module ended), for the IDE's Monitor.
 */
export type TraceFilter = 'all' | 'none' | 'only' | 'launcher';
const TRACE_FILTERS: readonly TraceFilter[] = ['all', 'none', 'only', 'launcher'];

/** The refusal of a bad `?trace=`, the body of its 400. */
export const TRACE_FILTER_ERROR = 'trace must be one of: all, none, only, launcher (default all)';

/** The refusal of a bad `?batch=`, the body of its 400. */
export const BATCH_ERROR = 'batch must be 0 or 1 (default 0)';

/** The `?batch=` of an upgrade URL: false when absent or 0, true for 1; null for any other value (or several). */
export function batchParam(url: URL): boolean | null {
  const values = url.searchParams.getAll('batch');
  if (values.length === 0) return false;
  const v = values[0]!;
  return (v === '0' || v === '1') && values.every((x) => x === v) ? v === '1' : null;
}

/** A batching socket sends at most one frame per this many ms while events stream. */
export const BATCH_MS = 50;
/** A batching socket's frame holds at most this many bytes of events (a replay goes as several frames; an event bigger than that alone). */
export const BATCH_BYTES = 256 * 1024;

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
  if (filter === 'launcher') return e.type === 'trace' || e.type === 'end' || (e.type === 'line' && e.source === 'launcher');
  return true;
}

export class JobWebSockets {
  // clients only send {"type":"cancel"} (ws-client-frames.ts): a bounded frame size (SERVICE_BOUNDS.wsMessageBytes)
  private readonly wss = new WebSocketServer({ noServer: true, maxPayload: SERVICE_BOUNDS.wsMessageBytes });

  constructor(
    private readonly service: Pick<JobService, 'get' | 'cancel'>,
    private readonly budget?: StreamBudget,
    private readonly streamBufferedBytes = SERVICE_BOUNDS.streamBufferedBytes,
  ) {}

  /** Handles an upgrade for a job id; returns false when the job does not exist. */
  upgrade(id: string, after: number, req: IncomingMessage, socket: Duplex, head: Buffer, trace: TraceFilter = 'all', batch = false): boolean {
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
      /** Events not sent yet (a batching socket): their frames, and their bytes with a comma each. */
      let pending: string[] = [];
      let pendingBytes = 0;
      let flushTimer: NodeJS.Timeout | undefined;
      let lastFlush = -Infinity;
      const drop = (): void => {
        if (dropped) return;
        dropped = true;
        clearTimeout(flushTimer);
        pending = [];
        share?.leave();
        unsubscribe();
        ws.terminate();
      };
      const share = this.budget?.join(drop);
      const send = (text: string): void => {
        backlog.sent(Buffer.byteLength(text));
        ws.send(text, () => {}); // a send on a closing socket reports here, not thrown
        if (backlog.tooFarBehind(ws.bufferedAmount)) return drop();
        share?.holds(ws.bufferedAmount);
      };
      /** Sends the events held, as one frame (a batching socket). */
      const flush = (): void => {
        clearTimeout(flushTimer);
        flushTimer = undefined;
        if (dropped || pending.length === 0) return;
        const text = `[${pending.join(',')}]`;
        pending = [];
        pendingBytes = 0;
        lastFlush = performance.now();
        send(text);
      };
      unsubscribe = job.events.subscribe(after, (e) => {
        // a filtered event is not sent, nor counted in the backlog (the end always passes)
        if (dropped || !wanted(trace, e)) return;
        const text = wsFrame(e);
        if (!batch) send(text);
        else {
          // a burst (a replay) goes in frames of BATCH_BYTES at most (a bigger event alone): the
          // frame is each event and a comma or bracket after it, and its opening bracket
          const bytes = Buffer.byteLength(text) + 1;
          if (pending.length && 1 + pendingBytes + bytes > BATCH_BYTES) flush();
          pending.push(text);
          pendingBytes += bytes;
          // the end goes at once, with what is held
          if (e.type === 'end') flush();
          else flushTimer ??= setTimeout(flush, Math.max(0, lastFlush + BATCH_MS - performance.now()));
        }
        if (e.type === 'end') setImmediate(() => ws.close(1000, 'job ended'));
      });
      // the replay's last frame is the replay's, not live events
      flush();
      backlog.replayDone();
      ws.on('message', (data, isBinary) => {
        const frame = readClientFrame(data, isBinary);
        if (frame.type === 'cancel') this.service.cancel(id).catch(() => {});
        // a frame the service does not take is said to the client (not an event: no seq, never batched); the stream goes on
        else if (!dropped && ws.readyState === WebSocket.OPEN) send(clientErrorFrame(frame.error));
      });
      ws.on('close', () => {
        clearTimeout(flushTimer);
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

  /**
   * The service going away (its jobs ended, each socket sent its job's `end`): every socket still
   * open is closed with 1001 (going away) and given up to `graceMs` for its closing handshake,
   * then cut (a socket that does not answer).
   */
  async shutdown(graceMs = 1000): Promise<void> {
    const open = [...this.wss.clients];
    // a socket closing already (1000 after its job's end) finishes its own handshake
    for (const c of open) if (c.readyState === WebSocket.OPEN) c.close(1001, 'service closing');
    let timer: NodeJS.Timeout | undefined;
    await Promise.race([
      Promise.all(open.map((c) => (c.readyState === WebSocket.CLOSED ? undefined : new Promise((r) => c.once('close', r))))),
      new Promise((r) => (timer = setTimeout(r, graceMs))),
    ]);
    clearTimeout(timer);
    this.close();
  }
}
