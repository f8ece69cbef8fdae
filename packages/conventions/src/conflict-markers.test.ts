import { describe, expect, it } from 'vitest';
import { conflictMarkerLines, conflictMarkers } from './conflict-markers.js';

describe('conflictMarkers', () => {
  it("finds git's markers at line start, diff3's base too, with their lines and kinds (CRLF or LF)", () => {
    for (const eol of ['\n', '\r\n']) {
      const text = ['void f(void){', '<<<<<<< ours', '  a();', '||||||| base', '  b();', '=======', '  c();', '>>>>>>> theirs', '}', ''].join(eol);
      const found = conflictMarkers(text);
      expect(found.map((m) => [m.line, m.kind])).toEqual([[2, 'ours'], [4, 'base'], [6, 'separator'], [8, 'theirs']]);
      expect(text.slice(found[0]!.offset, found[0]!.offset + found[0]!.length)).toBe('<<<<<<< ours');
      expect(conflictMarkerLines(found)).toBe('2, 4, 6, 8');
    }
  });

  it('finds a marker with nothing after it, and none in a text without an opening or closing marker', () => {
    expect(conflictMarkers('x\n<<<<<<<\ny\n=======\nz\n>>>>>>>').map((m) => m.line)).toEqual([2, 4, 6]);
    expect(conflictMarkers('/*\n=======\n rule\n=======\n*/\n')).toEqual([]);
    expect(conflictMarkers('  <<<<<<< indented\nx <<<<<<<< y\n<<<<<<<< eight\n')).toEqual([]);
    expect(conflictMarkers('a = b >>>>>>> 3;\n')).toEqual([]);
  });

  it('says at most 8 lines', () => {
    const text = Array.from({ length: 10 }, () => '<<<<<<< x').join('\n');
    expect(conflictMarkerLines(conflictMarkers(text))).toBe('1, 2, 3, 4, 5, 6, 7, 8, ...');
  });
});
