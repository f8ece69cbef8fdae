/**
 * GET /api/jobs/:id/events as Server-Sent Events: replays the job's events after Last-Event-ID
 * (or ?after=), then streams live ones; closes after the `end` event. Respects back-pressure by
 * buffering in the socket (events are bounded by the output limits).
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { Job } from '../pipeline/job.js';
import type { JobEvent } from '../pipeline/job-events.js';

export function eventPayload(e: JobEvent): Record<string, unknown> {
  const { type: _type, ...data } = e;
  return data;
}

/** The last event framed, and its frame: every client attached gets the same live event in turn. */
let lastEvent: JobEvent | null = null;
let lastFrame = '';

/** The SSE frame of an event (serialized once for all the clients it is delivered to at once). */
export function sseFrame(e: JobEvent): string {
  if (e !== lastEvent) {
    lastFrame = `id: ${e.seq}\nevent: ${e.type}\ndata: ${JSON.stringify(eventPayload(e))}\n\n`;
    lastEvent = e;
  }
  return lastFrame;
}

export function streamSse(job: Job, req: IncomingMessage, res: ServerResponse, after: number): void {
  res.writeHead(200, {
    'Content-Type': 'text/event-stream; charset=utf-8',
    'Cache-Control': 'no-cache, no-transform',
    Connection: 'keep-alive',
    'X-Accel-Buffering': 'no',
  });
  res.write(': contract build service\n\n');
  let closed = false;
  // a client that goes away mid-write must end this stream only, never the service
  const write = (text: string): void => {
    if (closed) return;
    try {
      res.write(text);
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
  req.on('close', stop);
  if (job.events.isEnded) setImmediate(stop);
}
