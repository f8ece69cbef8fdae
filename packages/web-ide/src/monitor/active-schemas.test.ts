/**
 * The schema the Monitor's diagram follows (docs/watching-a-run.md: "the schema that became active
 * last"): by activation time, not by the model's order of the schemas, and an event schema by the
 * rule that holds its modules.
 */
import { describe, it, expect } from 'vitest';
import { parseRecordLine, parseTrace, type LogFile } from '@contract-studio/build-service/trace';
import { recordedRunSteps } from './recorded-run.js';
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

/**
 * The rule behind a periodic schema's activation is the one whose action asked ORD for it (the
 * supervisor's own `activate schema S() (activation #N, to ORD)` line), as `contract trace` tells it
 * ("SUP activate schema fast() (activation #1)" right after "rule mission.START active"): not the
 * rule active when ORD's `request_received START S` comes, which may be the supervisor's next one.
 */
describe('the rule an active periodic schema is shown with (← SUP.F.R)', () => {
  const W2 = '2026-12-05T12:00:00.000000Z';
  const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
  const US = 1_000;
  /** SUP's log and ORD's, in the runtime's CSV format; ORD receives START `received` µs into the run. */
  function logs(received: number): LogFile[] {
    const sup = (us: number, event: string, peer: string, detail: string) => `${us * US},${W2},SUP,${event},${peer},,0,${detail}`;
    const ord = (us: number, event: string, peer: string, detail: string) => `${us * US},${W2},ORD,${event},${peer},,0,${detail}`;
    return [
      { name: 'ORD_5-Dec-2026-12h00m00s.csv', text: [HEADER,
        ord(1, 'module_started', '', 'pid=1 priority=90'),
        ord(received, 'request_received', 'SUP', 'START fast'),
        ord(received + 5, 'scheduler', '', 'activate fast (activation #1 from SUP)'),
        ord(received + 10, 'ord_release', 'FST', 'schema=fast cycle=0 release_ns=0'),
        ord(5000, 'module_exit', '', 'status=0'), ''].join('\n') },
      { name: 'SUP_5-Dec-2026-12h00m00s.csv', text: [HEADER,
        sup(2, 'module_started', '', 'pid=2 priority=98'),
        sup(10, 'supervisor', '', 'function mission() started'),
        sup(100, 'supervisor', '', 'rule mission.START active'),
        sup(101, 'sup_rule', '', 'mission.START active cause=elapsed=1000ns'),
        sup(110, 'supervisor', 'ORD', '"activate schema fast() (activation #1, to ORD)"'), // CSV-quoted: a comma in it
        // the next rule, 60 µs before ORD's record of the request in the field test's run
        sup(200, 'supervisor', '', 'rule mission.MODEA active'),
        sup(201, 'sup_rule', '', 'mission.MODEA active cause=elapsed=1000ns'),
        sup(6000, 'module_exit', '', 'status=0'), ''].join('\n') },
    ];
  }
  const CAT: SchemaInfo[] = [{ name: 'fast', kind: 'periodic', modules: ['FST'] }];

  for (const [when, received] of [['after the next rule became active', 260], ['before the next rule became active', 150]] as const) {
    it(`is the rule whose action asked ORD for it, when ORD received the request ${when}`, () => {
      const files = logs(received);
      const models = [new MonitorModel({ checkpointEvery: 2 }), new MonitorModel({ checkpointEvery: 2 })];
      models[0]!.pushAll(parseTrace(files));
      // as the Monitor builds a recorded run (a folder's logs, a job's)
      const steps = recordedRunSteps(files, 3, { checkpointEvery: 2 });
      let step = steps.next();
      while (!step.done) step = steps.next();
      models[1] = step.value.model;
      for (const m of models) {
        const t0 = m.t0!;
        for (const us of [received + 6, received + 50, 300, 4000]) {
          const s = m.stateAt(us * US - t0)!;
          expect(activeSchemas(s, CAT), `at ${us} µs`).toEqual([{ name: 'fast', kind: 'periodic', by: 'SUP.mission.START' }]);
          // what each rule started (`→ fast` on its row)
          if (us < 200) expect(s.supervisors.get('SUP')!.rules.get('mission.START')!.started).toEqual(['fast']);
          if (us > 201) expect(s.supervisors.get('SUP')!.rules.get('mission.MODEA')!.started).toEqual([]);
        }
      }
    });
  }

  it('is the rule active last when the supervisor\'s log names no action (a log of an older version)', () => {
    const files = logs(260).map((f) => ({ ...f, text: f.text.split('\n').filter((l) => !l.includes('activate schema fast')).join('\n') }));
    const m = new MonitorModel({ checkpointEvery: 2 });
    m.pushAll(parseTrace(files));
    expect(activeSchemas(m.stateAt(4000 * US - m.t0!), CAT)).toEqual([{ name: 'fast', kind: 'periodic', by: 'SUP.mission.MODEA' }]);
  });
});
