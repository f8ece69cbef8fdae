/**
 * The HTTP API against real bwrap jobs: streaming order and completeness (SSE and WebSocket,
 * live and replayed), queue full -> 429, cancel mid-build and mid-run within 2 s, diagnostics,
 * request validation.
 */
import WebSocket from 'ws';
import { describe, expect, test } from 'vitest';
import { CANCEL_DEADLINE_MS, CANCEL_GRACE_MS } from './limits.js';
import type { JobEvent, LineEvent } from './pipeline/job-events.js';
import { useBuildServer } from './test-support/build-server.js';
import { brokenProgram, honestProgram, infiniteLoop, makeProject } from './test-support/c-projects.js';
import { getJob, jobEventFromWire, postJob, readEvents } from './test-support/client.js';

const served = useBuildServer({ concurrency: 2, queueSize: 1, sandbox: 'bwrap' }, { snapshotRuntime: false });

function wsEvents(id: string): Promise<JobEvent[]> {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(`${served.url.replace('http', 'ws')}/api/jobs/${id}/ws`);
    const events: JobEvent[] = [];
    ws.on('message', (d) => events.push(jobEventFromWire(JSON.parse(String(d)) as Record<string, unknown>)));
    ws.on('close', () => resolve(events));
    ws.on('error', reject);
  });
}

function checkStream(lines: LineEvent[], stream: 'stdout' | 'stderr', prefix: string, n: number): void {
  const got = lines.filter((l) => l.step === 'run' && l.stream === stream && l.line.startsWith(prefix)).map((l) => l.line);
  expect(got).toEqual(Array.from({ length: n }, (_, i) => `${prefix} ${i}`));
}

describe('streaming', () => {
  test('every line arrives once, in order per stream, live and on replay (SSE and WebSocket)', async () => {
    const n = 3000;
    const r = await postJob(served.url, { action: 'run', kind: 'make', project: { files: makeProject(honestProgram(n)) } });
    expect(r.status).toBe(201);
    const id = r.json.id as string;
    const [live, ws] = await Promise.all([readEvents(served.url, id), wsEvents(id)]);
    const replay = await readEvents(served.url, id);
    for (const events of [live, ws, replay]) {
      expect(events.map((e) => e.seq)).toEqual(Array.from({ length: events.length }, (_, i) => i + 1));
      const lines = events.filter((e): e is LineEvent => e.type === 'line');
      checkStream(lines, 'stdout', 'out', n);
      checkStream(lines, 'stderr', 'err', n);
      expect(events.at(-1)!.type).toBe('end');
      for (const l of lines) expect(typeof l.t).toBe('number');
    }
    expect(JSON.stringify(ws)).toBe(JSON.stringify(live));
    expect(JSON.stringify(replay)).toBe(JSON.stringify(live));
    // resume after a given event
    const tail = await readEvents(served.url, id, undefined, 10);
    expect(tail[0]!.seq).toBe(11);
    // the text log keeps every line
    const log = await (await fetch(`${served.url}/api/jobs/${id}/log`)).text();
    expect(log.split('\n').filter((l) => / run run stdout \| out \d+$/.test(l))).toHaveLength(n);
  });
});

describe('diagnostics', () => {
  test('gcc problems come back structured, with file, line and column', async () => {
    const r = await postJob(served.url, { action: 'build', kind: 'make', project: { files: makeProject(brokenProgram) } });
    const events = await readEvents(served.url, r.json.id as string);
    const job = await getJob(served.url, r.json.id as string);
    expect(job.status).toBe('failed');
    expect(job.result.message).toMatch(/^build failed: 1 error\(s\)/);
    const err = job.diagnostics.find((d: any) => d.severity === 'error');
    expect(err).toMatchObject({ file: 'main.c', line: 9, column: 10, message: expect.stringContaining('undeclared_thing') });
    const warn = job.diagnostics.find((d: any) => d.severity === 'warning');
    expect(warn).toMatchObject({ file: 'main.c', line: 8, option: '-Wunused-variable' });
    expect(events.filter((e) => e.type === 'diagnostic')).toHaveLength(job.diagnostics.length);
  });
});

describe('queue and cancel', () => {
  test('a full queue answers 429; a queued job can be cancelled at once', async () => {
    const loop = { action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) }, limits: { runSeconds: 30 } };
    const a = await postJob(served.url, loop);
    const b = await postJob(served.url, loop);
    const c = await postJob(served.url, loop); // queued (queueSize 1)
    const d = await postJob(served.url, loop);
    expect([a.status, b.status, c.status]).toEqual([201, 201, 201]);
    expect(d.status).toBe(429);
    expect(d.json.code).toBe('queue_full');
    expect(d.headers.get('retry-after')).toBe('2');
    const cancelQueued = await fetch(`${served.url}/api/jobs/${c.json.id}`, { method: 'DELETE' });
    expect(cancelQueued.status).toBe(202);
    expect((await getJob(served.url, c.json.id as string)).status).toBe('cancelled');
    for (const j of [a, b]) await fetch(`${served.url}/api/jobs/${j.json.id}`, { method: 'DELETE' });
    for (const j of [a, b]) expect((await getJob(served.url, (await readEvents(served.url, j.json.id as string)) && (j.json.id as string))).status).toBe('cancelled');
  });

  async function cancelWhen(body: unknown, ready: (e: JobEvent) => boolean): Promise<{ ms: number; job: Record<string, any> }> {
    const r = await postJob(served.url, body);
    const id = r.json.id as string;
    let t0 = 0;
    let sent = false;
    await readEvents(served.url, id, (e) => {
      if (!sent && ready(e)) {
        sent = true;
        t0 = Date.now();
        void fetch(`${served.url}/api/jobs/${id}`, { method: 'DELETE' });
      }
    });
    return { ms: Date.now() - t0, job: await getJob(served.url, id) };
  }

  test('cancel mid-run stops everything within 2 s', async () => {
    const { ms, job } = await cancelWhen(
      { action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) } },
      (e) => e.type === 'line' && e.line === 'looping',
    );
    expect(job.status).toBe('cancelled');
    expect(job.result.message).toBe('cancelled');
    expect(ms).toBeLessThan(CANCEL_DEADLINE_MS);
  });

  test('cancel of a program that takes the launcher\'s name and ignores SIGTERM: asked, then killed after the grace, within 2 s', async () => {
    const files = makeProject(infiniteLoop);
    // `make run` runs a shell named like the launcher (its comm: the file name) that ignores SIGTERM
    files.Makefile = `all:\n\ttrue\nrun:\n\tcp /bin/sh ./contract-launch && exec ./contract-launch -c 'trap "" TERM; echo looping; while :; do sleep 1; done'\n`;
    const { ms, job } = await cancelWhen({ action: 'run', kind: 'make', project: { files } }, (e) => e.type === 'line' && e.line === 'looping');
    expect(job.status).toBe('cancelled');
    console.info(`cancel of a program named like the launcher that ignores SIGTERM: ${ms} ms`);
    expect(ms).toBeGreaterThanOrEqual(CANCEL_GRACE_MS - 50);
    expect(ms).toBeLessThan(CANCEL_DEADLINE_MS);
    const log = await (await fetch(`${served.url}/api/jobs/${job.id as string}/log`)).text();
    expect(log).toContain('stopping the architecture as at the end of a run');
    expect(log).toContain(`the architecture did not stop within ${CANCEL_GRACE_MS} ms: killed`);
  });

  test('cancel mid-build stops everything within 2 s', async () => {
    const files = makeProject(honestProgram(1));
    files.Makefile = `all:\n\t@echo compiling; sleep 60\nrun:\n\ttrue\n`;
    const { ms, job } = await cancelWhen({ action: 'build', kind: 'make', project: { files } }, (e) => e.type === 'line' && e.line === 'compiling');
    expect(job.status).toBe('cancelled');
    expect(job.result.step).toBe('build');
    expect(ms).toBeLessThan(CANCEL_DEADLINE_MS);
  });
});

describe('requests', () => {
  test.each([
    [{ project: { files: { '../x': '' } }, kind: 'make' }, 400, /"\.\." component/],
    [{ project: { files: { '/etc/passwd': '' } }, kind: 'make' }, 400, /absolute path/],
    // what a stage could not hold, or shows as another name: refused before anything is queued
    [{ project: { files: Object.fromEntries(Array.from({ length: 10_001 }, (_, i) => [`m${i}.contract`, ''])) } }, 400, /project\.files holds 10001 files: more than the 10000 a job is given/],
    [{ project: { files: { [`${'a/'.repeat(600)}x.contract`]: '' } } }, 400, /a path of at most 1024 bytes, each part at most 255/],
    [{ project: { files: { [`${'n'.repeat(256)}.contract`]: '' } } }, 400, /each part at most 255/],
    [{ project: { files: { '\u202eevil.contract': '' } } }, 400, /the character U\+202E is refused in a path/],
    [{ project: { files: { 'a\u0001b.contract': '' } } }, 400, /the character U\+0001 is refused in a path/],
    [{ project: { dir: '/etc' } }, 403, /outside the folders/],
    [{ project: { files: {} }, sandbox: 'chroot' }, 400, /sandbox must be one of/],
    [{ project: { files: {} }, limits: { memoryMiB: 4096 } }, 400, /above the server's 512/],
    [{ project: { files: {} }, limits: { cpu: 1 } }, 400, /unknown limit "cpu"/],
    // under what every sandbox can enforce (Docker's engine refused 1 MiB only once the job was accepted)
    [{ project: { files: {} }, limits: { memoryMiB: 1 } }, 400, /limit memoryMiB must be at least 32 MiB/],
    [{ project: { files: {} }, action: 'deploy' }, 400, /action must be/],
    [{ project: { files: {} }, cpus: '0; reboot' }, 400, /cpus must be a CPU list/],
    [{ project: { files: {} }, cpus: 1 }, 400, /cpus must be a CPU list/],
    // a CPU this machine lacks: refused now (contract-launch refused it only after the build)
    [{ project: { files: {} }, cpus: '0,4096' }, 400, /cpus: CPU 4096 is not available here \(\d+ CPUs online: 0-\d+\)/],
    [{ project: { files: {} }, start: "GLB.mission()'; rm -rf /work; '" }, 400, /start must be one line/],
    // READY_TIMEOUT ends up in the make command line: a number within the run's time only
    [{ project: { files: {} }, readyTimeout: '30; reboot' }, 400, /readyTimeout must be a number of seconds from 0\.1 to \d+/],
    [{ project: { files: {} }, readyTimeout: 0.01 }, 400, /readyTimeout must be a number of seconds from 0\.1/],
    [{ project: { files: {} }, readyTimeout: 1e9 }, 400, /readyTimeout must be a number of seconds from 0\.1 to \d+ \(the run's time limit, \d+ s, less the room kept to stop it\)/],
  ])('%j -> %i', async (body, status, message) => {
    const r = await postJob(served.url, body);
    expect(r.status).toBe(status);
    expect(r.json.error).toMatch(message);
  });

  test('invalid JSON and unknown ids get clear errors', async () => {
    const bad = await fetch(`${served.url}/api/jobs`, { method: 'POST', headers: { 'content-type': 'application/json' }, body: '{nope' });
    expect(bad.status).toBe(400);
    expect(((await bad.json()) as { error: string }).error).toMatch(/invalid JSON/);
    const missing = await fetch(`${served.url}/api/jobs/j-nothere`);
    expect(missing.status).toBe(404);
  });

  test('a client lists only its own jobs (X-Contract-Client); job ids are 128-bit handles', async () => {
    const alice = { 'X-Contract-Client': 'alice-0123456789abcdef' };
    const bob = { 'X-Contract-Client': 'bob-0123456789abcdef' };
    const list = async (headers: Record<string, string>) => (await (await fetch(`${served.url}/api/jobs`, { headers })).json()) as { jobs: Array<{ id: string }>; note?: string };
    const a = await postJob(served.url, { kind: 'make', project: { files: makeProject(honestProgram()) } }, alice);
    const b = await postJob(served.url, { kind: 'make', project: { files: makeProject(honestProgram()) } }, bob);
    expect([a.status, b.status]).toEqual([201, 201]);
    expect(a.json.id).toMatch(/^j-[0-9a-f]{32}$/);
    expect((await list(alice)).jobs.map((j) => j.id)).toEqual([a.json.id]);
    expect((await list(bob)).jobs.map((j) => j.id)).toEqual([b.json.id]);
    const anonymous = await list({});
    expect(anonymous.jobs).toEqual([]); // no key: nobody's jobs, and says how to list yours
    expect(anonymous.note).toMatch(/X-Contract-Client/);
    const short = await fetch(`${served.url}/api/jobs`, { headers: { 'X-Contract-Client': 'short' } });
    expect(short.status).toBe(400);
    await readEvents(served.url, a.json.id as string);
    await readEvents(served.url, b.json.id as string);
  });

  test('GET /api/sandboxes says what auto picks and the limits', async () => {
    const info = (await (await fetch(`${served.url}/api/sandboxes`)).json()) as Record<string, any>;
    expect(info.auto).toBe('bwrap');
    expect(info.limits).toMatchObject({ memoryMiB: 512, processes: 256, buildSeconds: 120, runSeconds: 60, outputBytesPerStream: 1048576 });
    expect(info.sandboxes.find((s: any) => s.name === 'none').detail).toMatch(/not enforced: network isolation/);
  });
});
