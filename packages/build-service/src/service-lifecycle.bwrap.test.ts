/**
 * What a client of the standalone service reads at the edges of a job's and the service's life
 * (docs/build-service-api.md), on real servers and clients: a run shortened to fit its time limit
 * says so in its warnings; an ended job's event stream, resumed at or past its end, is 204 (an
 * EventSource stops instead of reconnecting for ever); the service closing tells its WebSocket
 * clients their job's `end` and closes them normally, and its health says it is closing; a request
 * Node's parser refuses gets a JSON error; a cancel during the first build of the runtime ends the
 * job at once, and closes the service at once.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { connect } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import WebSocket from 'ws';
import { createBuildServer, type BuildServer } from './server.js';
import { infiniteLoop, makeProject, honestProgram } from './test-support/c-projects.js';
import { getJob, postJob, readEvents, streamEvents } from './test-support/client.js';
import { useBuildServer } from './test-support/build-server.js';
import { snapshotRuntime, tutorialFiles } from './test-support/tutorial.js';
import type { JobEvent } from './pipeline/job-events.js';

const served = useBuildServer({ sandbox: 'bwrap', concurrency: 2, log: () => {} });

const dirs: string[] = [];
afterAll(() => {
  for (const d of dirs) rmSync(d, { recursive: true, force: true });
});

/** A server of its own (closed by the test), over a fresh cache folder. */
async function ownServer(options: Parameters<typeof createBuildServer>[0] = {}): Promise<{ server: BuildServer; url: string }> {
  const cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
  dirs.push(cacheDir);
  const server = createBuildServer({ token: false, port: 0, sandbox: 'bwrap', cacheDir, log: () => {}, ...options });
  return { server, url: (await server.listen()).url };
}

/** The answer to `raw` (a request's head) on a socket of its own: status line and body. */
function rawRequest(url: string, raw: string): Promise<{ status: number; headers: string; body: string }> {
  const { hostname, port } = new URL(url);
  return new Promise((resolve, reject) => {
    const socket = connect(Number(port), hostname);
    let buf = '';
    socket.setEncoding('utf8');
    socket.on('data', (c: string) => (buf += c));
    socket.on('error', reject);
    socket.on('close', () => {
      const end = buf.indexOf('\r\n\r\n');
      resolve({ status: Number(/^HTTP\/1\.1 (\d{3})/.exec(buf)?.[1] ?? 0), headers: buf.slice(0, end), body: buf.slice(end + 4) });
    });
    socket.write(raw);
  });
}

const until = async (ok: () => boolean, ms: number): Promise<void> => {
  const t0 = Date.now();
  while (!ok() && Date.now() - t0 < ms) await new Promise((r) => setTimeout(r, 20));
};

describe('a run shortened to fit its run time limit', () => {
  test('says so in its warnings: the 201, the job, the log', async () => {
    const posted = await postJob(served.url, { action: 'run', kind: 'make', project: { files: makeProject(honestProgram(5)) }, duration: 1000, limits: { runSeconds: 2 } });
    expect(posted.status).toBe(201);
    const said = 'duration 1000 s capped to 1 s: the run time limit is 2 s, of which 1 s are kept to start and stop the architecture';
    expect(posted.json.warnings).toEqual([said]);
    await readEvents(served.url, posted.json.id as string);
    const job = await getJob(served.url, posted.json.id as string);
    expect(job.warnings).toEqual([said]);
    // a duration that fits: no warning
    const fits = await postJob(served.url, { action: 'run', kind: 'make', project: { files: makeProject(honestProgram(5)) }, duration: 0.5, limits: { runSeconds: 2 } });
    expect(fits.json.warnings).toEqual([]);
    await readEvents(served.url, fits.json.id as string);
  }, 60_000);
});

describe('the events of an ended job', () => {
  test('resumed at or past the end: 204 No Content (an EventSource stops); before it: the rest', async () => {
    const posted = await postJob(served.url, { action: 'build', kind: 'make', project: { files: makeProject(honestProgram(3)) } });
    const id = posted.json.id as string;
    const events = await readEvents(served.url, id);
    const end = events.at(-1)!;
    expect(end.type).toBe('end');
    const base = `${served.url}/api/jobs/${id}/events`;
    for (const [query, headers] of [[`?after=${end.seq}`, {}], ['?after=99999', {}], ['', { 'Last-Event-ID': String(end.seq) }]] as const) {
      const res = await fetch(`${base}${query}`, { headers });
      expect(res.status, `${query} ${JSON.stringify(headers)}`).toBe(204);
      expect(await res.text()).toBe('');
    }
    const rest: JobEvent[] = [];
    await streamEvents(served.url, id, (e) => rest.push(e), end.seq - 1);
    expect(rest.map((e) => e.seq)).toEqual([end.seq]);
  }, 60_000);
});

describe('a request the HTTP parser refuses', () => {
  test.each(['abc', '-5', '1e3'])('Content-Length: %s is a JSON 400 {error, code: "bad_request"}', async (length) => {
    const { hostname, port } = new URL(served.url);
    const answer = await rawRequest(served.url, `POST /api/jobs HTTP/1.1\r\nHost: ${hostname}:${port}\r\nContent-Type: application/json\r\nContent-Length: ${length}\r\n\r\n{}`);
    expect(answer.status).toBe(400);
    expect(answer.headers).toMatch(/content-type: application\/json/i);
    const json = JSON.parse(answer.body) as { error: string; code: string };
    expect(json.code).toBe('bad_request');
    expect(json.error).toMatch(/^malformed HTTP request: /);
  });
});

describe('the service closing', () => {
  test('its WebSocket clients get their job\'s end and a normal close; its health says closing', async () => {
    const { server, url } = await ownServer();
    const posted = await postJob(url, { action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) }, duration: 20 });
    const id = posted.json.id as string;
    const frames: Record<string, unknown>[] = [];
    const ws = new WebSocket(`${url.replace('http', 'ws')}/api/jobs/${id}/ws?trace=none`);
    const closed = new Promise<number>((resolve) => ws.on('close', (code) => resolve(code)));
    ws.on('message', (d) => frames.push(JSON.parse(String(d)) as Record<string, unknown>));
    // the run is going: its program's line arrived
    await until(() => frames.some((f) => f.type === 'line' && f.line === 'looping'), 30_000);
    expect(frames.some((f) => f.line === 'looping')).toBe(true);
    const closing = server.close();
    const health = await fetch(`${url}/api/health`);
    const healthJson = await health.json();
    const code = await closed;
    await closing;
    expect(frames.at(-1)).toMatchObject({ type: 'end', result: { message: 'cancelled' } });
    expect([1000, 1001]).toContain(code);
    expect(health.status).toBe(503);
    expect(healthJson).toMatchObject({ ok: false, closing: true });
  }, 60_000);

  test('its health is ok, closing false, while it runs', async () => {
    const res = await fetch(`${served.url}/api/health`);
    expect(res.status).toBe(200);
    expect(await res.json()).toMatchObject({ ok: true, closing: false });
  });
});

describe('a cancel during the first build of the runtime', () => {
  test('ends the job within 2 s, and the service closes at once', async () => {
    const runtimeSource = snapshotRuntime();
    dirs.push(runtimeSource);
    // a cold cache: the service builds the runtime for its first Cactal job
    const { server, url } = await ownServer({ runtimeSource });
    try {
      const posted = await postJob(url, { action: 'build', project: { files: await tutorialFiles() } });
      const id = posted.json.id as string;
      let building = false;
      let endedAt = 0;
      const stream = streamEvents(url, id, (e) => {
        if (e.type === 'line' && e.source === 'runtime' && /^building the runtime/.test(e.line)) building = true;
        if (e.type === 'end') endedAt = Date.now();
      });
      await until(() => building, 60_000);
      expect(building).toBe(true);
      // the runtime's make is under way
      await new Promise((r) => setTimeout(r, 300));
      const t0 = Date.now();
      const res = await fetch(`${url}/api/jobs/${id}`, { method: 'DELETE' });
      expect(res.status).toBe(202);
      await stream;
      expect(endedAt - t0).toBeLessThan(2000);
      expect((await getJob(url, id)).status).toBe('cancelled');
    } finally {
      const tc = Date.now();
      await server.close();
      expect(Date.now() - tc).toBeLessThan(3000);
    }
  }, 120_000);
});
