/**
 * What a client sends on a job's WebSocket (ws-client-frames.ts), on the real standalone server
 * with the real `ws` client: {"type":"cancel"} cancels the job; any other frame (not JSON, not an
 * object, an unknown or missing type, a binary frame) is answered with one error frame and the
 * stream goes on. Such frames were ignored without a word: a client that misspelt its cancel
 * never learnt that its job ran on.
 */
import WebSocket from 'ws';
import { describe, expect, test, vi } from 'vitest';
import { useServedJob } from '../test-support/served-job.js';
import { BAD_FRAME_CODE } from './ws-client-frames.js';

const ID = 'j-frames';
const job = useServedJob(ID);

interface Frame {
  type: string;
  seq?: number;
  code?: string;
  error?: string;
}

async function open(query = ''): Promise<{ ws: WebSocket; frames: Frame[]; next: (n: number) => Promise<Frame[]> }> {
  const ws = new WebSocket(`${job.built.url.replace('http', 'ws')}/api/jobs/${ID}/ws${query}`);
  const frames: Frame[] = [];
  const waiting: { n: number; resolve: (f: Frame[]) => void }[] = [];
  ws.on('message', (data) => {
    const parsed = JSON.parse(String(data)) as Frame | Frame[];
    frames.push(...(Array.isArray(parsed) ? parsed : [parsed]));
    for (const w of waiting.splice(0)) if (frames.length >= w.n) w.resolve(frames.slice());
    else waiting.push(w);
  });
  await new Promise((resolve, reject) => {
    ws.on('open', resolve);
    ws.on('error', reject);
  });
  const next = (n: number) => (frames.length >= n ? Promise.resolve(frames.slice()) : new Promise<Frame[]>((resolve) => waiting.push({ n, resolve })));
  return { ws, frames, next };
}

describe('frames a client sends on the job WebSocket', () => {
  test('every frame but {"type":"cancel"} is answered with an error frame naming it; the stream stays open and goes on', async () => {
    const cancel = vi.spyOn(job.built.server.service, 'cancel').mockResolvedValue(undefined);
    job.events.append({ type: 'status', status: 'running', step: 'run' });
    const { ws, next } = await open();
    await next(1); // the replay: the status
    const sent: [string | Buffer, RegExp][] = [
      ['not json', /^frame "not json" is not JSON \(/],
      ['[1,2]', /^frame "\[1,2\]" is not a JSON object: /],
      ['"cancel"', /^frame "\\"cancel\\"" is not a JSON object: /],
      ['{"type":"cancle"}', /^frame has the unknown type "cancle": /],
      ['{"action":"cancel"}', /^frame has no "type": /],
      [Buffer.from('{"type":"cancel"}'), /^binary frame refused: /],
    ];
    for (const [data] of sent) ws.send(data, { binary: Buffer.isBuffer(data) });
    const frames = (await next(1 + sent.length)).slice(1);
    expect(frames).toHaveLength(sent.length);
    frames.forEach((f, i) => {
      expect(f.type).toBe('error');
      expect(f.code).toBe(BAD_FRAME_CODE);
      expect(f.seq).toBeUndefined(); // not a job event
      expect(f.error).toMatch(sent[i]![1]);
      expect(f.error).toContain('the only frame a client may send is the text frame {"type":"cancel"}');
    });
    // none of them cancelled the job
    expect(cancel).not.toHaveBeenCalled();
    expect(ws.readyState).toBe(WebSocket.OPEN);
    // the stream goes on: a live event still comes
    job.events.append({ type: 'line', step: 'run', source: 'MSA', stream: 'stdout', line: 'still here' });
    const after = await next(2 + sent.length);
    expect(after.at(-1)).toMatchObject({ type: 'line', seq: 2, line: 'still here' });
    // and the one frame the service takes cancels the job, with no error frame
    ws.send('{"type":"cancel","why":"extra fields are ignored"}');
    await vi.waitFor(() => expect(cancel).toHaveBeenCalledWith(ID));
    job.events.append({ type: 'end', result: null });
    await new Promise((r) => ws.once('close', r));
    expect(after.filter((f) => f.type === 'error')).toHaveLength(sent.length);
  }, 15_000);

  test('a batching socket (?batch=1) gets the error frame on its own, not in an array of events', async () => {
    job.events.append({ type: 'status', status: 'running', step: 'run' });
    const ws = new WebSocket(`${job.built.url.replace('http', 'ws')}/api/jobs/${ID}/ws?batch=1`);
    const raw: string[] = [];
    ws.on('message', (d) => raw.push(String(d)));
    await new Promise((resolve, reject) => {
      ws.on('open', resolve);
      ws.on('error', reject);
    });
    await vi.waitFor(() => expect(raw).toHaveLength(1));
    ws.send('{"type":"stop"}');
    await vi.waitFor(() => expect(raw).toHaveLength(2));
    expect(JSON.parse(raw[1]!)).toEqual({ type: 'error', code: BAD_FRAME_CODE, error: 'frame has the unknown type "stop": the only frame a client may send is the text frame {"type":"cancel"}' });
    ws.close();
    await new Promise((r) => ws.once('close', r));
  }, 15_000);
});
