/**
 * The IDE server's own JSON routes (file API, Generate, new project, rename, Simulate) answer a
 * body that is not JSON as the build service answers it: `400 { code: "bad_request", error:
 * "invalid JSON: <the parser's error>" }` (one reading for both, conventions' parseJsonBody). They
 * said `request body must be a JSON object` for any fault, which named neither what nor where.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { createBuildServer, type BuildServer } from '@contract-studio/build-service';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';

let temp: TempIdeServer;
let standalone: BuildServer;
let standaloneUrl: string;
beforeAll(async () => {
  temp = await startTempIdeServer('ide-json-body-');
  standalone = createBuildServer({ host: '127.0.0.1', port: 0, token: false, sandbox: 'none', allowNoneSandbox: true });
  standaloneUrl = (await standalone.listen()).url;
});
afterAll(async () => {
  await temp?.close();
  await standalone?.close();
});

const MALFORMED = '{"path": "a.contract",';

async function post(base: string, path: string, body: string, headers: Record<string, string> = {}): Promise<{ status: number; json: Record<string, unknown> }> {
  const res = await fetch(base + path, { method: 'POST', headers: { 'content-type': 'application/json', ...headers }, body });
  return { status: res.status, json: (await res.json()) as Record<string, unknown> };
}

describe('a malformed JSON body', () => {
  it('is a 400 naming the parser\'s error on every JSON route of the IDE server, the same answer as the standalone build service gives', async () => {
    const service = await post(standaloneUrl, '/api/jobs', MALFORMED);
    expect(service.status).toBe(400);
    expect(service.json).toEqual({ code: 'bad_request', error: expect.stringMatching(/^invalid JSON: \S/) });
    for (const route of ['/api/create', '/api/rename', '/api/generate', '/api/new-project', '/api/rename-entity', '/api/simulate']) {
      const ide = await post(temp.ide.url, route, MALFORMED, { 'x-contract-token': temp.ide.token });
      expect({ route, ...ide }).toEqual({ route, status: 400, json: service.json });
    }
  });

  it('JSON that is no object is refused in the same words as the build service\'s', async () => {
    const service = await post(standaloneUrl, '/api/jobs', '[1]');
    const ide = await post(temp.ide.url, '/api/create', '[1]', { 'x-contract-token': temp.ide.token });
    expect(service).toEqual({ status: 400, json: { code: 'bad_request', error: 'the body must be a JSON object' } });
    expect(ide).toEqual(service);
  });
});
