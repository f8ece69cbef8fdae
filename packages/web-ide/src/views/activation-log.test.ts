import { describe, it, expect } from 'vitest';
import { splitCsvLine } from '@contract-studio/build-service/trace';
import { activationsFromCsv, inferPeriodOf } from './activation-log.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';

describe('activation log', () => {
  it('parses quoted CSV fields', () => {
    expect(splitCsvLine('1,"a,b","say ""hi""",,x')).toEqual(['1', 'a,b', 'say "hi"', '', 'x']);
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
    expect(inferPeriodOf(acts)?.ns).toBe(1000);
  });

  it('reads the period of the most active module, and names it (loops of several periods)', () => {
    const act = (module: string, start: number) => ({ module, start, end: start + 5, detail: '' });
    const acts = [...[0, 10, 20, 30, 40, 50].map((t) => act('FST', t)), ...[0, 50].map((t) => act('SLW', t))];
    expect(inferPeriodOf(acts)).toEqual({ ns: 10, module: 'FST' });
    expect(inferPeriodOf(acts.slice(0, 2))).toBeUndefined();
  });

  it('refuses a file that is not a runtime log', () => {
    expect(() => activationsFromCsv('a,b,c\n1,2,3')).toThrow(/not a ContrACT CSV log/);
  });
});

describe('activation log from a real tutorial run (runtime CSV excerpt)', () => {
  const csv = [
    HEADER,
    '5518146784649,2026-11-21T23:48:48.685592Z,MSC,module_started,,,0,pid=6981 priority=84',
    '5518147186959,2026-11-21T23:48:48.685995Z,MSC,memory_lock,,,0,"mlockall(MCL_CURRENT|MCL_FUTURE), 256 KiB of stack prefaulted"',
    '5518900442459,2026-11-21T23:48:49.439250Z,MSC,request_received,SUP,0,24,SETPARAM',
    '5520151929160,2026-11-21T23:48:50.690737Z,MSC,run_started,ORD,,0,activation=1',
    '5520151960477,2026-11-21T23:48:50.690768Z,MSC,run_finished,,,0,activation=1 ACK_FINISHED',
  ].join('\n');
  it('keeps quoted details with commas and pairs the activation', () => {
    const acts = activationsFromCsv(csv);
    expect(acts).toEqual([{ module: 'MSC', start: 5520151929160, end: 5520151960477, detail: 'activation=1' }]);
  });
});

describe('activation log of the engines (ORD and supervisors serve several activations at once)', () => {
  it('ORD is active while a schema is, whatever its run records say (one supervisor\'s STOP ended "its run" while another\'s schema went on)', () => {
    const csv = [
      HEADER,
      '100,w,ORD,run_started,SFT,,0,activation=1',
      '101,w,ORD,scheduler,,,0,activate conveyorLoop (activation #1 from SFT)',
      '200,w,ORD,scheduler,,,0,activate pickLoop (activation #2 from PRD)',
      '300,w,ORD,run_finished,PRD,,0,activation=2 cpu_ns=41000 STOP',
      '301,w,ORD,scheduler,,,0,deactivate pickLoop (activation #2 from PRD)',
      '450,w,ORD,run_started,PRD,,0,activation=3',
      '451,w,ORD,scheduler,,,0,activate degradedLoop',
      '500,w,ORD,scheduler,,,0,deactivate conveyorLoop (activation #1 from SFT)',
      '600,w,ORD,scheduler,,,0,deactivate degradedLoop',
      '700,w,ORD,scheduler,,,0,activate pickLoop (activation #4 from PRD)',
    ].join('\n');
    expect(activationsFromCsv(csv).map((a) => [a.module, a.start, a.end])).toEqual([['ORD', 101, 600], ['ORD', 700, undefined]]);
  });

  it('a supervisor is active while one of its functions runs; a module\'s own run records still make its bars', () => {
    const csv = [
      HEADER,
      '10,w,SFT,run_started,contract-launch,,0,activation=1',
      '11,w,SFT,supervisor,,,0,function cell() started',
      '20,w,SFT,supervisor,SAF,,0,subscribe SAF:0 =* :0 (activation #1)',
      '30,w,SFT,supervisor,,,0,function aux(n = 2) started',
      '40,w,SFT,run_finished,contract-launch,,0,activation=2 cpu_ns=41000 STOP',
      '41,w,SFT,supervisor,,,0,function aux stopped',
      '90,w,SFT,supervisor,,,0,function cell stopped',
      '50,w,MSC,run_started,ORD,,0,activation=1',
      '60,w,MSC,run_finished,,,0,activation=1 cpu_ns=41000 ACK_FINISHED',
    ].join('\n');
    expect(activationsFromCsv(csv).map((a) => [a.module, a.start, a.end])).toEqual([['SFT', 11, 90], ['MSC', 50, 60]]);
  });
});
