import { afterEach, describe, expect, it } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer, WebSocket } from 'ws';
import { NOT_A_LOG_WHY, encodeTraceRecords, type TraceLine } from '@contract-studio/build-service/trace';
import { LiveFollower, type SocketLike } from './live-follower.js';
import { RemoteMonitorModel, type FollowerPort } from './remote-model.js';
import { MonitorModel } from './monitor-model.js';
import type { FromFollower, ToFollower } from './live-follow-protocol.js';

const dir = fileURLToPath(new URL('./fixtures/tutorial-run', import.meta.url));
const lines: TraceLine[] = readdirSync(dir).flatMap((file) => readFileSync(join(dir, file), 'utf8').split('\n').map((text, i) => ({ file, line: i + 1, text })))
  .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));

/** The job's event stream as the service sends it on its WebSocket: seq'd trace events of `per` records, then end. */
function events(per: number): string[] {
  const out: string[] = [];
  let seq = 0;
  for (let i = 0; i < lines.length; i += per) out.push(JSON.stringify({ type: 'trace', seq: ++seq, t: Date.now(), ...encodeTraceRecords(lines.slice(i, i + per)) }));
  out.push(JSON.stringify({ type: 'end', seq: ++seq, t: Date.now(), result: { ok: true } }));
  return out;
}

/** A worker and its page in one process: the follower and the remote model, messages cloned both ways as postMessage does. */
function pair(url: string | null, snapshotMs?: number): { remote: RemoteMonitorModel; follower: LiveFollower; posted: FromFollower[] } {
  const posted: FromFollower[] = [];
  let follower!: LiveFollower;
  const port: FollowerPort = {
    postMessage: (m: ToFollower) => queueMicrotask(() => follower.handle(structuredClone(m))),
    onmessage: null,
  };
  follower = new LiveFollower((m) => {
    const copy = structuredClone(m);
    posted.push(copy);
    setTimeout(() => port.onmessage?.({ data: copy } as MessageEvent<FromFollower>), 0);
  }, (u) => new WebSocket(u) as unknown as SocketLike, snapshotMs);
  const remote = new RemoteMonitorModel(port, url);
  return { remote, follower, posted };
}

let server: WebSocketServer | undefined;
afterEach(async () => {
  await new Promise((r) => server?.close(r) ?? r(undefined));
  server = undefined;
});

/** A stream server: `serve(ws, after, connection)` sends what it wants. */
async function listen(serve: (ws: WebSocket, after: number, n: number, url: URL) => void): Promise<string> {
  server = new WebSocketServer({ port: 0, host: '127.0.0.1' });
  let n = 0;
  server.on('connection', (ws, req) => {
    const url = new URL(req.url ?? '/', 'http://x');
    serve(ws, Number(url.searchParams.get('after') ?? 0), n++, url);
  });
  await new Promise((r) => server!.once('listening', r));
  return `ws://127.0.0.1:${(server.address() as { port: number }).port}/api/jobs/j/ws?trace=only`;
}

const settled = (m: RemoteMonitorModel) => Promise.race([m.settled, new Promise((_, no) => setTimeout(() => no(new Error('not settled')), 10_000))]);

describe('a live run followed in a worker', () => {
  it('folds every record of the stream, in order, into the same state and marks as a model fed on the page, and answers states far back', async () => {
    const frames = events(40);
    const url = await listen((ws, after) => {
      for (const f of frames.slice(after)) ws.send(f);
    });
    const { remote, posted } = pair(url);
    await settled(remote);
    const local = new MonitorModel();
    for (const l of lines) local.pushLine(l.file, l.line, l.text);
    expect(remote.recordCount).toBe(lines.length);
    expect(remote.end).toBe(local.end);
    expect(remote.live).toEqual(local.live);
    expect(remote.marks).toEqual(local.marks);
    expect(remote.problems).toEqual([]);
    expect(remote.missed).toBe(0); // every log's lines 2, 3, … came: nothing missing
    expect(posted.filter((p) => p.type === 'snapshot').length).toBeGreaterThan(0);
    // a state before the end is asked of the worker: undefined at first, the same as the page's model once it comes
    for (const t of [0, local.marks[3]!.t, local.end / 3, local.end - 1]) {
      expect(remote.stateAt(t)).toBeUndefined();
      const v = remote.version;
      await expect.poll(() => remote.version).toBeGreaterThan(v);
      expect(remote.stateAt(t)).toEqual(local.stateAt(t));
      expect(remote.exactAt(t)).toBe(local.exactAt(t));
    }
    expect(remote.stateAt(remote.end)).toBe(remote.live);
    expect(remote.marksBetween(0, local.end)).toEqual(local.marksBetween(0, local.end));
  });

  it('marks a record the trace channel says was cut (its log\'s last line, with no line end), as a recorded run of the same log does', async () => {
    const last = lines.length - 1;
    const cutLines = lines.map((l, i) => (i === last ? { ...l, cut: true as const } : l));
    const url = await listen((ws) => {
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(cutLines) }));
      ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: true } }));
    });
    const { remote } = pair(url);
    await settled(remote);
    const local = new MonitorModel();
    for (const [i, l] of lines.entries()) local.pushLineIn(l.file, l.line, l.text, 0, l.text.length, undefined, i === last);
    const cuts = remote.marks.filter((m) => m.label.startsWith('cut: its log ends inside this record'));
    expect(cuts).toHaveLength(1);
    expect(cuts[0]!.where).toBe(lines[last]!.text.split(',')[2]);
    expect(remote.marks).toEqual(local.marks);
  });

  it("takes the launcher's own line saying a module ended as a sign it is gone; a module's line of the same words is not the launcher's", async () => {
    const half = lines.slice(0, lines.length >> 1);
    const line = (seq: number, source: string, stream: string, text: string) => JSON.stringify({ type: 'line', seq, t: Date.now(), step: 'run', source, stream, line: text });
    const url = await listen((ws) => {
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(half) }));
      // MAA's own output (its [MAA] tag: source MAA) and a launcher line on stdout, both naming real pids: not taken
      ws.send(line(2, 'MAA', 'stderr', 'contract-launch: module MSA (pid 27) died by signal 9 (Killed)'));
      ws.send(line(3, 'MAA', 'stderr', 'module MSA (pid 27) died by signal 9 (Killed)'));
      ws.send(line(4, 'launcher', 'stdout', 'module MSA (pid 27) died by signal 9 (Killed)'));
      ws.send(line(5, 'launcher', 'stderr', 'module MAB (pid 26) died by signal 9 (Killed)'));
      ws.send(JSON.stringify({ type: 'end', seq: 6, t: Date.now(), result: { ok: false, message: 'run failed' } }));
    });
    const { remote } = pair(url);
    await settled(remote);
    const gone = [...remote.live.modules].filter(([, m]) => m.gone !== undefined).map(([n, m]) => `${n} ${m.gone}`);
    expect(gone).toEqual(['MAB gone: contract-launch: module MAB (pid 26) died by signal 9 (Killed)']);
    expect(remote.marks.filter((m) => m.kind === 'crash').map((m) => m.where)).toEqual(['MAB']);
  });

  it('takes a broken stream up again after the last event seen: nothing lost, nothing twice', async () => {
    const frames = events(25);
    const afters: number[] = [];
    const url = await listen((ws, after, n) => {
      afters.push(after);
      // the first two connections break after 5 events each
      const upTo = n < 2 ? after + 5 : frames.length;
      for (const f of frames.slice(after, upTo)) ws.send(f);
      if (n < 2) setTimeout(() => ws.terminate(), 20);
    });
    const { remote } = pair(url);
    await settled(remote);
    expect(afters).toEqual([0, 5, 10]);
    expect(remote.recordCount).toBe(lines.length);
    const local = new MonitorModel();
    for (const l of lines) local.pushLine(l.file, l.line, l.text);
    expect(remote.marks).toEqual(local.marks);
    expect(remote.problems).toEqual([]);
  }, 20_000);

  it('skips what is not an event, says a batch it cannot read, and keeps the rest; a stream that never comes back is said lost', async () => {
    const frames = events(50);
    const url = await listen((ws, _after, n) => {
      if (n > 0) return ws.terminate();
      ws.send('not json');
      ws.send('null');
      ws.send(JSON.stringify({ type: 'trace', seq: 0, files: ['a.csv'], runs: [0, 1, 3], text: 'only one line' }));
      ws.send(JSON.stringify({ type: 'line', seq: 0, line: 'a log line' }));
      for (const f of frames.slice(0, 3)) ws.send(f);
      setTimeout(() => ws.terminate(), 20);
    });
    const { remote } = pair(url);
    await settled(remote);
    expect(remote.recordCount).toBe(150);
    expect(remote.problems[0]).toMatch(/^a trace event could not be read \(trace event: the runs count 3 records, the text holds 1 lines\)/);
    expect(remote.problems.at(-1)).toMatch(/^lost the connection to the build service/);
  }, 30_000);

  it('says how the job ended: succeeded, cancelled, failed with its message, or the connection lost', async () => {
    const results: Array<[unknown, string]> = [
      [{ ok: true, message: '' }, 'succeeded'],
      [{ ok: false, message: 'cancelled' }, 'cancelled'],
      [{ ok: false, message: 'run: CTL exited with status 1' }, 'failed: run: CTL exited with status 1'],
      [null, 'failed'],
      [{ ok: 'yes', message: { x: 1 } }, 'failed'],
    ];
    for (const [result, outcome] of results) {
      const frames = events(40).slice(0, 2);
      const url = await listen((ws) => {
        for (const f of frames) ws.send(f);
        ws.send(JSON.stringify({ type: 'end', seq: 3, t: Date.now(), result }));
      });
      const { remote } = pair(url);
      await settled(remote);
      expect(remote.ended).toBe(true);
      expect(remote.outcome, JSON.stringify(result)).toBe(outcome);
      expect(remote.recordCount).toBe(80);
      await new Promise((r) => server!.close(r));
    }
    // the service went away (killed): the stream is lost for good
    const url = await listen((ws, _after, n) => (n > 0 ? ws.terminate() : setTimeout(() => ws.terminate(), 20)));
    const { remote } = pair(url);
    await settled(remote);
    expect(remote.outcome).toBe('connection to the build service lost');
  }, 60_000);

  it('counts the records a stream attached late never got: the service keeps the first ones for replay, the later ones go live only', async () => {
    // as job-events.ts does past traceLinesKept: the kept events replay from seq 0; the later ones
    // went to the clients attached then (not this page, reloaded meanwhile) and are not kept; those
    // read after it attached come live, carrying the seq of the last kept event
    const kept = 80, gone = 100;
    const keptFrames: string[] = [];
    for (let i = 0; i < kept; i += 40) keptFrames.push(JSON.stringify({ type: 'trace', seq: keptFrames.length + 1, t: Date.now(), ...encodeTraceRecords(lines.slice(i, i + 40)) }));
    const received = [...lines.slice(0, kept), ...lines.slice(kept + gone)];
    let release!: () => void;
    const resumed = new Promise<void>((r) => (release = r));
    const url = await listen((ws, after) => {
      for (const f of keptFrames.slice(after)) ws.send(f);
      void resumed.then(() => {
        for (let i = kept + gone; i < lines.length; i += 40) ws.send(JSON.stringify({ type: 'trace', seq: keptFrames.length, t: Date.now(), ...encodeTraceRecords(lines.slice(i, i + 40)) }));
        ws.send(JSON.stringify({ type: 'end', seq: keptFrames.length + 1, t: Date.now(), result: { ok: true } }));
      });
    });
    const { remote } = pair(url);
    // the kept records alone: whole so far (nothing tells of a gap yet)
    await expect.poll(() => remote.recordCount).toBe(kept);
    expect(remote.missed).toBe(0);
    release();
    await settled(remote);
    expect(remote.recordCount).toBe(received.length);
    // each log's lines that did not come before one that did: the gap in its numbering
    const byFile = new Map<string, number[]>();
    for (const l of received) byFile.set(l.file, [...(byFile.get(l.file) ?? []), l.line]);
    const gaps = [...byFile.values()].reduce((n, ls) => n + Math.max(...ls) - 1 - ls.length, 0);
    expect(gaps).toBeGreaterThan(50);
    expect(remote.missed).toBe(gaps);
    // the records missing at the end of a log (none came after them) are not counted: only the logs say how many
    expect(remote.missed).toBeLessThanOrEqual(gone);
  });

  it('counts the lines the service counted without sending them (no record: junk past its bound) as unreadable, not as records missed', async () => {
    const file = lines[0]!.file;
    const own = lines.filter((l) => l.file === file).slice(0, 3);
    // the log's line 2 a record, lines 3..42 junk the service did not send, then its records again
    const sent: TraceLine[] = [{ ...own[0]!, line: 2 }, { file, line: 3, text: '', unsent: 40 }, { ...own[1]!, line: 43 }, { ...own[2]!, line: 44 }];
    const url = await listen((ws) => {
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(sent) }));
      ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: true } }));
    });
    const { remote } = pair(url);
    await settled(remote);
    // before, such lines came whole (millions of them, the kept room gone) or not at all (said missed records)
    expect(remote.missed).toBe(0);
    expect(remote.live.records).toBe(3);
    expect(remote.live.unknownLines).toBe(40);
  });

  it('says a second log of one module in the run\'s folder (forged by some module\'s code) while the run goes on', async () => {
    const ord = lines.find((l) => l.file === 'ORD.csv')!;
    const own = { ...ord, file: 'ORD_6-Dec-2026-10h00m00s.csv' };
    const sent: TraceLine[] = [own, { ...own, file: 'ORD_6-Dec-2026-99h99m99s.csv', line: 2 }];
    const url = await listen((ws) => {
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(sent) }));
      ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: true } }));
    });
    const { remote } = pair(url);
    await settled(remote);
    expect(remote.problems).toEqual([`ORD: a second log of it in the run's logs folder (ORD_6-Dec-2026-99h99m99s.csv, beside ${own.file}), read with the first: a run writes one log per module (a file named as its log that is not one)`]);
  });

  it('says a file whose line 1 is not the runtime\'s header (the service sends that line 1 alone) and folds none of it: no deadline miss of ORD, no second log', async () => {
    const named = lines.map((l) => ({ ...l, file: `${l.file.slice(0, -4)}_4-Dec-2026-05h49m24s.csv` }));
    const forged = 'ORD_4-Dec-2026-05h49m59s.csv';
    const miss = '52092900000000,2026-12-04T05:49:27.253000Z,ORD,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=3 tick_ns=52092787155629';
    const half = named.findIndex((l) => Number(l.text.slice(0, l.text.indexOf(','))) > 52092900000000);
    const sent: TraceLine[] = [...named.slice(0, half), { file: forged, line: 1, text: miss }, ...named.slice(half)];
    const url = await listen((ws) => {
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(sent) }));
      ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: true } }));
    });
    const { remote } = pair(url);
    await settled(remote);
    const clean = new MonitorModel();
    for (const l of named) clean.pushLine(l.file, l.line, l.text);
    expect(remote.problems).toEqual([`${forged}: ${NOT_A_LOG_WHY}`]);
    expect(remote.live.periodic.get('schemaCommande1')!.deadlineMisses).toBe(clean.live.periodic.get('schemaCommande1')!.deadlineMisses);
    expect(remote.marks.filter((m) => m.kind === 'miss')).toEqual(clean.marks.filter((m) => m.kind === 'miss'));
    expect(remote.recordCount).toBe(named.length);
    expect(remote.live.unknownLines).toBe(clean.live.unknownLines + 1);
  });

  it('sends the page at most one snapshot per snapshotMs, and the last one always', async () => {
    const frames = events(2); // many small events, sent at once
    const url = await listen((ws) => {
      for (const f of frames) ws.send(f);
    });
    const start = performance.now();
    const { remote, posted } = pair(url, 50);
    await settled(remote);
    const took = performance.now() - start;
    const snapshots = posted.filter((p) => p.type === 'snapshot').length;
    expect(frames.length).toBeGreaterThan(100);
    expect(snapshots).toBeLessThanOrEqual(Math.ceil(took / 50) + 2);
    expect(remote.recordCount).toBe(lines.length);
  });

  it('a worker that fails ends the live trace and says why', async () => {
    const { remote } = pair(null);
    let changes = 0;
    remote.onChange = () => changes++;
    remote.fail('the live trace\'s worker failed (boom)');
    await settled(remote);
    expect(remote.ended).toBe(true);
    expect(remote.problems).toEqual(['the live trace\'s worker failed (boom)']);
    expect(changes).toBe(1);
  });

  it('folds lines the page hands over when it follows no stream, bounded per line', async () => {
    const { remote } = pair(null);
    remote.feed(lines.slice(0, 100));
    remote.feed([{ file: 'x.csv', line: 2, text: `${'9'.repeat(5000)}` }, { file: 3, line: 'x', text: null } as unknown as TraceLine]);
    await expect.poll(() => remote.recordCount).toBe(101);
    expect(remote.live.unknownLines).toBe(1);
  });
});

describe('the benchmark\'s measure (follow with measure: true)', () => {
  it('reads each record\'s wall time to the microsecond, across seconds, from lines read in place', async () => {
    const url = await listen((ws) => {
      const text = (wall: string, n: number) => `${1000 + n},${wall},MSA,run_started,ORD,,0,activation=${n}`;
      const walls = ['2026-11-28T13:58:13.785123', '2026-11-28T13:58:13.999999', '2026-11-28T13:58:14.000001', '2026-11-28T13:59:00.500000'];
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(walls.map((w, i) => ({ file: 'MSA_1.csv', line: i + 2, text: text(w, i) }))) }));
      ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: true } }));
    });
    const posted: FromFollower[] = [];
    const follower = new LiveFollower((m) => posted.push(structuredClone(m)), (u) => new WebSocket(u) as unknown as SocketLike, 0);
    follower.handle({ type: 'follow', url, measure: true });
    await expect.poll(() => posted.some((m) => m.type === 'snapshot' && m.ended), { timeout: 5000 }).toBe(true);
    const walls = posted.flatMap((m) => (m.type === 'snapshot' && m.walls ? [...m.walls] : []));
    const second = Date.parse('2026-11-28T13:58:13Z');
    expect(walls).toHaveLength(4);
    expect(walls[0]).toBeCloseTo(second + 785.123, 6);
    expect(walls[1]).toBeCloseTo(second + 999.999, 6);
    expect(walls[2]).toBeCloseTo(second + 1000.001, 6);
    expect(walls[3]).toBeCloseTo(Date.parse('2026-11-28T13:59:00Z') + 500, 6);
    follower.handle({ type: 'stop' });
  });
});
