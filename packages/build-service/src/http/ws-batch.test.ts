/**
 * GET /api/jobs/:id/ws?batch=1 on the real standalone server with the real `ws` client: the
 * events come several to a frame (a JSON array, in order), at most one frame every BATCH_MS while
 * they stream, a replay in frames of BATCH_BYTES at most; every event exactly once, with its seq,
 * combined with `?trace=` and `?after=`. A module printing 10,000 lines a second was 10,000 frames
 * a second to the IDE's page, each a task of its main thread: the page fell seconds behind the run
 * and stopped answering keys (docs/build-service-api.md "Events"). Without the parameter, one
 * event a frame, as before. The job is a JobEvents of our own, handed out by the service for one
 * id (no sandbox needed).
 */
import WebSocket from 'ws';
import { describe, expect, test } from 'vitest';
import { useServedJob } from '../test-support/served-job.js';
import { upgradeStatus as rawUpgradeStatus } from '../test-support/client.js';
import { BATCH_BYTES, BATCH_MS } from './ws.js';

const ID = 'j-flood';
const job = useServedJob(ID);
const built = job.built;

const line = (n: number) => ({ type: 'line' as const, step: 'run' as const, source: 'MSA', stream: 'stdout' as const, line: `flood ${String(n).padStart(7, '0')}: the quick brown fox jumps over the lazy dog` });
const trace = (n: number) => ({ type: 'trace' as const, records: [{ file: 'M_1.csv', line: n, text: `${n},2026-11-26T12:00:00.000000Z,M,user,,,0,x` }] });

interface Followed {
  /** Each frame's events (`type@seq`), and each frame's size, once the server closed the socket. */
  done: Promise<{ frames: string[][]; bytes: number[] }>;
}

async function follow(query: string): Promise<Followed> {
  const ws = new WebSocket(`${built.url.replace('http', 'ws')}/api/jobs/${ID}/ws${query}`);
  const frames: string[][] = [];
  const bytes: number[] = [];
  ws.on('message', (data) => {
    const text = String(data);
    bytes.push(Buffer.byteLength(text));
    const parsed = JSON.parse(text) as { type: string; seq: number } | { type: string; seq: number }[];
    frames.push((Array.isArray(parsed) ? parsed : [parsed]).map((e) => `${e.type}@${e.seq}`));
  });
  const done = new Promise<{ frames: string[][]; bytes: number[] }>((resolve) => ws.on('close', () => resolve({ frames, bytes })));
  await new Promise((resolve, reject) => {
    ws.on('open', resolve);
    ws.on('error', reject);
  });
  return { done };
}

/** Status and body of a raw upgrade request to the service (101 for an accepted one). */
const upgradeStatus = (path: string) => rawUpgradeStatus(built.url + path);

/** `type@seq` of events `from`..`to`. */
const seqs = (type: string, from: number, to: number) => Array.from({ length: to - from + 1 }, (_, i) => `${type}@${from + i}`);

describe('job WebSocket ?batch=1', () => {
  test('a live flood (10 lines a ms for 1 s) comes whole and in order, in at most one frame per 50 ms; without batch, one frame a line', async () => {
    job.events.append({ type: 'status', status: 'running', step: 'run' });
    const batched = await follow('?trace=none&batch=1');
    const single = await follow('?trace=none');
    const t0 = performance.now();
    let n = 0;
    await new Promise<void>((resolve) => {
      const tick = setInterval(() => {
        const due = Math.min(10_000, Math.floor((performance.now() - t0) * 10));
        for (; n < due; n++) job.events.append(line(n));
        if (n >= 10_000) {
          clearInterval(tick);
          resolve();
        }
      }, 1);
    });
    const seconds = (performance.now() - t0) / 1000;
    job.events.append({ type: 'end', result: null });
    const want = ['status@1', ...seqs('line', 2, 10_001), 'end@10002'];
    const b = await batched.done;
    expect(b.frames.flat()).toEqual(want);
    // one frame per BATCH_MS at most, the first one (status, the replay) and the end's apart
    expect(b.frames.length).toBeLessThanOrEqual(Math.ceil((seconds * 1000) / BATCH_MS) + 3);
    expect(b.frames.length).toBeGreaterThan(2);
    const s = await single.done;
    expect(s.frames.flat()).toEqual(want);
    expect(s.frames.length).toBe(want.length);
  }, 20_000);

  test('events far apart go one a frame, as they come', async () => {
    job.events.append({ type: 'status', status: 'running', step: 'run' });
    const batched = await follow('?batch=1');
    for (let i = 1; i <= 3; i++) {
      await new Promise((r) => setTimeout(r, BATCH_MS * 2));
      job.events.append(line(i));
    }
    await new Promise((r) => setTimeout(r, BATCH_MS * 2));
    job.events.append({ type: 'end', result: null });
    expect((await batched.done).frames).toEqual([['status@1'], ['line@2'], ['line@3'], ['line@4'], ['end@5']]);
  }, 10_000);

  test('a replay of 20,000 events goes in frames of BATCH_BYTES at most, every event once; with ?trace= and ?after=', async () => {
    job.events.append({ type: 'status', status: 'running', step: 'run' });
    for (let i = 0; i < 20_000; i++) job.events.append(i % 4 === 3 ? trace(i) : line(i));
    job.events.append({ type: 'end', result: null });
    const all = await (await follow('?batch=1')).done;
    expect(all.frames.flat()).toEqual([...Array.from({ length: 20_001 }, (_, i) => `${i === 0 ? 'status' : (i - 1) % 4 === 3 ? 'trace' : 'line'}@${i + 1}`), 'end@20002']);
    expect(all.frames.length).toBeLessThan(20_002 / 100);
    for (const b of all.bytes) expect(b).toBeLessThanOrEqual(BATCH_BYTES);
    const none = await (await follow('?trace=none&batch=1&after=15000')).done;
    expect(none.frames.flat()).toEqual(Array.from({ length: 5002 }, (_, k) => 15_001 + k).filter((s) => s === 20_002 || (s - 2) % 4 !== 3).map((s) => `${s === 20_002 ? 'end' : 'line'}@${s}`));
  }, 20_000);

  test('any other value is a 400 saying what is allowed; batch=0 is one event a frame', async () => {
    job.events.append({ type: 'status', status: 'running', step: 'run' });
    for (const q of ['?batch=2', '?batch=', '?batch=true', '?batch=1&batch=0']) {
      const { status, body } = await upgradeStatus(`/api/jobs/${ID}/ws${q}`);
      expect(status, q).toBe(400);
      expect(body, q).toMatch(/batch must be 0 or 1/);
    }
    expect(job.events.subscriberCount).toBe(0);
    const zero = await follow('?batch=0');
    job.events.append(line(1));
    job.events.append(line(2));
    job.events.append({ type: 'end', result: null });
    expect((await zero.done).frames).toEqual([['status@1'], ['line@2'], ['line@3'], ['end@4']]);
  }, 10_000);
});
