/**
 * Who may drive the IDE server: only a client holding the session token (header or the cookie the
 * printed URL sets), from the server's own origin. Every /api route family and the job WebSocket
 * are tried without a token, with a wrong one, and with foreign Origin / Host variants. Real
 * server with the build service mounted; the job is a real `kind: "make"` job (sandbox none).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { request } from 'node:http';
import { mkdtempSync, mkdirSync, writeFileSync, existsSync, rmSync, realpathSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import WebSocket from 'ws';
import { startIdeServer, type IdeServer } from './ide-server.js';

let base: string;
let ws: string;
let ide: IdeServer;
let port: number;

beforeAll(async () => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-session-')));
  ws = join(base, 'ws');
  mkdirSync(ws);
  writeFileSync(join(ws, 'a.contract'), 'datatype T {int x};');
  ide = await startIdeServer({ workspace: ws, port: 0, buildService: true, distDir: join(base, 'no-dist') });
  port = Number(new URL(ide.url).port);
}, 60_000);
afterAll(async () => {
  await ide.close();
  rmSync(base, { recursive: true, force: true });
});

interface Answer {
  status: number;
  headers: Record<string, string | string[] | undefined>;
}

/** A raw request (no agent: each gets its own connection); 101 for an accepted upgrade. */
function raw(method: string, path: string, headers: Record<string, string> = {}, body = ''): Promise<Answer> {
  return new Promise((resolve, reject) => {
    const r = request(ide.url + path, { method, headers, agent: false }, (res) => {
      res.resume();
      resolve({ status: res.statusCode ?? 0, headers: res.headers });
    });
    r.on('upgrade', (res, socket) => {
      socket.destroy();
      resolve({ status: res.statusCode ?? 0, headers: res.headers });
    });
    r.on('error', reject);
    r.end(body);
  });
}

const JSON_TYPE = { 'content-type': 'application/json' };
const UPGRADE = { connection: 'Upgrade', upgrade: 'websocket', 'sec-websocket-version': '13', 'sec-websocket-key': 'dGhlIHNhbXBsZSBub25jZQ==' };
const NO_JOB = 'j-00000000000000000000000000000000';
const SLOW_RUN = { Makefile: 'all:\n\t@echo built\nrun:\n\t@echo running; sleep 60\n.PHONY: all run\n' };

/** One request of every /api route family (the build service's included). */
const ROUTES: [string, string, string?][] = [
  ['GET', '/api/tree'],
  ['GET', '/api/file?path=a.contract'],
  ['PUT', '/api/file?path=pwned.contract', 'x'],
  ['POST', '/api/create', JSON.stringify({ path: 'pwned2.contract', type: 'file' })],
  ['POST', '/api/rename', JSON.stringify({ from: 'a.contract', to: 'moved.contract' })],
  ['DELETE', '/api/file?path=a.contract'],
  ['GET', '/api/events'],
  ['GET', '/api/snapshot'],
  ['GET', '/api/info'],
  ['POST', '/api/generate', '{"project":""}'],
  ['POST', '/api/new-project', '{"folder":"pwned-project"}'],
  ['POST', '/api/rename-entity', '{"project":"","from":"T","to":"U"}'],
  ['GET', '/api/health'],
  ['GET', '/api/sandboxes'],
  ['POST', '/api/jobs', JSON.stringify({ action: 'run', kind: 'make', sandbox: 'none', project: { files: SLOW_RUN } })],
  ['GET', '/api/jobs'],
  ['GET', `/api/jobs/${NO_JOB}`],
  ['DELETE', `/api/jobs/${NO_JOB}`],
];

function untouched(): void {
  expect(existsSync(join(ws, 'pwned.contract'))).toBe(false);
  expect(existsSync(join(ws, 'pwned2.contract'))).toBe(false);
  expect(existsSync(join(ws, 'pwned-project'))).toBe(false);
  expect(existsSync(join(ws, 'a.contract'))).toBe(true);
}

describe('session token', () => {
  it('is random per server and printed in the URL to open', () => {
    expect(ide.token).toMatch(/^[A-Za-z0-9_-]{43}$/);
    expect(ide.openUrl).toBe(`${ide.url}/?token=${ide.token}`);
  });

  it('every /api route family answers 401 without the token or with a wrong one, and changes nothing', async () => {
    for (const [method, path, body] of ROUTES) {
      const refused: Array<Record<string, string>> = [{}, { 'x-contract-token': 'wrong-token-wrong-token' }, { cookie: `contract_session_${port}=wrong-token-wrong-token` }, { cookie: `contract_session_1=${ide.token}` }];
      for (const headers of refused) {
        const { status } = await raw(method, path, { ...(body ? JSON_TYPE : {}), ...headers }, body);
        expect(status, `${method} ${path} ${JSON.stringify(headers)}`).toBe(401);
      }
    }
    untouched();
  }, 60_000);

  it("an /api 401 says why in the same shape as the build service's: { error, code: 'unauthorized' }", async () => {
    for (const path of ['/api/snapshot', '/api/file?path=ok.contract']) {
      const res = await fetch(`${ide.url}${path}`);
      expect(res.status, path).toBe(401);
      expect(await res.json(), path).toEqual({ code: 'unauthorized', error: expect.stringMatching(/needs its session token/) });
    }
  });

  it('the same requests pass with the token, in the header or in the cookie', async () => {
    for (const [method, path] of ROUTES.filter(([m, p]) => m === 'GET' && p !== '/api/events')) {
      expect((await raw(method, path, { 'x-contract-token': ide.token })).status, path).not.toBe(401);
      expect((await raw(method, path, { cookie: `other=1; contract_session_${port}=${ide.token}` })).status, path).not.toBe(401);
    }
    const put = await raw('PUT', '/api/file?path=ok.contract', { 'x-contract-token': ide.token }, 'datatype U {int y};');
    expect(put.status).toBe(200);
  });

  it('the page: 401 without the token; ?token= sets an HttpOnly SameSite=Strict cookie and drops it from the address', async () => {
    expect((await raw('GET', '/')).status).toBe(401);
    expect((await raw('GET', '/?token=wrong-token-wrong-token')).status).toBe(401);
    const open = await raw('GET', `/?token=${ide.token}`);
    expect(open.status).toBe(303);
    expect(open.headers.location).toBe('/');
    const cookie = String(open.headers['set-cookie']);
    expect(cookie).toContain(`contract_session_${port}=${ide.token}`);
    expect(cookie).toContain('HttpOnly');
    expect(cookie).toContain('SameSite=Strict');
    // with the cookie the page is served (here: the "not built" answer, as no dist/ exists)
    expect((await raw('GET', '/', { cookie: `contract_session_${port}=${ide.token}` })).status).toBe(500);
  });
});

describe('job WebSocket through the IDE server', () => {
  const path = `/api/jobs/${NO_JOB}/ws`;
  const withToken = { ...UPGRADE, 'x-contract-token': '' };

  it('refuses upgrades without the token, with a wrong one, and with foreign Origin / Host', async () => {
    withToken['x-contract-token'] = ide.token;
    expect((await raw('GET', path, UPGRADE)).status).toBe(401);
    expect((await raw('GET', path, { ...UPGRADE, 'x-contract-token': 'wrong-token-wrong-token' })).status).toBe(401);
    expect((await raw('GET', path, { ...withToken, origin: 'http://evil.example' })).status).toBe(403);
    expect((await raw('GET', path, { ...withToken, origin: 'null' })).status).toBe(403);
    expect((await raw('GET', path, { ...withToken, host: 'evil.example' })).status).toBe(403);
    expect((await raw('GET', path, { ...withToken, host: `evil.example:${port}`, origin: `http://evil.example:${port}` })).status).toBe(403);
    // past the checks: the build service answers 404 for an unknown job
    expect((await raw('GET', path, withToken)).status).toBe(404);
    expect((await raw('GET', path, { ...UPGRADE, cookie: `contract_session_${port}=${ide.token}`, origin: ide.url })).status).toBe(404);
  });

  it('the workspace events socket (/api/events) has the same checks, and says hello to a page of this server', async () => {
    const path = '/api/events';
    expect((await raw('GET', path, UPGRADE)).status).toBe(401);
    expect((await raw('GET', path, { ...withToken, origin: 'http://evil.example' })).status).toBe(403);
    expect((await raw('GET', path, { ...withToken, host: 'evil.example' })).status).toBe(403);
    const first = await new Promise<unknown>((resolve, reject) => {
      const sock = new WebSocket(`${ide.url.replace('http', 'ws')}${path}`, { headers: { cookie: `contract_session_${port}=${ide.token}`, origin: ide.url } });
      sock.on('message', (d) => {
        resolve(JSON.parse(String(d)));
        sock.close();
      });
      sock.on('error', reject);
    });
    expect(first).toEqual({ event: 'hello', data: {} });
  });

  it('a page of another site cannot read nor cancel a running job, even holding the cookie', async () => {
    const post = await fetch(`${ide.url}/api/jobs`, {
      method: 'POST',
      headers: { ...JSON_TYPE, 'x-contract-token': ide.token },
      body: JSON.stringify({ action: 'run', kind: 'make', sandbox: 'none', project: { files: SLOW_RUN } }),
    });
    expect(post.status).toBe(201);
    const { id } = (await post.json()) as { id: string };
    const evil = await new Promise<{ opened: boolean; events: number }>((resolve) => {
      const sock = new WebSocket(`${ide.url.replace('http', 'ws')}/api/jobs/${id}/ws`, {
        origin: 'http://evil.example',
        headers: { cookie: `contract_session_${port}=${ide.token}` },
      });
      let opened = false;
      let events = 0;
      sock.on('open', () => {
        opened = true;
        sock.send(JSON.stringify({ type: 'cancel' }));
        setTimeout(() => sock.close(), 500);
      });
      sock.on('message', () => events++);
      sock.on('error', () => resolve({ opened, events }));
      sock.on('close', () => resolve({ opened, events }));
    });
    expect(evil).toEqual({ opened: false, events: 0 });
    await new Promise((r) => setTimeout(r, 300));
    const job = (await (await fetch(`${ide.url}/api/jobs/${id}`, { headers: { 'x-contract-token': ide.token } })).json()) as { status: string };
    expect(job.status).not.toBe('cancelled');
    expect((await raw('DELETE', `/api/jobs/${id}`, { 'x-contract-token': ide.token })).status).toBe(202);
  }, 60_000);
});
