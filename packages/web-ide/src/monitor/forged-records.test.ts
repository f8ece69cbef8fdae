import { describe, it, expect } from 'vitest';
import { recordedRunSteps } from './recorded-run.js';
import { MonitorModel } from './monitor-model.js';
import { activationsFromLogs } from '../views/run-logs.js';

/**
 * A hostile module's lines in its own log (docs/runtime-api.md "Whose records, and their times"):
 * ORD's deadline miss logged by MSA, and times the runtime never wrote. The Monitor, live and
 * replayed, and the Timeline read them as `contract trace` does.
 */
const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
const W = '2026-11-24T18:30:15.123456Z';
const BASE = 40_000_000_000_000;
const at = (ms: number) => BASE + ms * 1_000_000;
const ORD = 'ORD_24-Nov-2026-18h30m15s.csv';
const MSA = 'MSA_24-Nov-2026-18h30m15s.csv';
const logs = (msaExtra: string[]) => [
  { name: ORD, text: [HEADER, `${at(0)},${W},ORD,module_started,,,0,pid=1 priority=90`, `${at(10)},${W},ORD,scheduler,,,0,activate schemaCommande1 (activation #1 from SUP)`,
    `${at(11)},${W},ORD,ord_release,MSA,,0,schema=schemaCommande1 cycle=0 tick_ns=${at(11)} release_ns=${at(11)} release=1`,
    `${at(12)},${W},ORD,ord_complete,,,0,schema=schemaCommande1 cycle=0 tick_ns=${at(11)} response_ns=1000000`, ''].join('\n') },
  { name: MSA, text: [HEADER, `${at(1)},${W},MSA,module_started,,,0,pid=2 priority=84`, `${at(11)},${W},MSA,run_started,ORD,,0,activation=1`,
    `${at(12)},${W},MSA,run_finished,,,0,activation=1 cpu_ns=41000 ACK_FINISHED`, ...msaExtra, ''].join('\n') },
];
const FORGED = [
  `${at(20)},${W},MSA,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=99 tick_ns=1`,
  `${at(21)},${W},MSA,ord_release,MSA,,0,schema=schemaCommande1 cycle=99 tick_ns=${at(21)} release_ns=${at(21)} release=9`,
  `1,${W},MSA,user,,,0,EARLY`,
  `18000000000000000000,${W},MSA,user,,,0,LATE`,
  `9000000000000000000,${W},MSA,run_started,ORD,,0,activation=2`,
];

function replay(files: ReturnType<typeof logs>): MonitorModel {
  const steps = recordedRunSteps(files, 3);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value.model;
}

function live(files: ReturnType<typeof logs>): MonitorModel {
  const m = new MonitorModel();
  // the live channel's order: by time, each log's lines in file order (a forged line where it was written)
  const lines = files.flatMap((f) => f.text.split('\n').slice(1).filter(Boolean).map((text, i) => ({ file: f.name, line: i + 2, text })));
  for (const l of lines.filter((l) => l.file === ORD)) m.pushLine(l.file, l.line, l.text);
  for (const l of lines.filter((l) => l.file === MSA)) m.pushLine(l.file, l.line, l.text);
  return m;
}

describe('the Monitor and the Timeline on a hostile module\'s own log', () => {
  for (const [how, read] of [['replayed', replay], ['live', live]] as const) {
    it(`${how}: MSA's ord_* lines are its own user records, marked, never ORD's misses or releases; forged times are unreadable lines, the run's time base stays`, () => {
      const clean = read(logs([]));
      const m = read(logs(FORGED));
      const s = m.live.periodic.get('schemaCommande1')!;
      expect(s.deadlineMisses).toBe(0);
      expect(s.releases).toBe(clean.live.periodic.get('schemaCommande1')!.releases);
      expect(m.marks.filter((x) => x.kind === 'miss')).toEqual([]);
      const user = m.marks.filter((x) => x.kind === 'user').map((x) => x.label);
      expect(user[0]).toMatch(/^ord_deadline_miss: schema=schemaCommande1 cycle=99 tick_ns=1 \[MSA's own record under the name of ORD's records/);
      // EARLY, LATE and the far run_started: unreadable, counted; the axis is the run's 21 ms
      expect(m.live.unknownLines).toBe(3);
      expect(m.end).toBeLessThan(1e9);
      expect(m.live.modules.get('MSA')!.running).toBe(false);
    });
  }

  it('the Timeline draws no bar from a forged time, and says which lines it left out', () => {
    const { acts, errors } = activationsFromLogs(logs(FORGED));
    expect(acts.map((a) => [a.module, a.start])).toEqual([['ORD', at(10)], ['MSA', at(11)]]);
    expect(errors).toEqual([expect.stringMatching(/^MSA_24-Nov-2026-18h30m15s\.csv: 1 line\(s\) .* left out$/)]);
  });

  it('the Timeline names two logs of one module', () => {
    const files = [...logs([]), { name: 'ORD_24-Nov-2026-99h99m99s.csv', text: `${HEADER}\n` }];
    expect(activationsFromLogs(files).errors).toEqual([expect.stringMatching(/^ORD: 2 logs of it \(ORD_24-Nov-2026-18h30m15s\.csv, ORD_24-Nov-2026-99h99m99s\.csv\), read as one/)]);
  });
});
