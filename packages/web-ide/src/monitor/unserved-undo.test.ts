/**
 * A supervisor's undo that ORD never served, as the Monitor marks it on the schema's row, in the
 * words `contract trace` tells it: the real tutorial run of fixtures/killed-ord-run (its README:
 * ORD stopped during schemaCommande1's activation, terminated at the run's end with no exit record,
 * SUP's undo sent to its mailbox), replayed from its logs and followed live; and an ORD whose exit
 * record follows the undo.
 */
import { afterEach, describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer, WebSocket } from 'ws';
import { CSV_HEADER, encodeTraceRecords, parseTrace, renderStory, type LogFile, type TraceLine } from '@contract-studio/build-service/trace';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import { MonitorModel } from './monitor-model.js';
import { LiveFollower, type SocketLike } from './live-follower.js';
import { RemoteMonitorModel, type FollowerPort } from './remote-model.js';
import type { FromFollower, ToFollower } from './live-follow-protocol.js';

const dir = fileURLToPath(new URL('./fixtures/killed-ord-run', import.meta.url));
const logs: LogFile[] = readdirSync(dir).filter((n) => n.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(dir, name), 'utf8') }));

/** What `contract trace` tells of the undo after the last record (its words after the time and module). */
const told = renderStory(parseTrace(logs)).find((l) => l.includes('no answer to SUP\'s undo'));
const UNSERVED = /no answer to SUP's undo|before it served/;

function built(steps: Generator<void, RecordedRun>): MonitorModel {
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

let server: WebSocketServer | undefined;
afterEach(async () => {
  await new Promise((r) => server?.close(r) ?? r(undefined));
  server = undefined;
});

describe('an undo ORD never served, in the Monitor', () => {
  it('contract trace tells it for the real run (the sentence the Monitor must show)', () => {
    expect(told).toMatch(/^\+5\.009420s ORD {2}while the run stopped: ORD's log ends with no exit record .* schemaCommande1 may have stayed active to its end$/);
  });

  it('marks it on the schema\'s row of a recorded run\'s replay, in contract trace\'s words, after the last record', () => {
    const model = built(recordedRunSteps(logs, 7, { checkpointEvery: 16 }));
    const marks = model.marks.filter((m) => UNSERVED.test(m.label));
    expect(marks).toEqual([{ t: model.end, kind: 'schema', where: 'schemaCommande1', label: told!.replace(/^\S+ ORD {2}/, '') }]);
  });

  it('follows a live run without marking it while the job goes on (an undo in flight), and marks it when the job ends', async () => {
    const lines: TraceLine[] = logs.flatMap((f) => f.text.split('\n').map((text, i) => ({ file: f.name, line: i + 1, text })))
      .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
    let sendEnd!: () => void;
    server = new WebSocketServer({ port: 0, host: '127.0.0.1' });
    server.on('connection', (ws) => {
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(lines) }));
      sendEnd = () => ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: false, message: 'run failed' } }));
    });
    await new Promise((r) => server!.once('listening', r));
    const url = `ws://127.0.0.1:${(server.address() as { port: number }).port}/api/jobs/j/ws?trace=only`;
    let follower!: LiveFollower;
    const port: FollowerPort = { postMessage: (m: ToFollower) => queueMicrotask(() => follower.handle(structuredClone(m))), onmessage: null };
    follower = new LiveFollower((m) => {
      const copy = structuredClone(m);
      setTimeout(() => port.onmessage?.({ data: copy } as MessageEvent<FromFollower>), 0);
    }, (u) => new WebSocket(u) as unknown as SocketLike, 0);
    const remote = new RemoteMonitorModel(port, url);
    await expect.poll(() => remote.recordCount, { timeout: 10_000 }).toBe(lines.length);
    // every record is in, SUP's exit after the undo among them: still live, no undo said unserved
    await new Promise((r) => setTimeout(r, 100));
    expect(remote.ended).toBe(false);
    expect(remote.marks.filter((m) => UNSERVED.test(m.label))).toEqual([]);
    sendEnd();
    await Promise.race([remote.settled, new Promise((_, no) => setTimeout(() => no(new Error('not settled')), 10_000))]);
    expect(remote.marks.filter((m) => UNSERVED.test(m.label)).map((m) => [m.where, m.label])).toEqual([['schemaCommande1', told!.replace(/^\S+ ORD {2}/, '')]]);
  });

  it('marks live, at ORD\'s exit record, an undo that reached its mailbox after its last read of it', () => {
    const model = new MonitorModel();
    const bse = (l: string) => model.pushLine('BSE_1.csv', 2, l);
    const ord = (l: string) => model.pushLine('ORD_1.csv', 2, l);
    bse('1000000000,w,BSE,supervisor,ORD,,0,"activate schema fastLoop() (activation #4, to ORD)"');
    ord('1000100000,w,ORD,scheduler,,,0,activate fastLoop (activation #4 from BSE)');
    bse('6000000000,w,BSE,request_received,contract-launch,,0,KILL');
    bse('6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"');
    expect(model.marks.filter((m) => UNSERVED.test(m.label))).toEqual([]);
    ord('6000000300,w,ORD,module_exit,,,0,status=0 records=3');
    const story = renderStory(parseTrace([{ name: 'BSE_1.csv', text: [CSV_HEADER, '1000000000,w,BSE,supervisor,ORD,,0,"activate schema fastLoop() (activation #4, to ORD)"',
      '6000000000,w,BSE,request_received,contract-launch,,0,KILL', '6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"', ''].join('\n') },
    { name: 'ORD_1.csv', text: [CSV_HEADER, '1000100000,w,ORD,scheduler,,,0,activate fastLoop (activation #4 from BSE)', '6000000300,w,ORD,module_exit,,,0,status=0 records=3', ''].join('\n') }]));
    const words = story.find((l) => l.includes('ORD  exited'))!.replace(/^.*records=3\); /, '');
    expect(words).toMatch(/^while the run stopped: ORD ended before it served BSE's undo/);
    expect(model.marks.filter((m) => UNSERVED.test(m.label))).toEqual([{ t: 5_000_000_300, kind: 'schema', where: 'fastLoop', label: words }]);
  });
});
