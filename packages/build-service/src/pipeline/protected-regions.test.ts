import { describe, expect, it } from 'vitest';
import { findProtectedRegions } from './protected-regions.js';

describe('findProtectedRegions', () => {
  it('reads the markers as codegen does: spaces inside markers, trimmed IDs, `additionnal` as `additional`', () => {
    const text = ['int a;', '/* PROTECTED REGION ID( protect_additionnal_x ) ENABLED START */', 'mine();', '/*PROTECTED  REGION END*/'].join('\n');
    expect(findProtectedRegions(text)).toEqual([{ id: 'protect_additional_x', startLine: 2, endLine: 4 }]);
  });

  it('keeps the well-formed regions of a malformed file', () => {
    const text = ['/*PROTECTED REGION END*/', '/*PROTECTED REGION ID(a) ENABLED START*/', '/*PROTECTED REGION END*/', '/*PROTECTED REGION ID(b) ENABLED START*/'].join('\n');
    expect(findProtectedRegions(text)).toEqual([{ id: 'a', startLine: 2, endLine: 3 }]);
  });
});
