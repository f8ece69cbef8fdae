/**
 * Why the build service stopped a run (its limit, its run time limit, a cancel): contract-launch
 * sends the reason with every module's KILL (`KILL (the build service's memory limit was
 * reached)`), and the Monitor marks the first of them on its strip, in contract trace's words, in
 * each of the three ways it reads a run.
 */
import { describe, expect, it } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { recordedRunSteps } from './recorded-run.js';

const W = '2026-12-06T06:00:00.000000Z';
const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const WHY = "the build service's memory limit was reached";
const log = [
  `1000000000,${W},MAA,module_started,,,0,pid=7 priority=50`,
  `1000000100,${W},MSC,module_started,,,0,pid=8 priority=50`,
  // a KILL from another sender, and a plain one, mark nothing
  `1500000000,${W},MSC,request_received,SUP,,20,KILL (not the launcher)`,
  `1600000000,${W},MAA,request_received,contract-launch,,0,KILL`,
  `3000000000,${W},MAA,request_received,contract-launch,,45,KILL (${WHY})`,
  `3000000500,${W},MSC,request_received,contract-launch,,45,KILL (${WHY})`,
  `3000001000,${W},MAA,module_exit,,,0,status=0 records=4`,
];

function models(): MonitorModel[] {
  const live = new MonitorModel();
  log.forEach((l, i) => live.pushLine('X.csv', i + 2, l));
  const parsed = new MonitorModel();
  parsed.pushAll(log.map((l, i) => parseRecordLine('X.csv', i + 2, l)));
  const steps = recordedRunSteps([{ name: 'X_1.csv', text: `${HEADER}\n${log.join('\n')}\n` }], 1000);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return [live, parsed, step.value.model];
}

describe('the run\'s stop by the build service', () => {
  it('is marked once, at the first KILL saying why, in contract trace\'s words', () => {
    for (const m of models()) {
      expect(m.marks.filter((k) => k.kind === 'error')).toEqual([{ t: 2_000_000_000, kind: 'error', where: 'MAA', label: `asked to stop by contract-launch: ${WHY}` }]);
    }
  });
});
