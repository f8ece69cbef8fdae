import { describe, expect, it } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { supervisorRows, type SupervisorCatalogue } from './supervisor-rows.js';

const W = '2026-12-05T10:00:00.000000Z';

/** A recorded run of SUP (action: FIRST, then SECOND) and of GLB (mission: SINGLE). */
function run(): MonitorModel {
  const m = new MonitorModel({ checkpointEvery: 4 });
  const lines = [
    `1000,${W},SUP,supervisor,,,0,function action started`,
    `1001,${W},SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns`,
    `1002,${W},SUP,sup_rule,,,0,action.SECOND active cause=started(FIRST)`,
    `1003,${W},GLB,supervisor,,,0,function mission started`,
    `1004,${W},GLB,sup_rule,,,0,mission.SINGLE active cause=elapsed=1000000ns`,
  ];
  lines.forEach((l, i) => m.push(parseRecordLine('SUP.csv', i + 2, l)));
  return m;
}

describe("the Monitor's supervisor rows against the model", () => {
  it('mark what the run names and the model no longer has: a renamed rule, a removed function', () => {
    // since the run, SECOND was renamed SECOND_X; GLB's function is now called mission2
    const model: SupervisorCatalogue = new Map([
      ['SUP', new Map([['action', ['FIRST', 'SECOND_X']]])],
      ['GLB', new Map([['mission2', ['SINGLE']]])],
    ]);
    const [glb, sup] = supervisorRows(model, run().live);
    expect(sup!.functions.get('action')).toEqual(['FIRST', 'SECOND_X', 'SECOND']);
    expect([...sup!.notInModel]).toEqual(['action.SECOND']);
    expect(sup!.inModel).toBe(true);
    expect([...glb!.functions.keys()]).toEqual(['mission2', 'mission']);
    expect([...glb!.notInModel].sort()).toEqual(['mission', 'mission.SINGLE']);
  });

  it('mark a supervisor the model does not have, and every function and rule of it', () => {
    const model: SupervisorCatalogue = new Map([['SUP', new Map([['action', ['FIRST', 'SECOND']]])]]);
    const [glb, sup] = supervisorRows(model, run().live);
    expect(glb!.inModel).toBe(false);
    expect([...glb!.notInModel].sort()).toEqual(['mission', 'mission.SINGLE']);
    expect(sup!.inModel).toBe(true);
    expect(sup!.notInModel.size).toBe(0);
  });

  it('mark a supervisor renamed since the run: the run\'s name and all of it, after the model\'s new name', () => {
    // since the run, SUP was renamed SUP2 (same functions and rules)
    const model: SupervisorCatalogue = new Map([
      ['SUP2', new Map([['action', ['FIRST', 'SECOND']]])],
      ['GLB', new Map([['mission', ['SINGLE']]])],
    ]);
    const rows = supervisorRows(model, run().live);
    expect(rows.map((r) => [r.name, r.inModel, [...r.notInModel].sort()])).toEqual([
      ['GLB', true, []],
      ['SUP', false, ['action', 'action.FIRST', 'action.SECOND']],
      ['SUP2', true, []],
    ]);
    expect(rows[1]!.functions).toEqual(new Map([['action', ['FIRST', 'SECOND']]]));
  });

  it('mark nothing while the model names no supervisor (not read yet, or the logs of another project)', () => {
    const rows = supervisorRows(new Map(), run().live);
    expect(rows.map((r) => [r.name, r.inModel, r.notInModel.size])).toEqual([
      ['GLB', undefined, 0],
      ['SUP', undefined, 0],
    ]);
  });
});
