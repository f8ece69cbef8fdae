import { describe, expect, test } from 'vitest';
import { holdsUnderProcessLimit } from './process-limit-warning.js';

describe("contract check's process limit warning in a job", () => {
  const warning = {
    file: 'sup/power.contract', line: 7, column: 12, severity: 'warning' as const, code: 'architecture-over-process-limit',
    message: "This architecture runs 136 processes (128 modules, 7 supervisors and ORD), 2 threads each: with make and the launcher, 276 processes and threads, more than the build service's default process limit of 256 ...",
  };
  test('kept under the default limit, dropped under a job limit that fits (276 processes and threads); other problems kept', () => {
    expect(holdsUnderProcessLimit(warning, 256)).toBe(true);
    expect(holdsUnderProcessLimit(warning, 275)).toBe(true);
    expect(holdsUnderProcessLimit(warning, 276)).toBe(false);
    expect(holdsUnderProcessLimit(warning, 512)).toBe(false);
    expect(holdsUnderProcessLimit({ ...warning, code: 'import-unused' }, 512)).toBe(true);
  });
});
