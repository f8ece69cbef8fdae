import { describe, expect, it } from 'vitest';
import { DEFAULT_READY_TIMEOUT_SECONDS } from '@contract-studio/conventions';
import { ARTIFACT_BOUNDS } from './pipeline/artifacts.js';
import { DEFAULT_LIMITS, MIN_WHOLE_LIMIT, RUN_LOG_MAX_BYTES, RUN_LOG_MIN_BYTES, RUN_STOP_ROOM_SECONDS, RUNTIME_LOG_MAX_BYTES, longestDuration, memoryHeldByFiles, mergeLimits, runLogDiskReserve, runLogMaxBytes } from './limits.js';

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
  it('is 3/4 of the room left, at most what the service collects of a log (1 GiB), at least 64 KiB', () => {
    expect(runLogMaxBytes(250 * MiB)).toBe(187.5 * MiB); // the default 256 MiB work dir less a 6 MiB build
    expect(runLogMaxBytes(16 * MiB)).toBe(12 * MiB);
    // a large work dir keeps a longer log, past the runtime's own 256 MiB default: a 1 GiB work dir
    // less a 6 MiB build gives ORD (0.7 MB/s at 1 kHz) about 18 minutes, not 6.5
    expect(runLogMaxBytes(1018 * MiB)).toBe(763.5 * MiB);
    expect(runLogMaxBytes(1018 * MiB)).toBeGreaterThan(RUNTIME_LOG_MAX_BYTES);
    expect(runLogMaxBytes(2048 * MiB)).toBe(RUN_LOG_MAX_BYTES);
    expect(runLogMaxBytes(64 * 1024 * MiB)).toBe(RUN_LOG_MAX_BYTES);
    expect(RUN_LOG_MAX_BYTES).toBe(1024 * MiB);
    // the service collects that much of a log: half of what it collects of a run
    expect(RUN_LOG_MAX_BYTES * 2).toBeLessThanOrEqual(ARTIFACT_BOUNDS.totalBytes);
    expect(RUNTIME_LOG_MAX_BYTES).toBe(256 * MiB);
    expect(runLogMaxBytes(10_000)).toBe(RUN_LOG_MIN_BYTES);
    expect(runLogMaxBytes(-5)).toBe(RUN_LOG_MIN_BYTES);
    expect(runLogMaxBytes(Number.NaN)).toBe(RUN_LOG_MIN_BYTES);
    // the runtime refuses a bound under 4 records of 1280 bytes (runtime/src/csvlog.c): never given one
    expect(RUN_LOG_MIN_BYTES).toBeGreaterThanOrEqual(4 * 1280);
    expect(Number.isInteger(runLogMaxBytes(1234567))).toBe(true);
  });
});

describe('memoryHeldByFiles: a memory limit hit whose memory the job\'s tmpfs files held', () => {
  const MiB = 1024 * 1024;
  it('gives those bytes when they are half of the limit or more; else, or for another limit, undefined', () => {
    const hit = { name: 'memory' as const, value: 512 * MiB, unit: 'bytes' as const, mechanism: 'cgroup-v2' as const };
    expect(memoryHeldByFiles({ ...hit, memoryFilesBytes: 256 * MiB })).toBe(256 * MiB);
    expect(memoryHeldByFiles({ ...hit, memoryFilesBytes: 255 * MiB })).toBeUndefined();
    expect(memoryHeldByFiles(hit)).toBeUndefined(); // not read (rlimit-as, a cgroup that did not say)
    expect(memoryHeldByFiles({ name: 'workDiskMiB', value: 256 * MiB, unit: 'bytes', mechanism: 'tmpfs-size', memoryFilesBytes: 256 * MiB })).toBeUndefined();
  });
});

describe('runLogDiskReserve: the logs together stop before the work dir, or the memory its files take, is full', () => {
  const MiB = 1024 * 1024;
  it('keeps a sixteenth of the work dir (at least 1 MiB) free of modules\' logs, a quarter of that of ORD\'s, an eighth of a supervisor\'s', () => {
    expect(runLogDiskReserve(DEFAULT_LIMITS, true)).toEqual({ modules: 16 * MiB, ord: 4 * MiB, supervisors: 2 * MiB, usable: 256 * MiB, unusable: 0 });
    expect(runLogDiskReserve({ ...DEFAULT_LIMITS, workDiskMiB: 8 }, true)).toMatchObject({ modules: MiB, ord: MiB / 4, supervisors: MiB / 8 });
  });
  it('keeps out of the logs\' reach the part of a tmpfs work dir the memory limit cannot hold beside the processes', () => {
    // the field run: a 3 GiB work dir under 512 MiB of memory; the logs filled the memory and the OOM killer ended every process
    const r = runLogDiskReserve({ ...DEFAULT_LIMITS, workDiskMiB: 3072 }, true);
    expect(r.usable).toBe(384 * MiB); // 512 MiB less a quarter kept for the processes
    expect(r.unusable).toBe(2688 * MiB);
    expect(r).toMatchObject({ modules: 2688 * MiB + 24 * MiB, ord: 2688 * MiB + 6 * MiB, supervisors: 2688 * MiB + 3 * MiB });
    expect(runLogDiskReserve({ ...DEFAULT_LIMITS, memoryMiB: 96 }, true).usable).toBe(72 * MiB);
    expect(runLogDiskReserve({ ...DEFAULT_LIMITS, memoryMiB: 32 }, true).usable).toBe(16 * MiB); // at least 16 MiB for the processes
    // a work dir whose files are not memory (sandbox none): the disk limit alone
    expect(runLogDiskReserve({ ...DEFAULT_LIMITS, workDiskMiB: 3072 }, false)).toMatchObject({ usable: 3072 * MiB, unusable: 0 });
  });
});

describe('mergeLimits with the values as written (contract serve --limit NAME=VALUE)', () => {
  const refusal = (name: string, text: string): string => {
    try {
      mergeLimits(DEFAULT_LIMITS, { [name]: Number(text) }, false, { [name]: text });
    } catch (e) {
      return (e as Error).message;
    }
    return 'accepted';
  };

  it('quotes the text in a refusal, not the number it became (17 digits and more are rounded)', () => {
    expect(refusal('processes', '12345678901234567')).toBe('limit processes must be at most 4194304, got 12345678901234567');
    expect(refusal('modelBytes', '9007199254740993')).toBe('limit modelBytes must be at most 9007199254740991, got 9007199254740993');
    expect(refusal('runSeconds', '99999999999999999999')).toBe('limit runSeconds must be at most 2147483 s (about 24.8 days, a timer\'s range), got 99999999999999999999');
    expect(refusal('runSeconds', '0.00010000000000000000001')).toBe('limit runSeconds must be at least 0.001 s, got 0.00010000000000000000001');
  });

  it('refuses a count or a size whose text is no whole number, even when the number it became is one', () => {
    expect(refusal('generatedFiles', '10.0000000000000001')).toBe('limit generatedFiles must be a whole number (a count or a size), got 10.0000000000000001');
    expect(refusal('memoryMiB', '1023.99999999999999')).toBe('limit memoryMiB must be a whole number (a count or a size), got 1023.99999999999999');
    expect(refusal('generatedFiles', '10.0')).toBe('accepted');
    expect(refusal('modelBytes', '9007199254740991')).toBe('accepted');
    expect(refusal('runSeconds', '3660.5')).toBe('accepted');
  });
});

describe('the least memoryMiB, one minimum for every sandbox (MIN_WHOLE_LIMIT)', () => {
  it('refuses a memory limit under 32 MiB, naming the minimum (Docker refused 1 MiB only after the job was accepted; at 16 MiB the prepare of a changed model stopped)', () => {
    expect(MIN_WHOLE_LIMIT.memoryMiB).toBe(32);
    expect(() => mergeLimits(DEFAULT_LIMITS, { memoryMiB: 1 }, true)).toThrow('limit memoryMiB must be at least 32 MiB (the least every sandbox can enforce and run a build in), got 1');
    expect(() => mergeLimits(DEFAULT_LIMITS, { memoryMiB: 31 }, true)).toThrow(/at least 32 MiB/);
    expect(mergeLimits(DEFAULT_LIMITS, { memoryMiB: 32 }, true).memoryMiB).toBe(32);
  });
});
