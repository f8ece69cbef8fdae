import { describe, it, expect } from 'vitest';
import { activationsFromCsv, inferPeriod, parseCsvLine } from './activation-log.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';

describe('activation log', () => {
  it('parses quoted CSV fields', () => {
    expect(parseCsvLine('1,"a,b","say ""hi""",,x')).toEqual(['1', 'a,b', 'say "hi"', '', 'x']);
  });

  it('pairs run_started with run_finished per module and infers the period', () => {
    const rows = [HEADER];
    for (let k = 0; k < 5; k++) {
      rows.push(`${k * 1000 + 10},w,MSC,run_started,ORD,,0,`);
      rows.push(`${k * 1000 + 60},w,MSC,request_received,ORD,,0,`);
      rows.push(`${k * 1000 + 90},w,MSC,run_finished,,,0,"exec done, ok"`);
    }
    rows.push('5010,w,MSC,run_started,ORD,,0,');
    const acts = activationsFromCsv(rows.join('\n'));
    expect(acts).toHaveLength(6);
    expect(acts[0]).toMatchObject({ module: 'MSC', start: 10, end: 90 });
    expect(acts[5]!.end).toBeUndefined();
    expect(inferPeriod(acts)).toBe(1000);
  });

  it('refuses a file that is not a runtime log', () => {
    expect(() => activationsFromCsv('a,b,c\n1,2,3')).toThrow(/not a ContrACT CSV log/);
  });
});
