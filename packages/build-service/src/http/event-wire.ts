/**
 * A job event as it goes on the wire, the same for the SSE and WebSocket streams
 * (docs/build-service-api.md "Events"): the event's fields without its type (SSE names the type
 * in its `event:` line; a WebSocket frame carries it as "type"), a trace event's records in their
 * columnar wire form (trace/wire.ts). Each event is serialized once for all the clients it is
 * delivered to: a live event goes to every attached client in turn.
 */
import type { JobEvent } from '../pipeline/job-events.js';
import { encodeTraceRecords } from '../trace/wire.js';

/** The event's fields on the wire, without its type. */
export function eventPayload(e: JobEvent): Record<string, unknown> {
  if (e.type === 'trace') return { seq: e.seq, t: e.t, ...encodeTraceRecords(e.records), ...(e.dropped ? { dropped: e.dropped } : {}) };
  const { type: _type, ...data } = e;
  return data;
}

/** The last event serialized, and its JSON payload. */
let lastEvent: JobEvent | null = null;
let lastJson = '';

function payloadJson(e: JobEvent): string {
  if (e !== lastEvent) {
    lastJson = JSON.stringify(eventPayload(e));
    lastEvent = e;
  }
  return lastJson;
}

/** The SSE frame of an event. */
export function sseFrame(e: JobEvent): string {
  return `id: ${e.seq}\nevent: ${e.type}\ndata: ${payloadJson(e)}\n\n`;
}

/** The WebSocket text frame of an event: its payload with "type" first. */
export function wsFrame(e: JobEvent): string {
  const json = payloadJson(e);
  return `{"type":${JSON.stringify(e.type)}${json.length > 2 ? ',' : ''}${json.slice(1)}`;
}
