/**
 * GET /api/jobs/:id/events as Server-Sent Events: replays the job's events after Last-Event-ID
 * (or ?after=), then streams live ones; closes after the `end` event. A slow client never holds
 * the others back: its events wait in its socket's buffer, up to the replay plus
 * SERVICE_BOUNDS.streamBufferedBytes of live events, beyond which it is disconnected (the live
 * trace of a 1 kHz schema is megabytes a second; the client may resume from its last event id).
 * An event is serialized once for all the clients it is delivered to (event-wire.ts).
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { Job } from '../pipeline/job.js';
import { SERVICE_BOUNDS } from '../limits.js';
import { LiveBacklog } from './live-backlog.js';
import type { StreamBudget, StreamShare } from './stream-budget.js';
import { sseFrame } from './event-wire.js';

export function streamSse(job: Pick<Job, 'events'>, req: IncomingMessage, res: ServerResponse, after: number, budget?: StreamBudget, streamBufferedBytes = SERVICE_BOUNDS.streamBufferedBytes): void {
  res.writeHead(200, {
    'Content-Type': 'text/event-stream; charset=utf-8',
    'Cache-Control': 'no-cache, no-transform',
    Connection: 'keep-alive',
    'X-Accel-Buffering': 'no',
  });
  res.write(': contract build service\n\n');
  let closed = false;
  const backlog = new LiveBacklog(streamBufferedBytes);
  // too far behind (its own bound, or the server's budget for all): dropped at once (end() would
  // wait for it to read what is buffered)
  const drop = (): void => {
    if (closed) return;
    closed = true;
    clearInterval(ping);
    share?.leave();
    setImmediate(() => {
      unsubscribe();
      res.destroy();
    });
  };
  const share: StreamShare | undefined = budget?.join(drop);
  // a client that goes away mid-write must end this stream only, never the service
  const write = (text: string): void => {
    if (closed) return;
    try {
      res.write(text);
      backlog.sent(Buffer.byteLength(text));
      if (backlog.tooFarBehind(res.writableLength)) drop();
      else share?.holds(res.writableLength);
    } catch {
      setImmediate(stop);
    }
  };
  const ping = setInterval(() => write(': ping\n\n'), 15_000);
  ping.unref();
  let unsubscribe: () => void = () => {};
  const stop = (): void => {
    if (closed) return;
    closed = true;
    clearInterval(ping);
    share?.leave();
    unsubscribe();
    try {
      res.end();
    } catch {
      res.destroy();
    }
  };
  res.on('error', stop);
  req.on('error', stop);
  unsubscribe = job.events.subscribe(after, (e) => {
    write(sseFrame(e));
    if (e.type === 'end') setImmediate(stop);
  });
  backlog.replayDone();
  req.on('close', stop);
  if (job.events.isEnded) setImmediate(stop);
}
