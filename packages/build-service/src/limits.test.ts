import { describe, expect, it } from 'vitest';
import { DEFAULT_READY_TIMEOUT_SECONDS } from '@contract-studio/conventions';
import { RUN_LOG_MIN_BYTES, RUN_STOP_ROOM_SECONDS, RUNTIME_LOG_MAX_BYTES, longestDuration, runLogMaxBytes } from './limits.js';

describe('longestDuration: a run asked for the longest still ends on its own', () => {
  it('keeps RUN_STOP_ROOM_SECONDS (half the limit when that is less) to start and stop the architecture', () => {
    expect(longestDuration(60)).toBe(60 - RUN_STOP_ROOM_SECONDS);
    expect(longestDuration(4)).toBe(2);
  });

  it('takes the time the modules\' inits may add past the launcher\'s default out of it, never below that default', () => {
    expect(longestDuration(60, DEFAULT_READY_TIMEOUT_SECONDS)).toBe(55);
    expect(longestDuration(60, 5)).toBe(55); // a shorter wait adds nothing
    expect(longestDuration(60, 30)).toBe(35); // 20 s more for the inits
    expect(longestDuration(60, 55)).toBe(DEFAULT_READY_TIMEOUT_SECONDS);
    expect(longestDuration(4, 2)).toBe(2); // a short limit: as without
  });
});

describe('runLogMaxBytes: a module flooding its CSV log is capped before the work dir is full', () => {
  const MiB = 1024 * 1024;
  it('is 3/4 of the room left, at most the runtime\'s 256 MiB default, at least 64 KiB', () => {
    expect(runLogMaxBytes(250 * MiB)).toBe(187.5 * MiB); // the default 256 MiB work dir less a 6 MiB build
    expect(runLogMaxBytes(16 * MiB)).toBe(12 * MiB);
    expect(runLogMaxBytes(2048 * MiB)).toBe(RUNTIME_LOG_MAX_BYTES);
    expect(RUNTIME_LOG_MAX_BYTES).toBe(256 * MiB);
    expect(runLogMaxBytes(10_000)).toBe(RUN_LOG_MIN_BYTES);
    expect(runLogMaxBytes(-5)).toBe(RUN_LOG_MIN_BYTES);
    expect(runLogMaxBytes(Number.NaN)).toBe(RUN_LOG_MIN_BYTES);
    // the runtime refuses a bound under 4 records of 1280 bytes (runtime/src/csvlog.c): never given one
    expect(RUN_LOG_MIN_BYTES).toBeGreaterThanOrEqual(4 * 1280);
    expect(Number.isInteger(runLogMaxBytes(1234567))).toBe(true);
  });
});
