import { describe, expect, it } from 'vitest';
import { fuzzyFilter, fuzzyMatch } from './fuzzy.js';

describe('fuzzyMatch', () => {
  it('matches the query characters in order, case-insensitive', () => {
    expect(fuzzyMatch('schd', 'sched.contract')?.positions).toEqual([0, 1, 2, 4]);
    expect(fuzzyMatch('SCHED', 'sched.contract')).toBeDefined();
    expect(fuzzyMatch('dhcs', 'sched.contract')).toBeUndefined();
    expect(fuzzyMatch('x', 'sched.contract')).toBeUndefined();
  });

  it('an empty query matches everything', () => {
    expect(fuzzyMatch('', 'a/b.c')).toEqual({ score: 0, positions: [] });
  });

  it('moves a match to a word start when one is free', () => {
    // the s of "start" (after _), not the first s inside "mission"
    expect(fuzzyMatch('ms', 'mission_start')?.positions).toEqual([0, 8]);
    expect(fuzzyMatch('gen', 'src-gen/x')?.positions).toEqual([4, 5, 6]);
  });
});

describe('fuzzyFilter', () => {
  const files = [
    'src-gen/generated/architecture/modules/MSC/MSC.c',
    'sched.contract',
    'schema.contract',
    'supervisor.contract',
    'src-gen/Makefile',
  ];

  it('ranks file-name and word-start matches first', () => {
    expect(fuzzyFilter('sched', files, (f) => f)[0]!.item).toBe('sched.contract');
    expect(fuzzyFilter('sup', files, (f) => f)[0]!.item).toBe('supervisor.contract');
    expect(fuzzyFilter('msc.c', files, (f) => f)[0]!.item).toBe('src-gen/generated/architecture/modules/MSC/MSC.c');
  });

  it('drops what does not match and keeps the order of equals', () => {
    expect(fuzzyFilter('make', files, (f) => f).map((r) => r.item)).toEqual(['src-gen/Makefile']);
    expect(fuzzyFilter('', files, (f) => f).map((r) => r.item)).toEqual(files);
  });
});
