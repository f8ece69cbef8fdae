/**
 * The event streams (http/sse.ts, http/ws.ts) on a real HTTP server and sockets: trace events
 * arrive whole and in order; a client that stops reading neither holds the others back nor the
 * service's memory without end.
 */
import { createServer, type Server } from 'node:http';
import { connect } from 'node:net';
import type { AddressInfo } from 'node:net';
import { afterEach, describe, expect, test } from 'vitest';
import WebSocket from 'ws';
import { JobEvents, type TraceEvent, type TraceLine } from '../pipeline/job-events.js';
import { streamEvents } from '../test-support/client.js';
import { streamSse } from './sse.js';
import { sseFrame, wsFrame } from './event-wire.js';
import { decodeTraceRecords } from '../trace/wire.js';
import { JobWebSockets } from './ws.js';
import { StreamBudget } from './stream-budget.js';

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

describe('SSE stream of a job', () => {
  let server: Server | null = null;
  let sockets: JobWebSockets | null = null;
  afterEach(async () => {
    sockets?.close(); // upgraded sockets are not the HTTP server's to close
    sockets = null;
    server?.closeAllConnections();
    await new Promise((r) => server?.close(r));
    server = null;
  });

  /** A server streaming `events` to every client, with a live-buffer bound of `bound` bytes per client (and `budget` for all). */
  const serve = async (events: JobEvents, bound: number, budget?: StreamBudget): Promise<string> => {
    server = createServer((req, res) => streamSse({ events } as never, req, res, Number(new URL(req.url!, 'http://x').searchParams.get('after') ?? 0), budget, bound));
    await new Promise<void>((r) => server!.listen(0, '127.0.0.1', r));
    return `http://127.0.0.1:${(server!.address() as AddressInfo).port}`;
  };
  const records = (from: number, n: number): TraceLine[] =>
    Array.from({ length: n }, (_, i) => ({ file: 'M_1.csv', line: from + i, text: `${1000 + from + i},2026-11-26T12:00:00.000000Z,M,user,,,0,${'x'.repeat(200)}` }));

  /** A client that connects to SSE and never reads. */
  const stalledClient = (base: string) => {
    const c = connect((new URL(base).port as unknown as number), '127.0.0.1');
    c.write('GET /api/jobs/j/events HTTP/1.1\r\nHost: x\r\n\r\n');
    c.pause();
    c.on('error', () => {});
    return c;
  };

  /**
   * With two clients attached, one of them stalled: 30 MB of live trace (an event of 1000 records
   * every 15 ms; the service wakes every 10 ms at most) from line `first`, then the end. The stalled
   * client must have been unsubscribed (its socket destroyed: the service does not keep 30 MB for it)
   * before the end. Returns the line after the last one sent.
   */
  const floodPastStalled = async (events: JobEvents, first: number): Promise<number> => {
    for (let i = 0; i < 200 && events.subscriberCount < 2; i++) await sleep(10);
    expect(events.subscriberCount).toBe(2);
    let line = first;
    for (let k = 0; k < 120; k++) {
      events.append({ type: 'trace', records: records(line, 1000) });
      line += 1000;
      await sleep(15);
    }
    for (let i = 0; i < 200 && events.subscriberCount > 1; i++) await sleep(10);
    expect(events.subscriberCount).toBe(1);
    events.append({ type: 'end', result: null });
    return line;
  };

  test('one frame per event for all its clients; a stalled client is dropped past the bound, the others get every record in order', async () => {
    const events = new JobEvents();
    const base = await serve(events, 8 * 1024 * 1024);
    // a client that connects and never reads
    const stalled = connect((new URL(base).port as unknown as number), '127.0.0.1');
    stalled.write('GET /api/jobs/j/events HTTP/1.1\r\nHost: x\r\n\r\n');
    stalled.pause();
    stalled.on('error', () => {});
    const got: TraceLine[] = [];
    let traceEvents = 0;
    const reading = streamEvents(base, 'j', (e) => {
      if (e.type !== 'trace') return;
      traceEvents++;
      got.push(...(e as TraceEvent).records);
    });
    for (let i = 0; i < 200 && events.subscriberCount < 2; i++) await sleep(10);
    const e = events.append({ type: 'trace', records: records(2, 3) });
    expect(sseFrame(e)).toBe(sseFrame(e));
    // the columnar wire form: the file once, one run of 3 lines from line 2, the texts joined
    expect(sseFrame(e)).toMatch(/^id: 1\nevent: trace\ndata: \{"seq":1,"t":\d+,"files":\["M_1.csv"\],"runs":\[0,2,3\],"text":"1002,[^"]*\\n1003,[^"]*\\n1004,[^"]*"\}\n\n$/);
    expect(JSON.parse(wsFrame(e))).toEqual({ type: 'trace', seq: 1, t: e.t, files: ['M_1.csv'], runs: [0, 2, 3], text: records(2, 3).map((l) => l.text).join('\n') });
    const line = await floodPastStalled(events, 5);
    await reading;
    expect(traceEvents).toBe(121);
    expect(got.map((l) => l.line)).toEqual(Array.from({ length: line - 2 }, (_, i) => i + 2));
    stalled.destroy();
  }, 30_000);

  test('a replay larger than the bound is not a reason to drop the client', async () => {
    const events = new JobEvents();
    let line = 2;
    for (let k = 0; k < 20; k++) {
      events.append({ type: 'trace', records: records(line, 1000) });
      line += 1000;
    }
    events.append({ type: 'end', result: null });
    const base = await serve(events, 1024 * 1024); // the replay is about 4 MB
    const got: TraceLine[] = [];
    await streamEvents(base, 'j', (e) => {
      if (e.type === 'trace') got.push(...(e as TraceEvent).records);
    });
    expect(got).toHaveLength(20_000);
  });

  test('WebSocket: a stalled client is dropped past the bound, a reading one gets every record', async () => {
    const events = new JobEvents();
    sockets = new JobWebSockets({ get: () => ({ events }) as never, cancel: async () => undefined }, undefined, 8 * 1024 * 1024);
    server = createServer();
    server.on('upgrade', (req, socket, head) => sockets!.upgrade('j', 0, req, socket, head));
    await new Promise<void>((r) => server!.listen(0, '127.0.0.1', r));
    const url = `ws://127.0.0.1:${(server!.address() as AddressInfo).port}/api/jobs/j/ws`;
    const stalled = new WebSocket(url);
    stalled.on('error', () => {});
    await new Promise((r) => stalled.on('open', r));
    stalled.pause();
    const reader = new WebSocket(url);
    const got: TraceLine[] = [];
    const ended = new Promise<void>((resolve) => {
      reader.on('message', (data) => {
        const e = JSON.parse(String(data)) as { type: string };
        if (e.type === 'trace') got.push(...decodeTraceRecords(e));
        if (e.type === 'end') resolve();
      });
    });
    await new Promise((r) => reader.on('open', r));
    const line = await floodPastStalled(events, 2);
    await ended;
    expect(got.map((l) => l.line)).toEqual(Array.from({ length: line - 2 }, (_, i) => i + 2));
    reader.close();
    stalled.terminate();
  }, 30_000);

  test("the server's budget for all its clients: stalled clients each under their own bound are dropped, the one with the most unread first, until the rest fit; a reading client gets every record", async () => {
    const events = new JobEvents();
    const budget = new StreamBudget(12 * 1024 * 1024);
    // each stalled client alone stays under its own 64 MiB bound for the whole 30 MB flood
    const base = await serve(events, 64 * 1024 * 1024, budget);
    const stalled = [stalledClient(base), stalledClient(base), stalledClient(base)];
    const got: TraceLine[] = [];
    const reading = streamEvents(base, 'j', (e) => {
      if (e.type === 'trace') got.push(...(e as TraceEvent).records);
    });
    for (let i = 0; i < 200 && events.subscriberCount < 4; i++) await sleep(10);
    expect(events.subscriberCount).toBe(4);
    let line = 2;
    let most = 0;
    for (let k = 0; k < 120; k++) {
      events.append({ type: 'trace', records: records(line, 1000) });
      line += 1000;
      most = Math.max(most, budget.held);
      await sleep(15);
    }
    for (let i = 0; i < 200 && events.subscriberCount > 1; i++) await sleep(10);
    expect(events.subscriberCount).toBe(1);
    events.append({ type: 'end', result: null });
    await reading;
    expect(got.map((l) => l.line)).toEqual(Array.from({ length: line - 2 }, (_, i) => i + 2));
    // never more than the budget held (as last told) after a write, and nothing once all have left
    expect(most).toBeLessThanOrEqual(12 * 1024 * 1024);
    for (let i = 0; i < 100 && budget.held > 0; i++) await sleep(10);
    expect(budget.held).toBe(0);
    for (const c of stalled) c.destroy();
  }, 30_000);
});
