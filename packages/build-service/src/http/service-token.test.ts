/**
 * The standalone service's token and its refusal of unsandboxed jobs (docs/build-service-api.md,
 * "Token"): every route family and the job WebSocket answer 401 without the X-Contract-Token
 * header or with a wrong one, and serve with the right one; `sandbox: "none"` jobs get 403 unless
 * the server was started with allowNoneSandbox; a mounted service (`handle()`, as the IDE does)
 * is left to its host's guard. Real servers, real jobs (`kind: "make"`, the Makefile only echoes).
 */
import { createServer, request, type Server } from 'node:http';
import { chownSync, closeSync, openSync, readFileSync, readSync, statSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import type { AddressInfo } from 'node:net';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { createBuildServer } from '../server.js';
import { useScratch } from '../test-support/scratch.js';

const MAKE = { Makefile: 'all:\n\t@echo built\nrun:\n\t@echo ran\n.PHONY: all run\n' };
const { temp, serve } = useScratch();

async function start(options: Parameters<typeof createBuildServer>[0] = {}) {
  const server = createBuildServer({ port: 0, cacheDir: temp('contract-token-cache-'), concurrency: 2, log: () => {}, ...options });
  serve(server);
  return server.listen();
}

/** Status and JSON body of a raw request (101 for an accepted WebSocket upgrade). */
function call(url: string, path: string, headers: Record<string, string>, method = 'GET', body = ''): Promise<{ status: number; json: any }> {
  return new Promise((resolve, reject) => {
    const r = request(url + path, { method, headers: { ...headers, ...(body ? { 'content-type': 'application/json' } : {}) }, agent: false }, (res) => {
      let text = '';
      res.on('data', (c) => (text += c));
      res.on('end', () => {
        let json: unknown = null;
        try {
          json = JSON.parse(text);
        } catch {
          json = text;
        }
        resolve({ status: res.statusCode ?? 0, json });
      });
      // an SSE stream does not end by itself: its status is enough
      if (String(res.headers['content-type'] ?? '').startsWith('text/event-stream')) {
        res.destroy();
        resolve({ status: res.statusCode ?? 0, json: null });
      }
    });
    r.on('upgrade', (res, socket) => {
      socket.destroy();
      resolve({ status: res.statusCode ?? 101, json: null });
    });
    r.on('error', reject);
    r.end(body);
  });
}

const WS = { Connection: 'Upgrade', Upgrade: 'websocket', 'Sec-WebSocket-Version': '13', 'Sec-WebSocket-Key': 'dGhlIHNhbXBsZSBub25jZQ==' };

describe('the standalone service requires its token', () => {
  let url = '';
  let token = '';
  let jobId = '';
  beforeAll(async () => {
    const started = await start({ allowNoneSandbox: true });
    url = started.url;
    token = started.token!;
    expect(token).toMatch(/^[A-Za-z0-9_-]{40,}$/);
    const r = await call(url, '/api/jobs', { 'X-Contract-Token': token }, 'POST', JSON.stringify({ action: 'build', kind: 'make', sandbox: 'none', project: { files: MAKE } }));
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    jobId = r.json.id;
  });

  const routes = (): [string, string, string, Record<string, string>?, string?][] => [
    ['health', 'GET', '/api/health'],
    ['sandboxes', 'GET', '/api/sandboxes'],
    ['submit', 'POST', '/api/jobs', {}, JSON.stringify({ action: 'build', kind: 'make', sandbox: 'none', project: { files: MAKE } })],
    ['list', 'GET', '/api/jobs'],
    ['job', 'GET', `/api/jobs/${jobId}`],
    ['events', 'GET', `/api/jobs/${jobId}/events`],
    ['log', 'GET', `/api/jobs/${jobId}/log`],
    ['artifacts', 'GET', `/api/jobs/${jobId}/artifacts`],
    ['artifact', 'GET', `/api/jobs/${jobId}/artifacts/x.csv`],
    ['cancel', 'DELETE', `/api/jobs/${jobId}`],
    ['websocket', 'GET', `/api/jobs/${jobId}/ws`, WS],
    ['other path', 'GET', '/'],
  ];

  for (const [variant, headers] of [['no token', {}], ['a wrong token', { 'X-Contract-Token': 'x'.repeat(43) }], ['an empty token', { 'X-Contract-Token': '' }]] as const) {
    test(`every route family and the WebSocket answer 401 with ${variant}`, async () => {
      for (const [name, method, path, extra, body] of routes()) {
        const r = await call(url, path, { ...headers, ...(extra ?? {}) }, method, body);
        expect(r.status, name).toBe(401);
        if (name !== 'websocket') expect(r.json.code, name).toBe('unauthorized');
      }
    });
  }

  test('an artifact name that is no file name is 400, an unknown one 404', async () => {
    for (const bad of ['a%2Fb.csv', 'a%0Ab.csv', 'a%00.csv', 'x'.repeat(300)]) {
      const r = await call(url, `/api/jobs/${jobId}/artifacts/${bad}`, { 'X-Contract-Token': token });
      expect(r.status, bad).toBe(400);
      expect(r.json.code, bad).toBe('bad_request');
    }
    expect((await call(url, `/api/jobs/${jobId}/artifacts/x.csv`, { 'X-Contract-Token': token })).status).toBe(404);
  });

  test('the 401 says what is missing', async () => {
    expect((await call(url, '/api/health', {})).json.error).toBe(
      'missing X-Contract-Token header: this build service requires the token given when it was started (docs/build-service-api.md, "Token")');
    expect((await call(url, '/api/health', { 'X-Contract-Token': 'nope' })).json.error).toMatch(/^wrong X-Contract-Token header/);
  });

  test('with the token every route family and the WebSocket serve', async () => {
    const expected: Record<string, number> = { submit: 201, artifact: 404, cancel: 200, websocket: 101, 'other path': 404 };
    for (const [name, method, path, extra, body] of routes()) {
      const r = await call(url, path, { 'X-Contract-Token': token, ...(extra ?? {}) }, method, body);
      expect(r.status, name).toBe(name === 'cancel' ? r.status : expected[name] ?? 200);
      expect([200, 202, 201, 101, 404], name).toContain(r.status);
    }
  });

  test('a token given at start is the one required, and written to a 0600 token file', async () => {
    const file = join(temp('contract-token-file-'), 'build-service.token');
    const given = 'a-token-of-the-caller-0123456789';
    const started = await start({ token: given, tokenFile: file });
    expect(started.token).toBe(given);
    expect(readFileSync(file, 'utf8')).toBe(`${given}\n`);
    expect(statSync(file).mode & 0o777).toBe(0o600);
    expect((await call(started.url, '/api/health', {})).status).toBe(401);
    expect((await call(started.url, '/api/health', { 'X-Contract-Token': given })).status).toBe(200);
  });

  test('a token file someone else made (and holds open) beforehand is replaced, never written into', async () => {
    const file = join(temp('contract-token-planted-'), 'build-service.token');
    writeFileSync(file, 'planted\n', { mode: 0o666 });
    if (process.getuid?.() === 0) chownSync(file, 65534, 65534); // another user's file
    const held = openSync(file, 'r'); // the other user keeps it open to read what gets written
    try {
      const started = await start({ tokenFile: file });
      expect(readFileSync(file, 'utf8')).toBe(`${started.token}\n`);
      const st = statSync(file);
      expect(st.mode & 0o777).toBe(0o600);
      expect(st.uid).toBe(process.getuid?.());
      const seen = Buffer.alloc(256);
      const n = readSync(held, seen, 0, seen.length, 0);
      expect(seen.subarray(0, n).toString()).toBe('planted\n');
    } finally {
      closeSync(held);
    }
  });

  test('two starts get two different tokens', async () => {
    const a = await start();
    const b = await start();
    expect(a.token).not.toBe(b.token);
    expect((await call(b.url, '/api/health', { 'X-Contract-Token': a.token! })).status).toBe(401);
  });
});

describe('sandbox "none" over HTTP', () => {
  const noneJob = JSON.stringify({ action: 'build', kind: 'make', sandbox: 'none', project: { files: MAKE } });

  test('is refused with 403 unless the server allows it', async () => {
    const { url, token } = await start();
    const r = await call(url, '/api/jobs', { 'X-Contract-Token': token! }, 'POST', noneJob);
    expect(r.status).toBe(403);
    expect(r.json).toEqual({
      code: 'forbidden',
      error: 'sandbox "none" jobs (no isolation: they run as the service\'s user) are refused: this service was not started with allowNoneSandbox: true; use "bwrap", "docker" or "auto"',
    });
  });

  test('is refused when it is the service default and the job names no sandbox', async () => {
    const { url, token } = await start({ sandbox: 'none' });
    const r = await call(url, '/api/jobs', { 'X-Contract-Token': token! }, 'POST', JSON.stringify({ action: 'build', kind: 'make', project: { files: MAKE } }));
    expect(r.status).toBe(403);
  });

  test('a sandboxed job is accepted by the same server', async () => {
    const { url, token } = await start();
    const r = await call(url, '/api/jobs', { 'X-Contract-Token': token! }, 'POST', JSON.stringify({ action: 'build', kind: 'make', sandbox: 'bwrap', project: { files: MAKE } }));
    expect(r.status, JSON.stringify(r.json)).toBe(201);
  });
});

describe('a mounted service', () => {
  let host: Server;
  afterAll(() => new Promise<void>((resolve) => host.close(() => resolve())));

  test('is left to its host: handle() needs no token and keeps sandbox "none"', async () => {
    const service = createBuildServer({ cacheDir: temp('contract-token-mounted-'), concurrency: 1, log: () => {} });
    serve(service);
    host = createServer((req, res) => void service.handle(req, res));
    await new Promise<void>((resolve) => host.listen(0, '127.0.0.1', () => resolve()));
    const url = `http://127.0.0.1:${(host.address() as AddressInfo).port}`;
    expect((await call(url, '/api/health', {})).status).toBe(200);
    const r = await call(url, '/api/jobs', {}, 'POST', JSON.stringify({ action: 'build', kind: 'make', sandbox: 'none', project: { files: MAKE } }));
    expect(r.status, JSON.stringify(r.json)).toBe(201);
  });

  test('started with onlySandbox (contract serve --sandbox bwrap): a job naming another sandbox is 403, mounted or standalone; one naming it or none is accepted', async () => {
    const service = createBuildServer({ cacheDir: temp('contract-token-only-'), concurrency: 1, log: () => {}, sandbox: 'bwrap', onlySandbox: 'bwrap' });
    serve(service);
    const only = createServer((req, res) => void service.handle(req, res));
    await new Promise<void>((resolve) => only.listen(0, '127.0.0.1', () => resolve()));
    try {
      const url = `http://127.0.0.1:${(only.address() as AddressInfo).port}`;
      const job = (sandbox?: string) => JSON.stringify({ action: 'build', kind: 'make', ...(sandbox ? { sandbox } : {}), project: { files: MAKE } });
      for (const named of ['none', 'auto', 'docker']) {
        const r = await call(url, '/api/jobs', {}, 'POST', job(named));
        expect(r.status, named).toBe(403);
        expect(r.json).toEqual({ code: 'forbidden', error: `sandbox "${named}" refused: this server runs every job in bwrap (it was started so, e.g. \`contract serve --sandbox bwrap\`); name bwrap or no sandbox` });
      }
      for (const named of ['bwrap', undefined]) {
        const r = await call(url, '/api/jobs', {}, 'POST', job(named));
        expect(r.status, JSON.stringify(r.json)).toBe(201);
        expect(r.json.sandbox).toBe('bwrap');
      }
      // standalone, with none allowed: still refused
      const { url: standalone, token } = await start({ sandbox: 'bwrap', onlySandbox: 'bwrap', allowNoneSandbox: true });
      expect((await call(standalone, '/api/jobs', { 'X-Contract-Token': token! }, 'POST', job('none'))).status).toBe(403);
    } finally {
      await new Promise<void>((resolve) => only.close(() => resolve()));
    }
  });
});
