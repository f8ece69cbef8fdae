/** Test/bench helpers: a tiny HTTP + SSE client of the build service. */
import { request } from 'node:http';
import type { JobEvent } from '../pipeline/job-events.js';
import { decodeTraceRecords } from '../trace/wire.js';

export async function postJob(base: string, body: unknown, headers: Record<string, string> = {}): Promise<{ status: number; json: Record<string, unknown>; headers: Headers }> {
  const res = await fetch(`${base}/api/jobs`, { method: 'POST', headers: { 'content-type': 'application/json', ...headers }, body: JSON.stringify(body) });
  return { status: res.status, json: (await res.json()) as Record<string, unknown>, headers: res.headers };
}

export async function getJob(base: string, id: string): Promise<Record<string, any>> {
  const res = await fetch(`${base}/api/jobs/${id}`);
  return (await res.json()) as Record<string, any>;
}

/**
 * A job event from its wire form (an SSE payload with its type, or a WebSocket frame): a trace
 * event's records come in their columnar wire form (trace/wire.ts) and are decoded.
 */
export function jobEventFromWire(e: Record<string, unknown>): JobEvent {
  if (e.type === 'trace') return { type: 'trace', seq: e.seq, t: e.t, records: decodeTraceRecords(e) } as JobEvent;
  return e as unknown as JobEvent;
}

/**
 * Follows the SSE stream of a job from event `after` on until its end (or `signal` aborts it),
 * handing each event to `onEvent` as it arrives; keeps nothing.
 */
export async function streamEvents(base: string, id: string, onEvent: (e: JobEvent) => void, after = 0, signal?: AbortSignal): Promise<void> {
  const res = await fetch(`${base}/api/jobs/${id}/events${after ? `?after=${after}` : ''}`, { signal });
  if (!res.ok || !res.body) throw new Error(`events: HTTP ${res.status}`);
  const decoder = new TextDecoder();
  let buf = '';
  for await (const chunk of res.body as unknown as AsyncIterable<Uint8Array>) {
    buf += decoder.decode(chunk, { stream: true });
    let i;
    while ((i = buf.indexOf('\n\n')) >= 0) {
      const block = buf.slice(0, i);
      buf = buf.slice(i + 2);
      let type = '';
      let data = '';
      for (const l of block.split('\n')) {
        if (l.startsWith('event: ')) type = l.slice(7);
        else if (l.startsWith('data: ')) data += l.slice(6);
      }
      if (!type) continue;
      onEvent(jobEventFromWire({ type, ...(JSON.parse(data) as Record<string, unknown>) }));
    }
  }
}

/** Reads the SSE stream of a job until its end; `onEvent` sees each event as it arrives. */
export async function readEvents(base: string, id: string, onEvent?: (e: JobEvent) => void, after = 0): Promise<JobEvent[]> {
  const events: JobEvent[] = [];
  await streamEvents(base, id, (e) => {
    events.push(e);
    onEvent?.(e);
  }, after);
  return events;
}

export async function waitJob(base: string, id: string): Promise<Record<string, any>> {
  await readEvents(base, id);
  return getJob(base, id);
}

/** Status and body of a raw WebSocket upgrade request to `url` (101 for an accepted one; its socket is closed at once). */
export function upgradeStatus(url: string): Promise<{ status: number; body: string }> {
  return new Promise((resolve, reject) => {
    const r = request(url, {
      agent: false,
      headers: { connection: 'Upgrade', upgrade: 'websocket', 'sec-websocket-version': '13', 'sec-websocket-key': 'dGhlIHNhbXBsZSBub25jZQ==' },
    });
    r.on('response', (res) => {
      let body = '';
      res.setEncoding('utf8');
      res.on('data', (c: string) => (body += c));
      res.on('end', () => resolve({ status: res.statusCode ?? 0, body }));
    });
    r.on('upgrade', (res, socket) => {
      socket.destroy();
      resolve({ status: res.statusCode ?? 0, body: '' });
    });
    r.on('error', reject);
    r.end();
  });
}
