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
    expect(c.summary()).toBe('module MSC crashed (died by signal 11 (Segmentation fault) while the run stopped): a bad pointer: NULL, freed, or past the end of an array');
  });

  test('where a module crashed, when its crash site is known, after how it ended', () => {
    const c = new LauncherCrashes();
    c.line('module EST (pid 21) died by signal 11 (Segmentation fault)');
    c.line('FAILED: module EST crashed');
    const sites = new Map([['EST', ' at src-gen/m.c:248 in its protected region protect_exec_EST (est_update)']]);
    expect(c.summary(null, sites)).toBe('module EST crashed (died by signal 11 (Segmentation fault)) at src-gen/m.c:248 in its protected region protect_exec_EST (est_update): a bad pointer: NULL, freed, or past the end of an array');
    c.line('module PID (pid 22) died by signal 6 (Aborted)');
    c.line('FAILED: module PID crashed');
    expect(c.summary(null, sites)).toBe('2 modules crashed: EST (died by signal 11 (Segmentation fault) at src-gen/m.c:248 in its protected region protect_exec_EST (est_update): a bad pointer: NULL, freed, or past the end of an array), PID (died by signal 6 (Aborted): the code called abort(), or an assert() failed: its message is on stderr)');
  });

  test('several: each named with how it ended, the fifth on counted', () => {
    const c = new LauncherCrashes();
    for (const [m, how] of [['A', 'exited with status 3'], ['B', 'died by signal 6 (Aborted)'], ['C', 'exited with status 3 while the run stopped'], ['D', 'exited with status 1'], ['E', 'exited with status 2']]) {
      c.line(`module ${m} (pid 1) ${how}`);
      c.line(`FAILED: module ${m} crashed`);
    }
    // an exit with a status is no crash: each said as it ended
    expect(c.summary()).toBe('5 modules failed: A failed (exited with status 3), B crashed (died by signal 6 (Aborted)): the code called abort(), or an assert() failed: its message is on stderr, C failed (exited with status 3 while the run stopped), D failed (exited with status 1) and 1 more');
  });

  test("a kill (a SIGKILL the launcher did not send) is told apart from a crash, by the memory limit when that limit was hit", () => {
    const c = new LauncherCrashes();
    c.line('module HOG (pid 30) died by signal 9 (Killed)');
    c.line("FAILED: module HOG was killed (a SIGKILL the launcher did not send: the kernel's at a memory limit or the real-time CPU bound, or another process's)");
    expect(c.failures()).toEqual([{ module: 'HOG', how: 'died by signal 9 (Killed)', killed: true, initRefused: false }]);
    expect(c.summary()).toBe('module HOG was killed (died by signal 9 (Killed))');
    expect(c.summary({ name: 'memory' })).toBe('module HOG was killed by the memory limit (died by signal 9 (Killed))');
    c.line('module MSC (pid 31) died by signal 11 (Segmentation fault)');
    c.line('FAILED: module MSC crashed');
    expect(c.summary({ name: 'memory' })).toBe('2 modules crashed or were killed by the memory limit: HOG (killed: died by signal 9 (Killed)), MSC (died by signal 11 (Segmentation fault): a bad pointer: NULL, freed, or past the end of an array)');
    // an older launcher said `crashed` for a kill too: its signal 9 line tells
    const old = new LauncherCrashes();
    old.line('module HOG (pid 30) died by signal 9 (Killed) while the run stopped');
    old.line('FAILED: module HOG crashed');
    expect(old.summary()).toBe('module HOG was killed (died by signal 9 (Killed) while the run stopped)');
  });

  test('a module whose init region returned 0 did not start: said so, not as a crash (its own line read from its output)', () => {
    const c = new LauncherCrashes();
    c.moduleLine('MAB', 'MAB: its init region returned 0 (false): the module does not start');
    c.moduleLine('MSC', 'MAB: its init region returned 0 (false): the module does not start'); // another module's words: not MSC's
    c.line('module MAB (pid 63) exited with status 255');
    c.line('FAILED: module MAB crashed');
    expect(c.summary()).toBe('module MAB did not start: its init region returned 0 (exited with status 255)');
    c.line('module MSC (pid 64) died by signal 11 (Segmentation fault)');
    c.line('FAILED: module MSC crashed');
    expect(c.summary()).toBe('2 modules failed: MAB did not start: its init region returned 0 (exited with status 255), MSC crashed (died by signal 11 (Segmentation fault)): a bad pointer: NULL, freed, or past the end of an array');
    // an exit with a status without that line: failed, not crashed
    const d = new LauncherCrashes();
    d.line('module CTL (pid 70) exited with status 3');
    d.line('FAILED: module CTL crashed');
    expect(d.summary()).toBe('module CTL failed (exited with status 3)');
  });
  test("the launcher's FAILED line in its own words (died by signal, exited with status) is read as its older `crashed` was", () => {
    const c = new LauncherCrashes();
    c.line('module EST (pid 21) died by signal 11 (Segmentation fault)');
    c.line('FAILED: module EST died by signal 11 (Segmentation fault)');
    expect(c.summary()).toBe('module EST crashed (died by signal 11 (Segmentation fault)): a bad pointer: NULL, freed, or past the end of an array');
    const d = new LauncherCrashes();
    d.line('module CTL (pid 22) exited with status 3');
    d.line('FAILED: module CTL exited with status 3');
    expect(d.summary()).toBe('module CTL failed (exited with status 3)');
    expect(d.failures()).toEqual([{ module: 'CTL', how: 'exited with status 3', killed: false, initRefused: false }]);
    // a killed module's end line with the real-time bound's note is still its end
    const k = new LauncherCrashes();
    k.line('module HOG (pid 23) died by signal 9 (Killed): ran 0.5 s under SCHED_FIFO without blocking (real-time mode\'s RLIMIT_RTTIME hard limit 0.5 s)');
    k.line('FAILED: module HOG was killed (a SIGKILL the launcher did not send: another process\'s)');
    expect(k.failures()[0]).toMatchObject({ module: 'HOG', killed: true });
    expect(k.failures()[0]!.how).toMatch(/^died by signal 9 \(Killed\): ran 0.5 s/);
  });
});
