/** run_finished's cpu_ns (docs/runtime-api.md "Trace records"): each released module's last and largest CPU time per release, read three ways, and the words of its schema's block; ORD and supervisors are left out. */
import { describe, it, expect } from 'vitest';
import { readThreeWays } from './read-three-ways.test-support.js';
import { moduleCpuText } from './panel-text.js';

const W = '2026-12-07T11:02:48.568320Z';
const rel = (ns: number, m: string, cycle: number, id: number) => `${ns},${W},ORD,ord_release,${m},,0,schema=loop cycle=${cycle} tick_ns=${ns} release_ns=${ns} release=${id}`;
const ORD = [
  `1000000000,${W},ORD,module_started,,,0,pid=39 priority=50`,
  `1000000100,${W},ORD,run_started,SUP,,0,activation=1`,
  rel(1100000000, 'MSC', 0, 1), rel(1200000000, 'MSC', 1, 2), rel(1300000000, 'MSC', 2, 3),
  // ORD's own run: its whole life, no release
  `1400000000,${W},ORD,run_finished,SUP,,0,activation=1 cpu_ns=90000000 STOP`,
];
const SUP = [
  `1000000000,${W},SUP,module_started,,,0,pid=38 priority=40`,
  `1000000050,${W},SUP,supervisor,,,0,function action() started`,
  `1000000060,${W},SUP,run_started,contract-launch,,0,activation=1`,
  `1400000100,${W},SUP,run_finished,contract-launch,,0,activation=1 cpu_ns=70000000 STOP`,
];
const MSC = [
  `1000000000,${W},MSC,module_started,,,0,pid=41 priority=40`,
  `1100000010,${W},MSC,run_started,ORD,,0,activation=1`,
  `1101000000,${W},MSC,run_finished,,,0,activation=1 cpu_ns=1250000 ACK_FINISHED`,
  `1200000010,${W},MSC,run_started,ORD,,0,activation=2`,
  `1203000000,${W},MSC,run_finished,,,0,activation=2 cpu_ns=3100000 ACK_FINISHED`,
  `1300000010,${W},MSC,run_started,ORD,,0,activation=3`,
  `1300500000,${W},MSC,run_finished,,,0,activation=3 cpu_ns=400000 ACK_FINISHED`,
];
const OLD = [ // a log of an older version: no cpu_ns
  `1000000000,${W},MSA,module_started,,,0,pid=40 priority=40`,
  `1100000010,${W},MSA,run_started,ORD,,0,activation=1`,
  `1101000000,${W},MSA,run_finished,,,0,activation=1 ACK_FINISHED`,
];
const t = (ns: number) => ns - 1000000000;

describe("a module's CPU time per release (run_finished cpu_ns)", () => {
  it('is kept as the last and the largest, live, parsed and replayed alike; not for ORD nor a supervisor; logs of older versions give none', () => {
    const logs = [{ name: 'ORD_1.csv', lines: ORD }, { name: 'SUP_1.csv', lines: SUP }, { name: 'MSC_1.csv', lines: MSC }, { name: 'MSA_1.csv', lines: OLD }];
    for (const m of readThreeWays(logs, {})) {
      const mid = m.stateAt(t(1203000000))!.modules.get('MSC')!;
      expect([mid.lastCpuNs, mid.maxCpuNs]).toEqual([3100000, 3100000]);
      const end = m.stateAt(t(1400000100))!;
      expect([end.modules.get('MSC')!.lastCpuNs, end.modules.get('MSC')!.maxCpuNs]).toEqual([400000, 3100000]);
      expect(end.modules.get('MSA')!.lastCpuNs).toBeUndefined();
      expect(end.modules.get('ORD')?.lastCpuNs).toBeUndefined();
      expect(end.modules.get('SUP')?.lastCpuNs).toBeUndefined();
      // the schema's block: the modules ORD released in it, their CPU per release
      const loop = end.periodic.get('loop')!;
      expect(loop.modules).toEqual(['MSC']);
      expect(moduleCpuText(loop.modules, end.modules)).toBe(' · CPU per release: MSC last 400 µs, max 3.1 ms');
    }
  });

  it('a schema releasing more modules than its block shows says how many more said their CPU time', () => {
    // 20 modules M00..M19, each released once in cycle 0 of schema wide, each its own CPU time (k ms + 1 ms)
    const names = Array.from({ length: 20 }, (_, k) => `M${String(k).padStart(2, '0')}`);
    const ord = [`1000000000,${W},ORD,module_started,,,0,pid=39 priority=50`, ...names.map((m, k) => rel(1100000000 + k * 1000, m, 0, k + 1).replace('schema=loop', 'schema=wide'))];
    const logs = [{ name: 'ORD_1.csv', lines: ord }, ...names.map((m, k) => ({ name: `${m}_1.csv`, lines: [
      `${1100000500 + k * 1000},${W},${m},run_started,ORD,,0,activation=1`,
      `${1150000000 + k * 1000},${W},${m},run_finished,,,0,activation=1 cpu_ns=${(k + 1) * 1_000_000} ACK_FINISHED`,
    ] }))];
    for (const m of readThreeWays(logs, {})) {
      const end = m.stateAt(t(1150019000))!;
      const wide = end.periodic.get('wide')!;
      const text = moduleCpuText(wide.modules, end.modules);
      expect(text.startsWith(' · CPU per release: M00 last 1 ms, max 1 ms; M01 last 2 ms, max 2 ms;')).toBe(true);
      expect(text.endsWith('; M15 last 16 ms, max 16 ms; 4 more modules not shown: contract trace tells each')).toBe(true);
      expect(text).not.toContain('M16');
    }
  });

  it('says nothing of a module whose runs said no CPU time', () => {
    expect(moduleCpuText([], new Map())).toBe('');
    expect(moduleCpuText(['MSA', 'MSC'], new Map([['MSA', {}], ['MSC', { lastCpuNs: 5_000_000, maxCpuNs: 5_000_000 }]]))).toBe(' · CPU per release: MSC last 5 ms, max 5 ms');
  });
});
