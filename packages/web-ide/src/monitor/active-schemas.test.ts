/**
 * The schema the Monitor's diagram follows (docs/watching-a-run.md: "the schema that became active
 * last"): by activation time, not by the model's order of the schemas, and an event schema by the
 * rule that holds its modules.
 */
import { describe, it, expect } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { activeSchemas, lastActivated, type SchemaInfo } from './active-schemas.js';

const W = '2026-12-05T12:00:00.000000Z';
const line = (ms: number, module: string, event: string, peer: string, detail: string) =>
  parseRecordLine('x.csv', 2, `${ms * 1_000_000},${W},${module},${event},${peer},,0,${detail}`);
const MS = 1_000_000;

// the model lists them by name: not the order ORD activates them in
const CATALOGUE: SchemaInfo[] = [
  { name: 'localisationLoop', kind: 'periodic', modules: ['LOC'] },
  { name: 'obstacleWatch', kind: 'periodic', modules: ['OBS'] },
  { name: 'sensing', kind: 'event', modules: ['CAM'] },
  { name: 'velocityLoop', kind: 'periodic', modules: ['VEL'] },
];

function run() {
  const m = new MonitorModel({ checkpointEvery: 2 });
  m.pushAll([
    line(1, 'ORD', 'module_started', '', 'pid=1 priority=90'),
    line(10, 'ORD', 'scheduler', '', 'activate obstacleWatch'),
    line(20, 'ORD', 'scheduler', '', 'activate velocityLoop'),
    line(30, 'ORD', 'scheduler', '', 'activate localisationLoop'),
    line(40, 'ORD', 'scheduler', '', 'deactivate velocityLoop'),
    line(50, 'ORD', 'scheduler', '', 'activate velocityLoop'),
    line(60, 'CEL', 'sup_rule', '', 'run.WATCH active cause=elapsed=1000000ns'),
    line(61, 'CEL', 'module_hold', 'CAM', 'hold taken'),
    line(70, 'ORD', 'scheduler', '', 'deactivate localisationLoop'),
  ]);
  return (ms: number) => {
    const s = m.stateAt(ms * MS - 1)!;
    return lastActivated(s, activeSchemas(s, CATALOGUE));
  };
}

describe('lastActivated', () => {
  it('follows the schema activated last, whatever the model lists last', () => {
    const at = run();
    expect(at(5)).toBeUndefined();
    expect(at(15)).toBe('obstacleWatch');
    expect(at(25)).toBe('velocityLoop');
    expect(at(35)).toBe('localisationLoop');
    // velocityLoop stopped: the latest of those still active
    expect(at(45)).toBe('localisationLoop');
    expect(at(55)).toBe('velocityLoop');
  });

  it('an event schema counts from when the rule holding its modules became active', () => {
    const at = run();
    expect(at(65)).toBe('sensing');
    expect(at(75)).toBe('sensing');
  });
});
