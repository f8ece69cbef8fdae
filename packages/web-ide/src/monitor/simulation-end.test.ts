/**
 * The end of a simulation's trace file replayed in the Monitor (`contract simulate --trace`, a
 * click on the file). A simulation's ORD writes no exit record: before, the replay's end was taken
 * for ORD's log ending without one (killed?), its periodic schemas were shown ended at the last
 * record (`ORD gone: … shown ended here`) and Active schemas said `none` though the simulation's
 * last schema was still active. Now the end shows what was active, as a run's replay shows what its
 * records leave active; and where the end did deactivate (a run's stop, a simulation's `stop` or
 * its supervisor stopped), Active schemas says which schema ended, when and why, not a bare `none`.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { traceFileToLogs, type LogFile } from '@contract-studio/build-service/trace';
import { stepsToTrace } from '@contract-studio/simulator/trace';
import type { SimulateStep } from '../../server/api-types.js';
import { recordedRunSteps, type RecordedRun } from './recorded-run.js';
import type { MonitorModel } from './monitor-model.js';
import { activeSchemas, type SchemaInfo } from './active-schemas.js';
import { noActiveSchemaText } from './panel-text.js';

const fixture = (path: string) => fileURLToPath(new URL(`./fixtures/${path}`, import.meta.url));
const CATALOGUE: SchemaInfo[] = [
  { name: 'schemaReceptionMessage', kind: 'event', modules: ['MAA', 'MAB'] },
  { name: 'schemaCommande1', kind: 'periodic', modules: ['MSA', 'MSC', 'MSD'] },
  { name: 'schemaCommande2', kind: 'periodic', modules: ['MSA', 'MSB', 'MSC', 'MSD'] },
];

function built(steps: Generator<void, RecordedRun>): MonitorModel {
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

/** A trace file replayed as MonitorController.openTraceFile replays one (a simulation's when its reader found a sim_start). */
function replayedFile(name: string, text: string): MonitorModel {
  const t = traceFileToLogs(name, text);
  expect(t.simulation).toBeDefined();
  return built(recordedRunSteps(t.files, 7, { checkpointEvery: 16, simulation: t.simulation !== undefined }, undefined, t.order));
}

describe("a simulation's trace file replayed: its end", () => {
  it('shows the schema still active at the simulation\'s end active, with no ORD end marked (fixtures/simulated-flows)', () => {
    const m = replayedFile('flows.jsonl', readFileSync(fixture('simulated-flows/flows.jsonl'), 'utf8'));
    expect(m.end).toBe(3.5e9);
    expect(activeSchemas(m.live, CATALOGUE)).toEqual([{ name: 'schemaCommande1', kind: 'periodic', by: 'SUP.action.SECOND' }]);
    expect(m.live.schemas.get('schemaCommande1')).toMatchObject({ active: true, since: 1.5e9 });
    expect(m.marks.filter((k) => /ORD gone/.test(k.label))).toEqual([]);
    // the flows' closing row is still told at the end (the records did end)
    expect(m.live.quietDataFlows).toHaveLength(1);
  });

  it('says in words which schema the end deactivated, when and why (examples/tutorial mission.scenario: GLB stops SUP.action)', () => {
    const steps = JSON.parse(readFileSync(fileURLToPath(new URL('../simulate/fixtures/tutorial-mission-steps.json', import.meta.url)), 'utf8')) as SimulateStep[];
    const text = stepsToTrace(steps, 'scenarios/mission.scenario').map((r) => JSON.stringify(r)).join('\n') + '\n';
    const m = replayedFile('mission.jsonl', text);
    expect(activeSchemas(m.live, CATALOGUE)).toEqual([]);
    expect(noActiveSchemaText(m.live)).toBe('none · schemaCommande2 (periodic) deactivated by ORD at +1.000000 s: SUP.action.FOURTH, which activated it, became inactive ← its function stopped');
    // earlier, at 500 ms: FIRST's event schema undone by SECOND's disconnection, schemaCommande1 active
    expect(activeSchemas(m.stateAt(500e6), CATALOGUE)).toEqual([{ name: 'schemaCommande1', kind: 'periodic', by: 'SUP.action.SECOND' }]);
    expect(m.stateAt(500e6).lastEnded).toMatchObject({ name: 'schemaReceptionMessage', kind: 'event', how: 'undone', by: 'SUP.action.FIRST' });
    // before anything ended: a bare none
    expect(noActiveSchemaText(m.stateAt(0))).toBe('none');
  });
});

describe("a real run's replay: its end", () => {
  function replayedLogs(name: string): MonitorModel {
    const logs: LogFile[] = readdirSync(fixture(name)).filter((n) => n.endsWith('.csv')).map((n) => ({ name: n, text: readFileSync(join(fixture(name), n), 'utf8') }));
    return built(recordedRunSteps(logs, 7, { checkpointEvery: 64 }));
  }

  it('the run\'s stop deactivated its schema: said under Active schemas (fixtures/tutorial-run)', () => {
    const m = replayedLogs('tutorial-run');
    expect(activeSchemas(m.live, CATALOGUE)).toEqual([]);
    expect(noActiveSchemaText(m.live)).toMatch(/^none · schemaCommande1 \(periodic\) deactivated by ORD at \+\d+\.\d{6} s: SUP\.action\.SECOND, which activated it, became inactive ← its function stopped$/);
  });

  it('ORD killed with no exit record: its schemas shown ended at its last record, and said so (fixtures/killed-ord-run)', () => {
    const m = replayedLogs('killed-ord-run');
    expect(m.live.lastEnded?.how).toBe('ord-gone');
    expect(noActiveSchemaText(m.live)).toMatch(/^none · \S+ \(periodic\) shown ended at \+\d+\.\d{6} s: ORD's log ends there with no exit record \(killed\?\); whether it ran on is unknown$/);
  });
});
