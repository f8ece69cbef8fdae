import { describe, it, expect } from 'vitest';
import { parseTrace, StoryTeller, type LogFile } from '@contract-studio/build-service/trace';
import { recordedRunSteps } from './recorded-run.js';
import { recordCounts, recordCountsText, unreadableNote } from './record-counts.js';
import { csvLogsRunLabel } from './live-run-label.js';
import type { MonitorModel } from './monitor-model.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const W = '2026-11-26T12:00:00.000000Z';
/** A run's logs with unreadable lines: 4 records, 3 lines that are no record (one cut by a writer stopped mid-line). */
const logs: LogFile[] = [
  { name: 'SUP_1.csv', text: [HEADER, `1000000000,${W},SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000ns`, '\u00ff\u00fe junk', `1500000000,${W},SUP,supervisor,,,0,function action started`, ''].join('\n') },
  { name: 'ORD_1.csv', text: [HEADER, `1200000000,${W},ORD,scheduler,,,0,activate S`, 'not,a,record', `1300000000,${W},ORD,ord_deadline_miss,,,0,schema=S cycle=0 tick_ns=1`, '1400000000,w,ORD,sched'].join('\n') },
];

function monitorOf(files: LogFile[]): MonitorModel {
  const steps = recordedRunSteps(files, 1000);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

describe("a recorded run's counts in the Monitor, as contract trace counts them", () => {
  it('counts the readable records, the unreadable lines apart: the numbers of the story contract trace prints', () => {
    const teller = new StoryTeller(); // what `contract trace LOGDIR` tells, record by record
    for (const r of parseTrace(logs)) teller.tell(r);
    const model = monitorOf(logs);
    expect(recordCounts(model)).toEqual({ records: 4, unreadable: 3 });
    expect(teller.recordCounts).toEqual(recordCounts(model));
    expect(teller.summary()).toMatch(/^4 records: .*, 3 unreadable lines$/);
    expect(recordCountsText(recordCounts(model))).toBe('4 record(s), 3 unreadable line(s)');
    // the model still holds every line (its size: the memory bounds)
    expect(model.recordCount).toBe(7);
  });

  it('says them in the labels of a log folder or a job\'s CSV logs when some lines are unreadable, and a trace file\'s carried ones', () => {
    const counts = recordCounts(monitorOf(logs));
    expect(unreadableNote(counts)).toBe(' · 4 record(s), 3 unreadable line(s)');
    expect(csvLogsRunLabel('j-1', ['MSC_1.csv capped'], 'succeeded', counts)).toBe('Build & Run job j-1 · CSV logs · 4 record(s), 3 unreadable line(s) (not whole: MSC_1.csv capped) · ended: succeeded');
    // whole logs: the label counts nothing, as before
    const clean = recordCounts(monitorOf([{ name: 'ORD_1.csv', text: `${HEADER}\n1200000000,${W},ORD,scheduler,,,0,activate S\n` }]));
    expect(clean).toEqual({ records: 1, unreadable: 0 });
    expect(unreadableNote(clean)).toBe('');
    expect(csvLogsRunLabel('j-1', [], undefined, clean)).toBe('Build & Run job j-1 · CSV logs');
    // a trace file: the unreadable lines of the logs it was written from, which it carries, counted with the model's
    expect(recordCountsText(recordCounts(monitorOf(logs), 2))).toBe('4 record(s), 5 unreadable line(s)');
    expect(recordCountsText({ records: 12_345, unreadable: 0 })).toBe('12,345 record(s)');
  });
});
