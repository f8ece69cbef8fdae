/**
 * The standalone service refuses foreign Hosts (DNS rebinding) and cross-site Origins on its HTTP
 * API and on the job WebSocket: a page of another site must not read a job's events nor cancel it.
 * Real server, real job (`kind: "make"`, sandbox none: the Makefile only echoes and sleeps).
 */
import { request } from 'node:http';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import WebSocket from 'ws';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { createBuildServer, type BuildServer } from '../server.js';
import { getJob, postJob } from '../test-support/client.js';

let server: BuildServer;
let url: string;
let port: number;
let cacheDir: string;

const SLOW_RUN = { Makefile: 'all:\n\t@echo built\nrun:\n\t@echo running; sleep 60\n.PHONY: all run\n' };

beforeAll(async () => {
  cacheDir = mkdtempSync(join(tmpdir(), 'contract-guard-'));
  server = createBuildServer({ token: false, allowNoneSandbox: true, port: 0, cacheDir, sandbox: 'none', concurrency: 2 });
  ({ url, port } = await server.listen());
});
afterAll(async () => {
  await server?.close();
  rmSync(cacheDir, { recursive: true, force: true });
});

/** Status of a raw request (101 for an accepted WebSocket upgrade). */
function status(path: string, headers: Record<string, string>, method = 'GET', body = ''): Promise<number> {
  return new Promise((resolve, reject) => {
    const r = request(url + path, { method, headers, agent: false }, (res) => {
      res.resume();
      resolve(res.statusCode ?? 0);
    });
    r.on('upgrade', (res, socket) => {
      socket.destroy();
      resolve(res.statusCode ?? 0);
    });
    r.on('error', reject);
    r.end(body);
  });
}

const UPGRADE = { connection: 'Upgrade', upgrade: 'websocket', 'sec-websocket-version': '13', 'sec-websocket-key': 'dGhlIHNhbXBsZSBub25jZQ==' };

async function startSlowJob(): Promise<string> {
  const { status: code, json } = await postJob(url, { action: 'run', kind: 'make', sandbox: 'none', project: { files: SLOW_RUN } });
  expect(code).toBe(201);
  return json.id as string;
}

/** Opens the job socket as a page of `origin` would, sends cancel; resolves what it could read. */
function evilSocket(id: string, origin: string): Promise<{ opened: boolean; events: number }> {
  return new Promise((resolve) => {
    const ws = new WebSocket(`${url.replace('http', 'ws')}/api/jobs/${id}/ws`, { origin });
    let opened = false;
    let events = 0;
    ws.on('open', () => {
      opened = true;
      ws.send(JSON.stringify({ type: 'cancel' }));
      setTimeout(() => ws.close(), 500);
    });
    ws.on('message', () => events++);
    ws.on('error', () => resolve({ opened, events }));
    ws.on('close', () => resolve({ opened, events }));
  });
}

describe('standalone build service: Host and Origin checks', () => {
  test('a page of another site cannot read nor cancel a job over the WebSocket', async () => {
    const id = await startSlowJob();
    for (const origin of ['http://evil.example', 'null', `http://evil.example:${port}`]) {
      expect(await evilSocket(id, origin), origin).toEqual({ opened: false, events: 0 });
    }
    await new Promise((r) => setTimeout(r, 300));
    expect((await getJob(url, id)).status).not.toBe('cancelled');
    // the service's own clients (no Origin: programs; or its own origin) still can
    expect(await status(`/api/jobs/${id}/ws`, UPGRADE)).toBe(101);
    expect(await status(`/api/jobs/${id}/ws`, { ...UPGRADE, origin: url })).toBe(101);
    expect(await status(`/api/jobs/${id}`, {}, 'DELETE')).toBe(202);
  }, 60_000);

  test('upgrade variants: evil origin, null origin, wrong Host without Origin, DNS-rebinding Host', async () => {
    const path = '/api/jobs/j-00000000000000000000000000000000/ws';
    expect(await status(path, { ...UPGRADE, origin: 'http://evil.example' })).toBe(403);
    expect(await status(path, { ...UPGRADE, origin: 'null' })).toBe(403);
    expect(await status(path, { ...UPGRADE, host: 'evil.example' })).toBe(403);
    expect(await status(path, { ...UPGRADE, host: `evil.example:${port}`, origin: `http://evil.example:${port}` })).toBe(403);
    // past the checks, an unknown job is a 404
    expect(await status(path, UPGRADE)).toBe(404);
    expect(await status(path, { ...UPGRADE, host: `localhost:${port}`, origin: `http://localhost:${port}` })).toBe(404);
  });

  test('HTTP variants: rebinding Host refused on reads, cross-site Origin refused on writes', async () => {
    expect(await status('/api/health', { host: `evil.example:${port}` })).toBe(403);
    expect(await status('/api/health', {})).toBe(200);
    const body = JSON.stringify({ action: 'build', kind: 'make', sandbox: 'none', project: { files: SLOW_RUN } });
    expect(await status('/api/jobs', { origin: 'http://evil.example', 'content-type': 'text/plain' }, 'POST', body)).toBe(403);
    expect(await status('/api/jobs', { origin: 'null', 'content-type': 'application/json' }, 'POST', body)).toBe(403);
    expect(await status('/api/jobs/j-00000000000000000000000000000000', { origin: 'http://evil.example' }, 'DELETE')).toBe(403);
    expect(await status('/api/jobs/j-00000000000000000000000000000000', {}, 'DELETE')).toBe(404);
  });
});
