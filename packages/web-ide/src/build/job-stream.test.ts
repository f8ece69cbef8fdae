import { describe, it, expect } from 'vitest';
import { JobStream, type SocketLike, type StreamEvent } from './job-stream.js';

/** A socket of our own: `frame(x)` delivers x as a text frame. */
class FakeSocket implements SocketLike {
  onmessage: ((m: MessageEvent) => void) | null = null;
  onclose: ((e: CloseEvent) => void) | null = null;
  closed = false;
  constructor(readonly url: string) {}
  close(): void {
    this.closed = true;
  }
  frame(data: unknown): void {
    this.onmessage?.({ data: typeof data === 'string' ? data : JSON.stringify(data) } as MessageEvent);
  }
}

function open(url = '/api/jobs/j/ws?trace=none&batch=1') {
  const sockets: FakeSocket[] = [];
  const got: StreamEvent[] = [];
  let stream!: JobStream;
  const on = {
    event: (e: StreamEvent) => {
      got.push(e);
      if (e.type === 'end') stream.close();
    },
    lost: () => undefined,
  };
  stream = new JobStream(url, on, (u) => {
    const s = new FakeSocket(u);
    sockets.push(s);
    return s;
  });
  return { stream, sockets, got };
}

const line = (seq: number) => ({ type: 'line', seq, t: 0, step: 'run', source: 'MSA', stream: 'stdout', line: `flood ${seq}` });

describe('JobStream', () => {
  it('takes a frame of several events (batch=1) as those events, in order, and one event a frame as before', () => {
    const { sockets, got } = open();
    sockets[0]!.frame(line(1));
    sockets[0]!.frame([line(2), line(3), line(4)]);
    sockets[0]!.frame([]);
    sockets[0]!.frame([line(5)]);
    expect(got.map((e) => e.seq)).toEqual([1, 2, 3, 4, 5]);
  });

  it('resumes after the last event of the last frame when the socket breaks', async () => {
    const { sockets } = open();
    sockets[0]!.frame([line(1), line(2), line(3)]);
    sockets[0]!.onclose?.({} as CloseEvent);
    await new Promise((r) => setTimeout(r, 350));
    expect(sockets[1]!.url).toBe('/api/jobs/j/ws?trace=none&batch=1&after=3');
  });

  it('skips what is no event in a frame (hostile), keeps the others', () => {
    const { sockets, got } = open();
    sockets[0]!.frame([null, 7, 'x', [line(1)], line(2), { type: 'line', seq: 'NaN' }, line(3)]);
    sockets[0]!.frame('not json');
    sockets[0]!.frame([line(4)]);
    expect(got.map((e) => e.seq)).toEqual([2, 'NaN', 3, 4]);
  });

  it('hands nothing after the end: a frame that holds the end and more stops there', () => {
    const { sockets, got } = open();
    sockets[0]!.frame([line(1), { type: 'end', seq: 2, t: 0, result: null }, line(3)]);
    expect(got.map((e) => e.seq)).toEqual([1, 2]);
    expect(sockets[0]!.closed).toBe(true);
  });
});
