/**
 * The runs shared by the IDE's tabs (docs/ide.md "Several tabs"): through the real IDE server and
 * its embedded build service (bwrap), a client of /api/events hears of every job another client
 * submits on a project folder of the workspace (`job`), a client connecting while it runs is told
 * of it (`jobs`), one connecting after it ended is not, and a job on inline files is not announced.
 */
import { mkdirSync, mkdtempSync, realpathSync, writeFileSync, chmodSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { startIdeServer, type IdeServer } from './ide-server.js';

const MAKEFILE = 'all: prog\nprog: main.c\n\tgcc -std=c11 -O1 -o prog main.c\nrun: prog\n\t./prog\n.PHONY: all run\n';
/** Runs about 2 s, saying so. */
const MAIN = '#include <stdio.h>\n#include <unistd.h>\nint main(void) { for (int i = 0; i < 8; i++) { printf("tick %d\\n", i); fflush(stdout); usleep(250000); } return 0; }\n';

let base: string;
let ide: IdeServer;
const headers = () => ({ 'x-contract-token': ide.token, 'content-type': 'application/json' });

/** A client of /api/events: the events it got so far, by name. */
interface Listener {
  events: Array<{ event: string; data: unknown }>;
  close(): void;
}

async function listen(): Promise<Listener> {
  const ac = new AbortController();
  const res = await fetch(`${ide.url}/api/events`, { headers: headers(), signal: ac.signal });
  expect(res.status).toBe(200);
  const events: Listener['events'] = [];
  const reader = res.body!.getReader();
  const decoder = new TextDecoder();
  let buf = '';
  void (async () => {
    try {
      for (;;) {
        const { value, done } = await reader.read();
        if (done) return;
        buf += decoder.decode(value, { stream: true });
        for (let end = buf.indexOf('\n\n'); end >= 0; end = buf.indexOf('\n\n')) {
          const block = buf.slice(0, end);
          buf = buf.slice(end + 2);
          const event = /^event: (.*)$/m.exec(block)?.[1];
          const data = /^data: (.*)$/m.exec(block)?.[1];
          if (event && data !== undefined) events.push({ event, data: JSON.parse(data) });
        }
      }
    } catch {
      /* aborted */
    }
  })();
  // the greeting has come when `hello` has
  await expect.poll(() => events.some((e) => e.event === 'hello')).toBe(true);
  return { events, close: () => ac.abort() };
}

const named = (l: Listener, name: string) => l.events.filter((e) => e.event === name).map((e) => e.data);

async function submit(project: unknown, opts: { action?: 'build' | 'run'; client?: string } = {}): Promise<string> {
  const head = { ...headers(), ...(opts.client ? { 'x-contract-client': opts.client } : {}) };
  const r = await fetch(`${ide.url}/api/jobs`, { method: 'POST', headers: head, body: JSON.stringify({ action: opts.action ?? 'run', kind: 'make', sandbox: 'bwrap', project }) });
  expect(r.status, await r.clone().text()).toBe(201);
  return ((await r.json()) as { id: string }).id;
}

async function finished(id: string): Promise<string> {
  let status = 'queued';
  for (let i = 0; i < 600 && !['succeeded', 'failed', 'cancelled'].includes(status); i++) {
    await new Promise((r) => setTimeout(r, 100));
    status = ((await (await fetch(`${ide.url}/api/jobs/${id}`, { headers: headers() })).json()) as { status: string }).status;
  }
  return status;
}

beforeAll(async () => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-shared-runs-')));
  chmodSync(base, 0o711);
  mkdirSync(join(base, 'robot'));
  writeFileSync(join(base, 'robot', 'Makefile'), MAKEFILE);
  writeFileSync(join(base, 'robot', 'main.c'), MAIN);
  ide = await startIdeServer({ workspace: base, port: 0, buildService: true, distDir: join(base, 'no-dist') });
}, 60_000);

afterAll(async () => {
  await ide?.close();
  spawnSync('rm', ['-rf', '--one-file-system', base]);
});

describe('runs shared by the tabs of the IDE', () => {
  it('announces a job on a workspace project to every tab, tells a tab that connects while it runs, and nothing else', async () => {
    const first = await listen();
    expect(named(first, 'jobs')).toEqual([{ jobs: [] }]);
    const id = await submit({ dir: join(base, 'robot') });
    await expect.poll(() => named(first, 'job')).toEqual([{ id, action: 'run', project: 'robot' }]);
    // a tab opened (or reloaded) during the run
    await expect.poll(async () => (await (await fetch(`${ide.url}/api/jobs/${id}`, { headers: headers() })).json() as { status: string }).status, { timeout: 60_000 }).toBe('running');
    const during = await listen();
    expect(named(during, 'jobs')).toEqual([{ jobs: [{ id, action: 'run', project: 'robot' }] }]);
    expect(await finished(id)).toBe('succeeded');
    const after = await listen();
    expect(named(after, 'jobs')).toEqual([{ jobs: [] }]);
    // a job on inline files has no folder of the workspace: not announced
    const inline = await submit({ files: { Makefile: MAKEFILE, 'main.c': MAIN } });
    expect(await finished(inline)).toBe('succeeded');
    expect(named(first, 'job')).toEqual([{ id, action: 'run', project: 'robot' }]);
    expect(named(during, 'job')).toEqual([]);
    for (const l of [first, during, after]) l.close();
  }, 120_000);

  it("lists the workspace's recent Build & Run jobs the build service keeps, newest first: not a build, not inline files, not a job a client submitted with its own key", async () => {
    const older = await submit({ dir: join(base, 'robot') });
    expect(await finished(older)).toBe('succeeded');
    const build = await submit({ dir: join(base, 'robot') }, { action: 'build' });
    const script = await submit({ dir: join(base, 'robot') }, { client: 'a-script-of-its-own-0123456789' });
    const inline = await submit({ files: { Makefile: MAKEFILE, 'main.c': MAIN } });
    for (const id of [build, script, inline]) expect(await finished(id)).toBe('succeeded');
    const newer = await submit({ dir: join(base, 'robot') });
    await expect.poll(async () => (await (await fetch(`${ide.url}/api/jobs/${newer}`, { headers: headers() })).json() as { status: string }).status, { timeout: 60_000 }).toBe('running');
    const list = async () => ((await (await fetch(`${ide.url}/api/recent-runs`, { headers: headers() })).json()) as { jobs: Array<Record<string, unknown>> }).jobs;
    const during = await list();
    const ids = during.map((j) => j.id);
    expect(ids.indexOf(newer)).toBe(0);
    expect(ids).toContain(older);
    expect(ids.indexOf(older)).toBeGreaterThan(0);
    for (const id of [build, script, inline]) expect(ids).not.toContain(id);
    expect(during[0]).toMatchObject({ id: newer, project: 'robot', status: 'running', finishedAt: null, ok: null, message: null });
    expect(during.find((j) => j.id === older)).toMatchObject({ project: 'robot', status: 'succeeded', ok: true });
    expect(await finished(newer)).toBe('succeeded');
    expect((await list())[0]).toMatchObject({ id: newer, status: 'succeeded', ok: true });
    // the IDE server's key is its own: a client without one lists nothing from the service, the script its own job
    const anonymous = (await (await fetch(`${ide.url}/api/jobs`, { headers: headers() })).json()) as { jobs: unknown[] };
    expect(anonymous.jobs).toEqual([]);
    const own = (await (await fetch(`${ide.url}/api/jobs`, { headers: { ...headers(), 'x-contract-client': 'a-script-of-its-own-0123456789' } })).json()) as { jobs: Array<{ id: string }> };
    expect(own.jobs.map((j) => j.id)).toEqual([script]);
    // a session is needed
    expect((await fetch(`${ide.url}/api/recent-runs`)).status).toBe(401);
  }, 180_000);
});
