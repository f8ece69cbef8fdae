import { describe, expect, test } from 'vitest';
import { forkingModule, withForkingModule, type ProcessTable } from './forking-module.js';

/** A process table from [name, parent] rows: pid = row index + 2 (pid 1 is the sandbox's first process). */
function table(rows: ReadonlyArray<readonly [string, number]>): { pids: number[]; table: ProcessTable } {
  return {
    pids: rows.map((_, i) => i + 2),
    table: { nameOf: (pid) => rows[pid - 2]?.[0] ?? '', parentOf: (pid) => rows[pid - 2]?.[1] ?? 0 },
  };
}

/** bwrap (2) -> sh (3) -> make (4) -> contract-launch (5) -> ORD (6), ENC (7), MOT (8), HMI (9). */
const SANDBOX: Array<readonly [string, number]> = [['bwrap', 1], ['sh', 2], ['make', 3], ['contract-launch', 4], ['ORD', 5], ['ENC', 5], ['MOT', 5], ['HMI', 5]];

describe('forkingModule', () => {
  test('names the module most processes descend from when its forks keep its name', () => {
    const t = table([...SANDBOX, ...Array.from({ length: 240 }, () => ['HMI', 9] as const)]);
    expect(forkingModule(t.pids, t.table)).toEqual({ module: 'HMI', processes: 241 });
  });
  test('names it when its code forks then execs another program (sh, sleep: no module\'s name)', () => {
    // HMI (9) forks shells (pids 10..109), each runs a sleep of its own (110..209)
    const shells = Array.from({ length: 100 }, () => ['sh', 9] as const);
    const sleeps = Array.from({ length: 100 }, (_, i) => ['sleep', 10 + i] as const);
    const t = table([...SANDBOX, ...shells, ...sleeps]);
    expect(forkingModule(t.pids, t.table)).toEqual({ module: 'HMI', processes: 201 });
    // and a chain of forks, each child forking the next: still HMI's
    const chain = Array.from({ length: 150 }, (_, i) => ['worker', i === 0 ? 9 : 10 + i - 1] as const);
    const c = table([...SANDBOX, ...chain]);
    expect(forkingModule(c.pids, c.table)).toEqual({ module: 'HMI', processes: 151 });
  });
  test('a process whose parent exited (given to the sandbox\'s first process) counts for the name it bears', () => {
    const orphans = Array.from({ length: 30 }, () => ['MOT', 1] as const);
    const t = table([...SANDBOX, ...orphans, ['sleep', 1], ['sleep', 1]]);
    expect(forkingModule(t.pids, t.table)).toEqual({ module: 'MOT', processes: 31 });
  });
  test('no one: the sandbox\'s own programs, a tie, a module with one child, a name that is no module\'s', () => {
    const tools = table([...SANDBOX.slice(0, 4), ...Array.from({ length: 50 }, () => ['make', 4] as const)]);
    expect(forkingModule(tools.pids, tools.table)).toBeNull();
    const tie = table([...SANDBOX, ['ORD', 6], ['ORD', 6], ['ENC', 7], ['ENC', 7]]);
    expect(forkingModule(tie.pids, tie.table)).toBeNull();
    const one = table([...SANDBOX, ['sh', 8]]);
    expect(forkingModule(one.pids, one.table)).toBeNull();
    const odd = table(Array.from({ length: 9 }, () => ['kworker/0:1', 1] as const));
    expect(forkingModule(odd.pids, odd.table)).toBeNull();
  });
  test('the walk stays within the job: the service\'s own process above the sandbox names no module', () => {
    // bwrap's parent is the build service (pid 900, `node`, not one of the job's processes)
    const rows = new Map<number, readonly [string, number]>([[900, ['node', 1]], [2, ['bwrap', 900]], [3, ['bwrap', 2]], [4, ['make', 3]], [5, ['contract-launch', 4]], [6, ['ORD', 5]]]);
    const t: ProcessTable = { nameOf: (pid) => rows.get(pid)?.[0] ?? '', parentOf: (pid) => rows.get(pid)?.[1] ?? 0 };
    expect(forkingModule([2, 3, 4, 5, 6], t)).toBeNull();
    // and a loop of reused pids ends the walk
    const loop: ProcessTable = { nameOf: () => 'CTL', parentOf: (pid) => (pid === 2 ? 4 : pid - 1) };
    expect(forkingModule([2, 3, 4], loop)).toEqual({ module: 'CTL', processes: 3 });
  });
  test('processes gone while read (name \'\', parent 0) count for no one', () => {
    const t = table([...SANDBOX, ...Array.from({ length: 5 }, () => ['', 0] as const), ['sh', 9], ['sh', 9]]);
    expect(forkingModule(t.pids, t.table)).toEqual({ module: 'HMI', processes: 3 });
  });
  test('withForkingModule: the hit with the module and its count when one is named, else the hit as it was', () => {
    const hit = { name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1' } as const;
    const t = table([...SANDBOX, ['sh', 6], ['sh', 6]]);
    expect(withForkingModule(hit, t.pids, t.table)).toEqual({ ...hit, module: 'ORD', moduleProcesses: 3 });
    expect(withForkingModule(hit, t.pids.slice(0, 5), t.table)).toBe(hit);
  });
});
