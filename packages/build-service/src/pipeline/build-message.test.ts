import { describe, expect, it } from 'vitest';
import { compilerDiagnosticsCount } from './job.js';

describe("a successful build's message counts the compiler's diagnostics as the compiler's", () => {
  it('says warnings as warnings, others apart, nothing when there is none (it said "1 diagnostic(s)" after 9 model hints and 1 gcc warning)', () => {
    expect(compilerDiagnosticsCount([])).toBe('');
    expect(compilerDiagnosticsCount([{ severity: 'warning' }])).toBe(' (1 compiler warning)');
    expect(compilerDiagnosticsCount([{ severity: 'warning' }, { severity: 'warning' }, { severity: 'note' }])).toBe(' (2 compiler warnings, 1 other compiler diagnostic)');
  });
});
