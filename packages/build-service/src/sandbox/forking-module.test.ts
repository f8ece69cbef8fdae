import { describe, expect, test } from 'vitest';
import { forkingModule, withForkingModule } from './forking-module.js';

describe('forkingModule', () => {
  const names = (list: string[]) => (pid: number) => list[pid] ?? '';
  test('names the module most processes are named after (its forks keep its name)', () => {
    const list = ['bwrap', 'bwrap', 'sh', 'make', 'contract-launch', 'ORD', 'ENC', 'MOT', ...Array(240).fill('HMI'), 'HMI'];
    expect(forkingModule(list.map((_, i) => i), names(list))).toEqual({ module: 'HMI', processes: 241 });
  });
  test('no one: the sandbox\'s own programs, a tie, a module with one child, a name that is no module\'s', () => {
    const tools = Array(50).fill('make');
    expect(forkingModule(tools.map((_, i) => i), names(tools))).toBeNull();
    const tie = ['A', 'A', 'A', 'B', 'B', 'B'];
    expect(forkingModule(tie.map((_, i) => i), names(tie))).toBeNull();
    const one = ['CTL', 'CTL', 'MOT'];
    expect(forkingModule(one.map((_, i) => i), names(one))).toBeNull();
    const odd = Array(9).fill('kworker/0:1');
    expect(forkingModule(odd.map((_, i) => i), names(odd))).toBeNull();
  });
  test('withForkingModule: the hit with the module and its count when one is named, else the hit as it was', () => {
    const hit = { name: 'processes', value: 256, unit: 'count', mechanism: 'cgroup-v1' } as const;
    const list = ['make', 'CTL', 'CTL', 'CTL'];
    expect(withForkingModule(hit, [0, 1, 2, 3], (p) => list[p] ?? '')).toEqual({ ...hit, module: 'CTL', moduleProcesses: 3 });
    expect(withForkingModule(hit, [0, 1], (p) => list[p] ?? '')).toBe(hit);
  });
});
