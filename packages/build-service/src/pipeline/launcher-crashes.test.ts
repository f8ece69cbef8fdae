import { describe, expect, test } from 'vitest';
import { LauncherCrashes } from './launcher-crashes.js';

describe("the launcher's crashes, for a failed run's message", () => {
  test('one crash: the module and how it ended; a clean end or a stop-time termination is no crash', () => {
    const c = new LauncherCrashes();
    c.line('module MAB (pid 18) exited with status 0');
    c.line('module MSB (pid 19) terminated by signal 15 (Terminated)');
    c.line('module MSC (pid 21) died by signal 11 (Segmentation fault) while the run stopped');
    expect(c.summary()).toBeUndefined();
    c.line('FAILED: module MSC crashed');
    c.line('FAILED: module MSC crashed');
    expect(c.summary()).toBe('module MSC crashed (died by signal 11 (Segmentation fault) while the run stopped)');
  });

  test('several: each named with how it ended, the fifth on counted', () => {
    const c = new LauncherCrashes();
    for (const [m, how] of [['A', 'exited with status 3'], ['B', 'died by signal 6 (Aborted)'], ['C', 'exited with status 3 while the run stopped'], ['D', 'exited with status 1'], ['E', 'exited with status 2']]) {
      c.line(`module ${m} (pid 1) ${how}`);
      c.line(`FAILED: module ${m} crashed`);
    }
    expect(c.summary()).toBe('5 modules crashed: A (exited with status 3), B (died by signal 6 (Aborted)), C (exited with status 3 while the run stopped), D (exited with status 1) and 1 more');
  });
});
