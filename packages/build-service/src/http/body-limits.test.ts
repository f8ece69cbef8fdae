/**
 * POST /api/jobs bodies (docs/build-service-api.md): every refusal that needs no body (content
 * type, declared length, a full queue, too many bodies being read) is answered before a byte of
 * the body is read; bodies are streamed under a running cap and a time bound; with many large
 * bodies at once the service's memory stays bounded (a child service's peak RSS, VmHWM).
 */
import type { ChildProcess } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createServer, request, type Server } from 'node:http';
import { connect, type AddressInfo, type Socket } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { createBuildServer, type BuildServer } from '../server.js';
import { ServiceError } from '../service-errors.js';
import { infiniteLoop, makeProject } from '../test-support/c-projects.js';
import { startChildService } from '../test-support/child-process-service.js';
import { postJob, readEvents } from '../test-support/client.js';
import { BodyReader } from './body-reader.js';

const tempDirs: string[] = [];
let server: BuildServer;
let url: string;

beforeAll(async () => {
  const cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
  tempDirs.push(cacheDir);
  server = createBuildServer({ token: false, port: 0, concurrency: 1, queueSize: 0, cacheDir, sandbox: 'bwrap', log: () => {} });
  url = (await server.listen()).url;
});

afterAll(async () => {
  await server?.close();
  for (const d of tempDirs) rmSync(d, { recursive: true, force: true });
});

interface RawAnswer {
  status: number;
  headers: string;
  json: { error?: string; code?: string };
}

/**
 * Sends the head of a POST (and `body`, possibly shorter than the declared length) on a raw
 * socket, and resolves with the answer: the test sees what the service says without the rest.
 */
function rawPost(base: string, headers: Record<string, string>, body = ''): { answer: Promise<RawAnswer>; socket: Socket } {
  const { hostname, port } = new URL(base);
  const socket = connect(Number(port), hostname);
  const head = [`POST /api/jobs HTTP/1.1`, `Host: ${hostname}:${port}`, ...Object.entries(headers).map(([k, v]) => `${k}: ${v}`), '', ''].join('\r\n');
  socket.write(head + body);
  const answer = new Promise<RawAnswer>((resolve, reject) => {
    let buf = '';
    socket.setEncoding('utf8');
    socket.on('data', (c: string) => {
      buf += c;
      const end = buf.indexOf('\r\n\r\n');
      if (end < 0) return;
      const headText = buf.slice(0, end);
      const length = Number(/content-length: (\d+)/i.exec(headText)?.[1] ?? NaN);
      const rest = buf.slice(end + 4);
      if (Buffer.byteLength(rest) < length) return;
      let json: RawAnswer['json'];
      try {
        json = JSON.parse(rest) as RawAnswer['json'];
      } catch {
        json = { code: rest }; // the plain-text answers of the small server below
      }
      resolve({ status: Number(headText.split(' ')[1]), headers: headText, json });
    });
    socket.on('error', reject);
    socket.on('close', () => reject(new Error(`closed before an answer: ${buf.slice(0, 200)}`)));
  });
  return { answer, socket };
}

const JSON_HEADERS = { 'Content-Type': 'application/json' };

describe('refused from the headers, before the body is read', () => {
  test('Content-Length above the cap: 413 at once, the connection closed', async () => {
    const { answer, socket } = rawPost(url, { ...JSON_HEADERS, 'Content-Length': String(2 ** 40) });
    const a = await answer; // no byte of the body was sent: an answer now means none was awaited
    socket.destroy();
    expect(a.status).toBe(413);
    expect(a.json.code).toBe('too_large');
    expect(a.json.error).toMatch(`above the ${SERVICE_BOUNDS.requestBodyBytes}-byte limit`);
    expect(a.headers).toMatch(/^connection: close$/im);
  });

  test('not JSON: 415', async () => {
    const { answer, socket } = rawPost(url, { 'Content-Type': 'text/plain', 'Content-Length': '1000' });
    const a = await answer;
    socket.destroy();
    expect(a.status).toBe(415);
    expect(a.json.code).toBe('unsupported_media_type');
  });

  test(`more than ${SERVICE_BOUNDS.requestBodiesAtOnce} bodies being read: 503 busy; the slots come back`, async () => {
    const slow = Array.from({ length: SERVICE_BOUNDS.requestBodiesAtOnce }, () => rawPost(url, { ...JSON_HEADERS, 'Content-Length': '1000' }, '{"kind":'));
    for (const s of slow) s.answer.catch(() => {});
    await new Promise((r) => setTimeout(r, 300)); // their heads are in: they hold the slots
    const third = rawPost(url, { ...JSON_HEADERS, 'Content-Length': '1000' });
    const a = await third.answer;
    third.socket.destroy();
    expect(a.status).toBe(503);
    expect(a.json.code).toBe('busy');
    expect(a.headers).toMatch(/^retry-after: 2$/im);
    for (const s of slow) s.socket.destroy();
    await new Promise((r) => setTimeout(r, 300));
    const after = await postJob(url, { action: 'nope', project: { files: {} } });
    expect(after.status).toBe(400); // read and answered: the slots were given back
  });

  test('queue full: 429 before the body is read', async () => {
    const loop = await postJob(url, { action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) } });
    expect(loop.status).toBe(201);
    try {
      const { answer, socket } = rawPost(url, { ...JSON_HEADERS, 'Content-Length': '5000000' });
      const a = await answer;
      socket.destroy();
      expect(a.status).toBe(429);
      expect(a.json.code).toBe('queue_full');
    } finally {
      await fetch(`${url}/api/jobs/${loop.json.id}`, { method: 'DELETE' });
      await readEvents(url, loop.json.id as string);
    }
  });
});

describe('BodyReader: running cap and time bound on a real HTTP server', () => {
  let small: Server;
  let smallUrl: string;
  const reader = new BodyReader(1024, 1, 1);

  beforeAll(async () => {
    small = createServer((req, res) => {
      let admitted;
      try {
        admitted = reader.admit(req);
      } catch (e) {
        res.writeHead((e as ServiceError).status, { Connection: 'close' }).end((e as ServiceError).code);
        return;
      }
      admitted.read().then(
        (v) => res.writeHead(200).end(JSON.stringify(v)),
        (e: ServiceError) => res.writeHead(e.status ?? 500, { Connection: 'close' }).end(e.code),
      );
    });
    await new Promise<void>((r) => small.listen(0, '127.0.0.1', r));
    smallUrl = `http://127.0.0.1:${(small.address() as AddressInfo).port}`;
  });

  afterAll(() => new Promise<void>((r) => small.close(() => r())));

  function chunked(chunks: string[]): Promise<{ status: number; text: string }> {
    return new Promise((resolve, reject) => {
      const req = request(`${smallUrl}/`, { method: 'POST', headers: { 'Content-Type': 'application/json', 'Transfer-Encoding': 'chunked' } }, (res) => {
        let text = '';
        res.on('data', (c) => (text += c));
        res.on('end', () => resolve({ status: res.statusCode!, text }));
      });
      req.on('error', reject);
      for (const c of chunks) req.write(c);
      req.end();
    });
  }

  test('a chunked body is read under the running cap: within it, parsed; above it, 413', async () => {
    expect(await chunked(['{"a":', '[1,2]}'])).toEqual({ status: 200, text: '{"a":[1,2]}' });
    const over = await chunked(['"', 'x'.repeat(600), 'x'.repeat(600), '"']).catch((e: Error) => ({ status: 0, text: e.message }));
    expect(over).toEqual({ status: 413, text: 'too_large' });
    expect(reader.active).toBe(0);
  });

  test('a body that does not arrive in time: 408, and its slot is free again', async () => {
    const { answer, socket } = rawPost(smallUrl, { ...JSON_HEADERS, 'Content-Length': '100' }, '{"a"');
    const a = await answer.catch(() => null);
    socket.destroy();
    expect(a?.status).toBe(408);
    expect(a?.json.code).toMatch(/timeout/);
    expect(reader.active).toBe(0);
  }, 10_000);
});

/** Peak resident memory of a process, bytes (VmHWM). */
function peakRss(pid: number): number {
  const kb = /^VmHWM:\s+(\d+) kB$/m.exec(readFileSync(`/proc/${pid}/status`, 'utf8'))?.[1];
  return Number(kb) * 1024;
}

describe('many large bodies at once (12 concurrent POSTs of 75 MB)', () => {
  let child: ChildProcess | null = null;
  afterAll(() => {
    child?.kill('SIGKILL');
  });

  test('the service peak RSS stays bounded; it answers every client and stays up', async () => {
    const cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
    tempDirs.push(cacheDir);
    const started = await startChildService(cacheDir);
    child = started.child;
    const base = started.url;
    const idle = peakRss(child.pid!);
    // 75 MB of valid JSON each, refused by validation only once read and parsed (no job runs)
    const body = Buffer.from(JSON.stringify({ action: 'nope', project: { files: { 'a.c': 'x'.repeat(75_000_000) } } }));
    const post = (): Promise<number> =>
      new Promise((resolve) => {
        const req = request(`${base}/api/jobs`, { method: 'POST', headers: { 'Content-Type': 'application/json', 'Content-Length': body.length } }, (res) => {
          res.resume();
          res.on('end', () => resolve(res.statusCode!));
        });
        req.on('error', () => resolve(0)); // refused early: the service closed while we still sent
        req.end(body);
      });
    const statuses = await Promise.all(Array.from({ length: 12 }, post));
    const peak = peakRss(child.pid!);
    // read and refused by validation (400), or refused before reading (503 busy, or the reset of that answer)
    expect(statuses.every((s) => [400, 503, 0].includes(s)), statuses.join(',')).toBe(true);
    expect(statuses.filter((s) => s === 400).length).toBeGreaterThanOrEqual(1);
    const health = await fetch(`${base}/api/health`);
    expect(health.status).toBe(200);
    // per body being read: its bytes, the decoded text and the parsed value (~3 x 75 MB)
    const bound = idle + SERVICE_BOUNDS.requestBodiesAtOnce * 4 * body.length;
    process.stderr.write(`body-limits: service RSS idle ${(idle / 2 ** 20).toFixed(0)} MiB, peak ${(peak / 2 ** 20).toFixed(0)} MiB (bound ${(bound / 2 ** 20).toFixed(0)} MiB); answers ${statuses.join(',')}\n`);
    expect(peak).toBeLessThan(bound);
  }, 180_000);
});
