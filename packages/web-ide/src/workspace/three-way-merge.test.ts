import { describe, it, expect } from 'vitest';
import { threeWayMerge, findConflictMarker } from './three-way-merge.js';

const SCHED = `scheduler configuration {

    modules{
        MSA;
        MSB;
        MSC;
        MSD;
    }
}
`;

describe('threeWayMerge (tab text vs disk text, both edited from the tab base)', () => {
  it('merges edits of two adjacent lines (the two-tab case of sched.contract)', () => {
    const mine = SCHED.replace('MSD;', 'MSD; // A');
    const theirs = SCHED.replace('MSC;', 'MSC; // B');
    const r = threeWayMerge(SCHED, mine, theirs);
    expect(r).toEqual({ clean: true, text: SCHED.replace('MSD;', 'MSD; // A').replace('MSC;', 'MSC; // B') });
  });

  it('merges edits far apart, insertions and deletions included', () => {
    const mine = SCHED.replace('scheduler', '// header\nscheduler').replace('        MSB;\n', '');
    const theirs = SCHED.replace('    }\n}', '    }\n    schemas{ s1; }\n}');
    const r = threeWayMerge(SCHED, mine, theirs);
    expect(r.clean).toBe(true);
    if (r.clean) expect(r.text).toBe('// header\n' + SCHED.replace('        MSB;\n', '').replace('    }\n}', '    }\n    schemas{ s1; }\n}'));
  });

  it('takes the only side that changed, and identical edits once', () => {
    const edited = SCHED.replace('MSA;', 'MSA; // x');
    expect(threeWayMerge(SCHED, SCHED, edited)).toEqual({ clean: true, text: edited });
    expect(threeWayMerge(SCHED, edited, SCHED)).toEqual({ clean: true, text: edited });
    expect(threeWayMerge(SCHED, edited, edited)).toEqual({ clean: true, text: edited });
  });

  it('reports overlapping edits as a conflict, both sides kept in the marked text', () => {
    const mine = SCHED.replace('MSA;', 'MSA; // mine');
    const theirs = SCHED.replace('MSA;', 'MSA; // theirs');
    const r = threeWayMerge(SCHED, mine, theirs);
    expect(r.clean).toBe(false);
    if (r.clean) return;
    expect(r.conflicts).toBe(1);
    expect(r.marked).toContain('<<<<<<< yours\n        MSA; // mine\n=======\n        MSA; // theirs\n>>>>>>> on disk\n');
    expect(r.marked.startsWith('scheduler configuration {')).toBe(true);
    expect(r.marked).toContain('MSD;');
  });

  it('an edit inside a block the other side deleted is a conflict, not a silent loss', () => {
    const mine = SCHED.replace('MSB;', 'MSB; // keep me');
    const theirs = SCHED.replace('        MSA;\n        MSB;\n        MSC;\n', '');
    const r = threeWayMerge(SCHED, mine, theirs);
    expect(r.clean).toBe(false);
    if (!r.clean) expect(r.marked).toContain('keep me');
  });

  it('keeps texts without a final line end and with CRLF byte for byte', () => {
    const base = 'a\r\nb\r\nc';
    const r = threeWayMerge(base, 'a1\r\nb\r\nc', 'a\r\nb\r\nc2');
    expect(r).toEqual({ clean: true, text: 'a1\r\nb\r\nc2' });
  });
});

describe('findConflictMarker (what "Save the right side as edited here" refuses)', () => {
  it("finds the first marker of a merge's marked text, with its line", () => {
    const r = threeWayMerge(SCHED, SCHED.replace('MSD;', 'MSD; // mine'), SCHED.replace('MSD;', 'MSD; // theirs'));
    expect(r.clean).toBe(false);
    const marked = (r as { marked: string }).marked;
    const line = marked.split('\n').indexOf('<<<<<<< yours') + 1;
    expect(line).toBeGreaterThan(1);
    expect(findConflictMarker(marked)).toEqual({ line, marker: '<<<<<<< yours' });
  });
  it('a separator or closing marker left alone is found too (CRLF text included)', () => {
    expect(findConflictMarker('a\nb\n=======\nc\n')).toEqual({ line: 3, marker: '=======' });
    expect(findConflictMarker('a\r\n>>>>>>> on disk\r\n')).toEqual({ line: 2, marker: '>>>>>>> on disk' });
    expect(findConflictMarker('<<<<<<<\n')).toEqual({ line: 1, marker: '<<<<<<<' });
  });
  it('text that only looks alike is not a marker', () => {
    expect(findConflictMarker(SCHED)).toBeUndefined();
    expect(findConflictMarker('// =======\n==========\n  <<<<<<< indented\nx <<<<<<< y\n<<<<<<<<< nine\n')).toBeUndefined();
  });
});
