/**
 * The engine's process list (docker-top.ts) as a process table: the columns found by their
 * titles, hostile rows left out, and the forking module named from it as from /proc.
 */
import { describe, expect, test } from 'vitest';
import { processTableOfTop } from './docker-top.js';
import { forkingModule } from './forking-module.js';

describe('processTableOfTop', () => {
  test('pid, parent and name by their titles; rows that are no process left out; names bounded', () => {
    const { pids, table } = processTableOfTop({
      Titles: ['PID', 'PPID', 'COMMAND'],
      Processes: [['10', '1', 'sh'], ['11', '10', 'contract-launch'], ['12', '11', 'MSC'], ['13', '12', 'MSC'], ['x', '1', 'evil'], ['14', '-1', 'evil'], ['15'], 'row', ['16', '12', 'y'.repeat(500)]],
    });
    expect(pids).toEqual([10, 11, 12, 13, 16]);
    expect(table.nameOf(12)).toBe('MSC');
    expect(table.parentOf(13)).toBe(12);
    expect(table.nameOf(16)).toHaveLength(64);
    expect(table.nameOf(99)).toBe('');
    expect(table.parentOf(99)).toBe(0);
  });

  test('columns in another order; an answer of another shape is an empty table', () => {
    expect(processTableOfTop({ Titles: ['COMM', 'PID', 'PPID'], Processes: [['MSC', '5', '4']] }).pids).toEqual([5]);
    for (const bad of [undefined, null, 'text', { Titles: ['UID', 'PID'], Processes: [['0', '5']] }, { Titles: ['PID', 'PPID', 'COMMAND'], Processes: 'x' }]) {
      expect(processTableOfTop(bad).pids).toEqual([]);
    }
  });

  test('names the module whose code forks, as from /proc', () => {
    const rows = [['10', '1', 'contract-launch'], ['11', '10', 'MSA'], ['12', '10', 'MSC'], ...Array.from({ length: 20 }, (_, i) => [String(20 + i), '12', 'MSC'])];
    const { pids, table } = processTableOfTop({ Titles: ['PID', 'PPID', 'COMMAND'], Processes: rows });
    expect(forkingModule(pids, table)).toEqual({ module: 'MSC', processes: 21 });
  });
});
