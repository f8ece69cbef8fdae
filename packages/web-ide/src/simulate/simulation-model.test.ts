/**
 * The Simulate panel's simulation in the Monitor (simulation-model.ts) ends its records as a
 * finished run's are ended: the Deliveries' closing row (`a simulation runs no module code: …`,
 * the line `contract trace` of the simulation's trace file ends its flows with) is there, where
 * before the panel's model was never ended and showed no closing row at all; a schema still
 * active at the session's time stays active (its ORD did not end), and a session whose end
 * deactivated its schemas says which, when and why under Active schemas, not a bare `none`.
 * Steps: real POST /api/simulate answers (scripts/record-mission-steps.mjs) of examples/tutorial's
 * scenarios/mission.scenario (fixtures/tutorial-mission-steps.json: SUP.action stopped at 1 s, its
 * schemas deactivated) and of monitor/fixtures/simulated-flows/flows.scenario
 * (fixtures/tutorial-flows-steps.json: schemaCommande1's data flows connected from 1.5 s to the
 * end, 3.5 s; its trace file is that folder's flows.jsonl).
 */
import { describe, it, expect } from 'vitest';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import type { SimulateStep } from '../../server/api-types.js';
import { activeSchemas, type SchemaInfo } from '../monitor/active-schemas.js';
import { noActiveSchemaText } from '../monitor/panel-text.js';
import { simulationModel } from './simulation-model.js';

const stepsOf = (name: string) => JSON.parse(readFileSync(fileURLToPath(new URL(`./fixtures/${name}`, import.meta.url)), 'utf8')) as SimulateStep[];
const steps = stepsOf('tutorial-mission-steps.json');
const flowSteps = stepsOf('tutorial-flows-steps.json');
const CATALOGUE: SchemaInfo[] = [
  { name: 'schemaReceptionMessage', kind: 'event', modules: ['MAA', 'MAB'] },
  { name: 'schemaCommande1', kind: 'periodic', modules: ['MSA', 'MSC', 'MSD'] },
  { name: 'schemaCommande2', kind: 'periodic', modules: ['MSA', 'MSB', 'MSC', 'MSD'] },
];
/** The steps of the session up to (and with) its step at `t`: the session as it stood then. */
const upTo = (t: number) => steps.filter((s) => s.timeNs <= t && s.kind !== 'end');

describe("the Simulate panel's simulation in the Monitor", () => {
  it('ends its records: the Deliveries closing row a run ends with, as contract trace ends the same simulation', () => {
    const m = simulationModel(flowSteps, 3.5e9);
    expect(m.live.quietDataFlows).toEqual([
      'a simulation runs no module code: data values are not simulated, nor the events its modules post: what 2 data flows and 1 event flow connected over 1 s delivered is not told',
    ]);
    // at the session's end, schemaCommande1 (SECOND's, from 1.5 s) still runs: shown active, no ORD end marked
    expect(activeSchemas(m.live, CATALOGUE)).toEqual([{ name: 'schemaCommande1', kind: 'periodic', by: 'SUP.action.SECOND' }]);
    expect(m.marks.filter((k) => /ORD gone/.test(k.label))).toEqual([]);
  });

  it('keeps a schema active at the session\'s time active (no ORD end at the last record)', () => {
    // the session at 500 ms: SECOND's schemaCommande1 runs
    const m = simulationModel(upTo(500e6), 500e6);
    expect(m.end).toBe(500e6);
    expect(activeSchemas(m.live, CATALOGUE)).toEqual([{ name: 'schemaCommande1', kind: 'periodic', by: 'SUP.action.SECOND' }]);
    expect(m.marks.filter((k) => /ORD gone/.test(k.label))).toEqual([]);
  });

  it('a session whose end deactivated its schemas says which, when and why, not a bare none', () => {
    const m = simulationModel(steps, 3e9);
    expect(activeSchemas(m.live, CATALOGUE)).toEqual([]);
    expect(noActiveSchemaText(m.live)).toBe('none · schemaCommande2 (periodic) deactivated by ORD at +1.000000 s: SUP.action.FOURTH, which activated it, became inactive ← its function stopped');
  });
});
