/**
 * What the flows did, told as `contract trace` tells it: an event flood (fixtures/event-flood-run:
 * PSH posts every 1 ms, BIN takes 20 ms an event) warned on its Deliveries row and marked where its
 * first waits happen; data flows that delivered nothing or far less than read (fixtures/silent-flow-run)
 * and an event flow a supervisor connected that delivered nothing (fixtures/silent-event-flow-run)
 * told at the records' end. Replayed from the real logs, and fed line by line as a live run is.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseTrace, renderStory, type LogFile } from '@contract-studio/build-service/trace';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import { MonitorModel } from './monitor-model.js';
import { flowWaitText, flowWaitTitle, quietDataFlowRow } from './panel-text.js';

function logsOf(name: string): LogFile[] {
  const dir = fileURLToPath(new URL(`./fixtures/${name}`, import.meta.url));
  return readdirSync(dir).filter((n) => n.endsWith('.csv')).map((n) => ({ name: n, text: readFileSync(join(dir, n), 'utf8') }));
}

function replayed(logs: LogFile[], whole = true): MonitorModel {
  const steps: Generator<void, RecordedRun> = recordedRunSteps(logs, 7, { checkpointEvery: 64 }, undefined, undefined, whole);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

/** The logs' lines fed in time order, each with its log and line, as the live trace channel brings them. */
function fedLive(logs: LogFile[]): MonitorModel {
  const lines = logs.flatMap((f) => f.text.split('\n').map((text, i) => ({ file: f.name, line: i + 1, text, mono: /^\d+,/.test(text) ? BigInt(text.split(',')[0]!) : -1n })))
    .filter((l) => l.mono >= 0n).sort((a, b) => (a.mono < b.mono ? -1 : a.mono > b.mono ? 1 : 0));
  const model = new MonitorModel({ checkpointEvery: 64 });
  for (const l of lines) model.pushLine(l.file, l.line, l.text);
  return model;
}

const FIRST_WAIT = "events PSH:0 -> BIN:0 waited for room in BIN's full mailbox 5 times in 1.18 s (1.127 s in all, up to 244.19 ms each): " +
  'BIN takes its events slower than PSH posts them; later waits are counted at the end';
const SILENT = 'data flow SRT:1 -> BLT:0 connected for 3.705 s (schema sortLoop): 0 values delivered (SRT posted none on its output :1); BLT read nothing in its 529 releases';
const SPARSE = 'data flow CAM:0 -> SRT:0 connected for 3.705 s (schema sortLoop): 26 values delivered (7 a second), read 26 times in SRT\'s 529 releases (140 a second): 1 value for 20 releases';

/** `contract trace`'s closing line for the flow: its waits over all six streaks, its longest delivery latency. */
const CLOSING = renderStory(parseTrace(logsOf('event-flood-run'))).find((l) => l.startsWith("PSH's events to BIN"))!;
const STREAKS = logsOf('event-flood-run').flatMap((f) => f.text.split('\n')).filter((l) => l.includes(',event_waited,'));

describe('an event flood (fixtures/event-flood-run)', () => {
  const logs = logsOf('event-flood-run');
  it("trace's closing line counts its six streaks", () => {
    expect(STREAKS).toHaveLength(6);
    expect(CLOSING).toBe("PSH's events to BIN (PSH:0 -> BIN:0) waited for room 24 times (5.767 s in all, up to 298.552 ms): BIN takes its events slower than PSH posts them; delivery latency up to 540.627 ms");
  });
  for (const [how, model] of [['replayed', replayed(logs)], ['fed live', fedLive(logs)]] as const) {
    it(`${how}: a mark at the first streak of waits; PSH:0 -> BIN:0's Deliveries row has the totals over every streak so far, trace's closing line its title`, () => {
      const marks = model.marks.filter((m) => m.kind === 'waited');
      expect(marks.map((m) => ({ where: m.where, label: m.label }))).toEqual([{ where: 'PSH', label: FIRST_WAIT }]);
      expect(Math.floor(marks[0]!.t / 1000)).toBe(1_455_710); // +1.455710 s, where trace tells it
      const flow = model.live.eventFlows.get('PSH:0->BIN:0')!;
      expect(flow.waits).toBe(24);
      expect(flowWaitText(flow)).toBe(' · ⚠ waited for room 24 times (5.767 s in all, up to 298.552 ms)');
      expect(flowWaitTitle('PSH:0->BIN:0', flow)).toBe(CLOSING);
      // before the first streak the row has no warning; at it, that streak's; at the second, both (a scrub back tells the same)
      const before = model.stateAt(marks[0]!.t - 1)!.eventFlows.get('PSH:0->BIN:0');
      expect(before ? flowWaitText(before) : '').toBe('');
      expect(flowWaitText(model.stateAt(marks[0]!.t)!.eventFlows.get('PSH:0->BIN:0')!)).toBe(' · ⚠ waited for room 5 times (1.127 s in all, up to 244.19 ms)');
      const second = model.stateAt(marks[0]!.t + 1_249_339_734)!.eventFlows.get('PSH:0->BIN:0')!; // the second streak's record, 1.249339734 s after the first
      expect(flowWaitText(second)).toBe(' · ⚠ waited for room 10 times (2.309 s in all, up to 263.038 ms)');
      expect(flowWaitTitle('PSH:0->BIN:0', second)).toMatch(/^PSH's events to BIN \(PSH:0 -> BIN:0\) waited for room 10 times \(2\.309 s in all, up to 263\.038 ms\): BIN takes its events slower than PSH posts them; delivery latency up to /);
    });
  }
  it('a flow that did not wait has no warning and no title', () => {
    expect(flowWaitText({ count: 3, last: 0 })).toBe('');
    expect(flowWaitTitle('A:0->B:0', { count: 3, last: 0 })).toBe('');
  });
});

describe('data flows that delivered nothing or far less than read (fixtures/silent-flow-run)', () => {
  const logs = logsOf('silent-flow-run');

  it('a whole replay tells them at its end, in trace\'s words', () => {
    const model = replayed(logs);
    expect(model.live.quietDataFlows).toEqual([SPARSE, SILENT]);
    expect(quietDataFlowRow(SILENT)).toBe(`━ ⚠ ${SILENT}`);
  });

  it('a replay of logs read in part tells none (their end is not the run\'s)', () => {
    expect(replayed(logs, false).live.quietDataFlows).toEqual([]);
  });

  it('live: none while the run goes on, the same lines once the job ended', () => {
    const model = fedLive(logs);
    expect(model.live.quietDataFlows).toEqual([]);
    model.recordsEnded();
    expect(model.live.quietDataFlows).toEqual([SPARSE, SILENT]);
  });
});

describe('an event flow a supervisor connected that delivered nothing (fixtures/silent-event-flow-run, a real bwrap run)', () => {
  const logs = logsOf('silent-event-flow-run');
  const SILENT_EVENTS = "event flow PRD:0 =* CNS:0 connected for 3.002 s (schema relay, connected by MIS's rule mission.RELAY): " +
    '0 events delivered (PRD posted none on its output :0); CNS received nothing';

  it('a whole replay tells it at its end, with who connected it, in trace\'s words', () => {
    expect(replayed(logs).live.quietDataFlows).toEqual([SILENT_EVENTS]);
  });

  it('live: none while the run goes on, the same line once the job ended', () => {
    const model = fedLive(logs);
    expect(model.live.quietDataFlows).toEqual([]);
    model.recordsEnded();
    expect(model.live.quietDataFlows).toEqual([SILENT_EVENTS]);
  });
});
