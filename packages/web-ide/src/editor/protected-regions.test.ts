import { describe, it, expect } from 'vitest';
import { scanProtectedRegions, editsAllowed, skeletonOf } from './protected-regions.js';

const FILE = [
  'int a;',
  '/*PROTECTED REGION ID(protect_init_MAA) ENABLED START*/',
  '  user();',
  '/*PROTECTED REGION END*/',
  'int b;',
  '/*PROTECTED REGION ID(protect_exec_MAA) START*/',
  '/*PROTECTED REGION END*/',
].join('\n');

describe('scanProtectedRegions', () => {
  it('finds regions with their editable spans', () => {
    const { regions, errors } = scanProtectedRegions(FILE);
    expect(errors).toEqual([]);
    expect(regions.map((r) => [r.id, r.enabled])).toEqual([['protect_init_MAA', true], ['protect_exec_MAA', false]]);
    expect(FILE.slice(regions[0]!.start, regions[0]!.end)).toBe('\n  user();\n');
  });

  it('reads markers written with extra spaces, as the generator and the server do', () => {
    const spaced = 'a\n/* PROTECTED REGION ID( protect_x )  ENABLED   START */\nmine\n/*  PROTECTED  REGION END */\nb';
    const { regions, errors } = scanProtectedRegions(spaced);
    expect(errors).toEqual([]);
    expect(regions.map((r) => [r.id, r.enabled])).toEqual([['protect_x', true]]);
    expect(spaced.slice(regions[0]!.start, regions[0]!.end)).toBe('\nmine\n');
  });

  it('reports START without END, nested START, stray END and duplicate IDs', () => {
    const bad = '/*PROTECTED REGION ID(x) ENABLED START*/\n/*PROTECTED REGION ID(x) ENABLED START*/\n/*PROTECTED REGION END*/\n/*PROTECTED REGION END*/\n/*PROTECTED REGION ID(y) ENABLED START*/';
    const msgs = scanProtectedRegions(bad).errors.map((e) => e.message);
    expect(msgs.some((m) => m.includes('nested'))).toBe(true);
    expect(msgs.some((m) => m.includes('duplicate'))).toBe(true);
    expect(msgs.some((m) => m.includes('END without'))).toBe(true);
    expect(msgs.some((m) => m.includes('START without END'))).toBe(true);
  });
});

describe('editsAllowed / skeletonOf', () => {
  const { regions } = scanProtectedRegions(FILE);
  const inside = FILE.indexOf('user');
  it('accepts edits inside a region and refuses edits that touch the skeleton', () => {
    expect(editsAllowed(regions, [{ start: inside, end: inside + 4 }])).toBe(true);
    expect(editsAllowed(regions, [{ start: 0, end: 1 }])).toBe(false);
    expect(editsAllowed(regions, [{ start: inside, end: FILE.indexOf('int b') }])).toBe(false);
  });
  it('a protected-only change keeps the skeleton, any other change does not', () => {
    const edited = FILE.replace('user();', 'user(); more();');
    expect(skeletonOf(edited)).toBe(skeletonOf(FILE));
    expect(skeletonOf(FILE.replace('int b;', 'int c;'))).not.toBe(skeletonOf(FILE));
  });
});
