import { describe, expect, it } from 'vitest';
import { DEFAULT_READY_TIMEOUT_SECONDS } from '@contract-studio/conventions';
import { RUN_STOP_ROOM_SECONDS, longestDuration } from './limits.js';

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
