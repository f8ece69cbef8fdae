import { describe, expect, it } from 'vitest';
import { isLauncherNews } from './launcher-lines.js';

describe("the launcher's lines", () => {
  it('news of a run that goes well is told as news', () => {
    for (const line of [
      'run directory /tmp/contract-run-abc',
      'modules pinned to CPUs 0',
      '5 module(s) running',
      'started GLB.mission(consigne={1.0,2.0,3.0})',
      'stopping',
      'stopping: the job was cancelled',
      "stopping: the build service's memory limit was reached",
      "stopping: the run's duration (6 s) is over",
      'stopping: SIGINT from the terminal',
      'stopping: SIGTERM from module ORD (pid 812)',
      'stopping: make kill (contract-launch --kill, pid 4242)',
      'module LOC (pid 15) exited with status 0',
      'module MAA (pid 25) terminated by signal 15 (Terminated)',
      'all modules stopped cleanly',
    ]) expect(isLauncherNews(line), line).toBe(true);
  });

  it('a problem keeps the error colour', () => {
    for (const line of [
      'module VEL (pid 31) died by signal 11 (Segmentation fault)',
      'module VEL (pid 31) exited with status 3',
      'module MAA (pid 25) terminated by signal 9 (Killed)',
      'FAILED: module VEL crashed',
      'all modules stopped',
      'SUP refused to start action(consigne={1.0,2.0,3.0})',
      'module MIS is not ready after 10 s: its init has not returned (does its init region loop or block?); the run stops without its start request',
      'sent the start request to GLB.mission() (no acknowledgement within 2 s)',
      'module ORD did not end within 2 s: stopping the others',
      // a module's own line that merely looks like news is not the launcher's: only the launcher's source is asked
      'module LOC (pid 15) exited with status 0 and more',
    ]) expect(isLauncherNews(line), line).toBe(false);
  });
});
