/**
 * A simulation's trace in the Monitor (fixtures/simulated-flows: `contract simulate --trace` of the
 * tutorial, an event flow connected 1.5 s and two data flows 2 s): its modules ran no code, so no
 * Deliveries row says a flow delivered nothing (before: three ⚠ rows, `MSC never read its input
 * :0: GetData or GetLatestData` and `MAA posted none on its output :0; MAB received nothing` though
 * MAB received the scenario's message); one row without ⚠ says why. Both ways the Monitor reads
 * one: the model fed the simulation's records (the Simulate panel's, with their `sim_start`), and
 * a trace file replayed (its reader skips `sim_start`, the model is told it is a simulation, as
 * MonitorController.openTraceFile does). A real run's logs keep their rows (fixtures/silent-flow-run,
 * fixtures/silent-event-flow-run).
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { recordOfJsonLine, traceFileToLogs, type LogFile, type TraceRecord } from '@contract-studio/build-service/trace';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import { MonitorModel, type MonitorModelOptions } from './monitor-model.js';
import { quietDataFlowRow } from './panel-text.js';

const dir = (name: string) => fileURLToPath(new URL(`./fixtures/${name}`, import.meta.url));
const SIM = readFileSync(join(dir('simulated-flows'), 'flows.jsonl'), 'utf8');
const WHY = 'a simulation runs no module code: data values are not simulated, nor the events its modules post: what 2 data flows and 1 event flow connected over 1 s delivered is not told';
/** The findings of flows that delivered nothing, as `contract trace` words them. */
const SILENT = /never read its input|posted none|received nothing/;

function built(steps: Generator<void, RecordedRun>): MonitorModel {
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

/** The simulation's records pushed as the Simulate panel pushes stepsToTrace's, its sim_start first. */
function fed(): MonitorModel {
  const records = SIM.split('\n').filter(Boolean).map((l, i) => recordOfJsonLine('flows.jsonl', i + 1, l)).filter((r): r is TraceRecord => r !== undefined);
  expect(records[0]?.kind).toBe('sim_start');
  const model = new MonitorModel({ checkpointEvery: 16 });
  model.pushAll(records);
  model.recordsEnded();
  return model;
}

/** The trace file replayed as the Monitor replays one: its logs in the file's order, a simulation when its reader found a sim_start. */
function replayedFile(): MonitorModel {
  const t = traceFileToLogs('flows.jsonl', SIM);
  expect(t.simulation).toBe('flows.scenario');
  const options: MonitorModelOptions = { checkpointEvery: 16, simulation: t.simulation !== undefined };
  return built(recordedRunSteps(t.files, 7, options, undefined, t.order));
}

function replayedLogs(name: string): MonitorModel {
  const logs: LogFile[] = readdirSync(dir(name)).filter((n) => n.endsWith('.csv')).map((n) => ({ name: n, text: readFileSync(join(dir(name), n), 'utf8') }));
  return built(recordedRunSteps(logs, 7, { checkpointEvery: 64 }));
}

describe("a simulation's flows in the Monitor (fixtures/simulated-flows)", () => {
  for (const [how, model] of [['its records fed to the model', fed], ['its trace file replayed', replayedFile]] as const) {
    it(`${how}: no flow told as delivering nothing, one row without ⚠ says why`, () => {
      const m = model();
      // what the old rows were made of is there: MAB received the scenario's message on the flow, the data flows' posts
      expect(m.live.eventFlows.get('MAA:0->MAB:0')?.count).toBe(1);
      expect(m.live.quietDataFlows.filter((l) => SILENT.test(l))).toEqual([]);
      expect(m.live.quietDataFlows).toEqual([WHY]);
      expect(quietDataFlowRow(WHY)).toBe(`━ ${WHY}`);
    });
  }
});

describe("a real run's silent flows keep their ⚠ rows", () => {
  it('fixtures/silent-flow-run and fixtures/silent-event-flow-run', () => {
    const data = replayedLogs('silent-flow-run').live.quietDataFlows;
    expect(data).toEqual([
      "data flow CAM:0 -> SRT:0 connected for 3.705 s (schema sortLoop): 26 values delivered (7 a second), read 26 times in SRT's 529 releases (140 a second): 1 value for 20 releases",
      'data flow SRT:1 -> BLT:0 connected for 3.705 s (schema sortLoop): 0 values delivered (SRT posted none on its output :1); BLT read nothing in its 529 releases',
    ]);
    expect(quietDataFlowRow(data[1]!)).toBe(`━ ⚠ ${data[1]}`);
    expect(replayedLogs('silent-event-flow-run').live.quietDataFlows).toEqual([
      "event flow PRD:0 =* CNS:0 connected for 3.002 s (schema relay, connected by MIS's rule mission.RELAY): 0 events delivered (PRD posted none on its output :0); CNS received nothing",
    ]);
  });
});
