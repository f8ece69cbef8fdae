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

  it('finds the best alignment, not the leftmost: a module folder typed whole ranks that module first', () => {
    const modules = ['LOC', 'CTL', 'MIS'].map((m) => `rover/src-gen/generated/architecture/modules/${m}_mod/module.c`);
    const ranked = fuzzyFilter('CTL_mod/module.c', modules, (f) => f);
    expect(ranked[0]!.item).toBe(modules[1]);
    // contiguous: the positions are CTL_mod/module.c itself
    expect(ranked[0]!.match.positions[0]).toBe(modules[1]!.indexOf('CTL_mod'));
    expect(fuzzyFilter('smod3', ['smodule1.contract', 'smodule3.contract', 'sschema1.contract'], (f) => f)[0]!.item).toBe('smodule3.contract');
  });

  it('ranks the path typed whole first among 5,000 alike', () => {
    const paths = Array.from({ length: 5000 }, (_, i) => `robot${i % 7}/src-gen/generated/architecture/modules/M${i}_mod/module_${i}.c`);
    const ranked = fuzzyFilter('M4242_mod/module_4242', paths, (f) => f);
    expect(ranked[0]!.item).toBe(paths[4242]);
  });

  it('drops what does not match and keeps the order of equals', () => {
    expect(fuzzyFilter('make', files, (f) => f).map((r) => r.item)).toEqual(['src-gen/Makefile']);
    expect(fuzzyFilter('', files, (f) => f).map((r) => r.item)).toEqual(files);
  });
});
