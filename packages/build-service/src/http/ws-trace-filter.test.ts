/**
 * GET /api/jobs/:id/ws?trace=all|none|only on the real standalone server with the real `ws`
 * client: each value gives its events with their original seqs, in replay and live, combined with
 * `?after=`; any other value is a 400 that leaves the service serving. The job is a JobEvents of
 * a few events of our own, handed out by the service for one id (no sandbox needed).
 */
import WebSocket from 'ws';
import { describe, expect, test } from 'vitest';
import { useServedJob } from '../test-support/served-job.js';
import { upgradeStatus as rawUpgradeStatus } from '../test-support/client.js';

const ID = 'j-fake';
const job = useServedJob(ID);
const built = job.built;

const trace = (line: number) => ({ type: 'trace' as const, records: [{ file: 'M_1.csv', line, text: `${line},2026-11-26T12:00:00.000000Z,M,user,,,0,x` }] });

/** seqs 1..5, kept for replay: status, line, trace, trace, line. */
function appendReplay(): void {
  job.events.append({ type: 'status', status: 'running', step: 'run' });
  job.events.append({ type: 'line', step: 'run', source: 'M', stream: 'stdout', line: 'hello' });
  job.events.append(trace(2));
  job.events.append(trace(3));
  job.events.append({ type: 'line', step: 'run', source: 'M', stream: 'stderr', line: 'oops' });
}

/** seqs 6..9 live: trace, status, trace, end. */
function appendLive(): void {
  job.events.append(trace(4));
  job.events.append({ type: 'status', status: 'succeeded' });
  job.events.append(trace(5));
  job.events.append({ type: 'end', result: null });
}

/** Opens a socket on `query`; `frames` resolves the `type@seq` of every frame it got once the server closed it. */
async function follow(query: string): Promise<{ frames: Promise<string[]> }> {
  const ws = new WebSocket(`${built.url.replace('http', 'ws')}/api/jobs/${ID}/ws${query}`);
  const got: string[] = [];
  ws.on('message', (data) => {
    const e = JSON.parse(String(data)) as { type: string; seq: number };
    got.push(`${e.type}@${e.seq}`);
  });
  const frames = new Promise<string[]>((resolve) => ws.on('close', () => resolve(got)));
  await new Promise((resolve, reject) => {
    ws.on('open', resolve);
    ws.on('error', reject);
  });
  return { frames };
}

/** Status and body of a raw upgrade request to the service (101 for an accepted one). */
const upgradeStatus = (path: string) => rawUpgradeStatus(built.url + path);

const ALL = ['status@1', 'line@2', 'trace@3', 'trace@4', 'line@5', 'trace@6', 'status@7', 'trace@8', 'end@9'];
const NONE = ['status@1', 'line@2', 'line@5', 'status@7', 'end@9'];
const ONLY = ['trace@3', 'trace@4', 'trace@6', 'trace@8', 'end@9'];

describe('job WebSocket ?trace= filter', () => {
  test('all / none / only: the right events with their own seqs, replayed then live, and with ?after=', async () => {
    appendReplay();
    const streams = {
      absent: await follow(''),
      all: await follow('?trace=all'),
      none: await follow('?trace=none'),
      only: await follow('?trace=only'),
      noneAfter2: await follow('?trace=none&after=2'),
      onlyAfter3: await follow('?after=3&trace=only'),
      onlyAfter5: await follow('?trace=only&after=5'),
    };
    // every socket attached before the live events: these come by live delivery, not replay
    expect(job.events.subscriberCount).toBe(Object.keys(streams).length);
    appendLive();
    expect(await streams.absent.frames).toEqual(ALL);
    expect(await streams.all.frames).toEqual(ALL);
    expect(await streams.none.frames).toEqual(NONE);
    expect(await streams.only.frames).toEqual(ONLY);
    expect(await streams.noneAfter2.frames).toEqual(['line@5', 'status@7', 'end@9']);
    expect(await streams.onlyAfter3.frames).toEqual(['trace@4', 'trace@6', 'trace@8', 'end@9']);
    expect(await streams.onlyAfter5.frames).toEqual(['trace@6', 'trace@8', 'end@9']);
  }, 10_000);

  test('a finished job: the filter applies to the whole replay, which ends with the end event', async () => {
    appendReplay();
    appendLive();
    expect(await (await follow('?trace=none')).frames).toEqual(NONE);
    expect(await (await follow('?trace=only')).frames).toEqual(ONLY);
    // resuming a filtered stream from the last seq it saw
    expect(await (await follow('?trace=only&after=4')).frames).toEqual(['trace@6', 'trace@8', 'end@9']);
    expect(await (await follow('?trace=none&after=7')).frames).toEqual(['end@9']);
  }, 10_000);

  test("launcher: the trace, the launcher's own lines and the end, in seq order, replayed then live; a module's line is not one of them", async () => {
    appendReplay();
    job.events.append({ type: 'line', step: 'run', source: 'launcher', stream: 'stderr', line: 'module M (pid 4) died by signal 9 (Killed)' });
    // a module's line holding the launcher's words is the module's (its [M] tag), never sent on this socket
    job.events.append({ type: 'line', step: 'run', source: 'M', stream: 'stderr', line: 'contract-launch: module ORD (pid 2) died by signal 9 (Killed)' });
    const live = await follow('?trace=launcher');
    appendLive();
    const frames = ['trace@3', 'trace@4', 'line@6', 'trace@8', 'trace@10', 'end@11'];
    expect(await live.frames).toEqual(frames);
    expect(await (await follow('?trace=launcher')).frames).toEqual(frames);
    expect(await (await follow('?trace=launcher&after=6')).frames).toEqual(['trace@8', 'trace@10', 'end@11']);
  }, 10_000);

  test('any other value is a 400 saying what is allowed; the service keeps serving', async () => {
    appendReplay();
    for (const q of ['?trace=bogus', '?trace=', '?trace=ALL', '?trace=none&trace=bogus', '?trace=only&trace=none', '?trace=only&trace']) {
      const { status, body } = await upgradeStatus(`/api/jobs/${ID}/ws${q}`);
      expect(status, q).toBe(400);
      expect(body, q).toMatch(/all, none, only, launcher/);
    }
    // the same for a job that does not exist; a good value there is still a 404
    expect((await upgradeStatus('/api/jobs/j-none/ws?trace=x')).status).toBe(400);
    expect((await upgradeStatus('/api/jobs/j-none/ws?trace=only')).status).toBe(404);
    // nobody was attached by a refused upgrade, and the service still serves HTTP and sockets
    expect(job.events.subscriberCount).toBe(0);
    expect((await fetch(`${built.url}/api/health`)).status).toBe(200);
    expect((await upgradeStatus(`/api/jobs/${ID}/ws?trace=only&trace=only`)).status).toBe(101);
    const stream = await follow('?trace=only');
    appendLive();
    expect(await stream.frames).toEqual(ONLY);
  }, 10_000);

  test('a resume position that is no event number (after=, Last-Event-ID) is a 400 on both streams, not a replay from the start', async () => {
    appendReplay();
    for (const q of ['?after=abc', '?after=', '?after=+1', '?after=%201', '?after=0x10', '?after=1e308', '?after=-3', '?after=1.5', `?after=${'9'.repeat(5000)}`, '?after=1&after=abc', '?after=1&after=2']) {
      const ws = await upgradeStatus(`/api/jobs/${ID}/ws${q}`);
      expect(ws.status, q).toBe(400);
      expect(ws.body, q).toMatch(/must be an event number/);
      const sse = await fetch(`${built.url}/api/jobs/${ID}/events${q}`);
      expect(sse.status, q).toBe(400);
      expect(await sse.json(), q).toMatchObject({ code: 'bad_request', error: expect.stringMatching(/must be an event number/) });
    }
    const header = await fetch(`${built.url}/api/jobs/${ID}/events`, { headers: { 'Last-Event-ID': '1e400' } });
    expect(header.status).toBe(400);
    await header.body?.cancel();
    // the header before the parameter (what a reconnecting EventSource sends); one value given twice is one
    const both = await fetch(`${built.url}/api/jobs/${ID}/events?after=1&after=1`, { headers: { 'Last-Event-ID': '4' } });
    expect(both.status).toBe(200);
    await both.body?.cancel();
    // a good one resumes as before
    const resumed = await follow('?after=3');
    expect(job.events.subscriberCount).toBe(1);
    appendLive();
    expect(await resumed.frames).toEqual(['trace@4', 'line@5', 'trace@6', 'status@7', 'trace@8', 'end@9']);
  }, 10_000);
});
