/** The editor a workspace path gets, and what the status bar names its language. */
import { describe, it, expect } from 'vitest';
import { languageLabel, languageOf } from './file-kinds.js';

describe('languageLabel', () => {
  it('names each kind of file the workspace opens', () => {
    const label = (path: string) => languageLabel(path, languageOf(path));
    expect(label('robot/mission.contract')).toBe('Cactal');
    expect(label('robot/scenarios/auto.scenario')).toBe('Cactal scenario');
    expect(label('robot/src-gen/generated/architecture/modules/VEL_mod/module.c')).toBe('C (generated)');
    expect(label('robot/tools/helper.c')).toBe('C');
    expect(label('robot/logs/MIS_5-Dec-2026-17h03m31s.csv')).toBe('CSV');
    expect(label('robot/notes.txt')).toBe('Plain text');
    expect(label('robot/src-gen/generated/architecture/Makefile')).toBe('Plain text');
  });
});
