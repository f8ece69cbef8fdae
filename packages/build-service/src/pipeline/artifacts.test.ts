import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { collectRunArtifacts, hostWorkDirReader } from './artifacts.js';

let work: string;
let outside: string;
beforeEach(() => {
  work = mkdtempSync(join(tmpdir(), 'artifacts-work-'));
  outside = mkdtempSync(join(tmpdir(), 'artifacts-host-'));
  writeFileSync(join(outside, 'secret.csv'), 'host secret\n');
});
afterEach(() => {
  rmSync(work, { recursive: true, force: true });
  rmSync(outside, { recursive: true, force: true });
});

describe('collectRunArtifacts on a host work dir (bwrap, none)', () => {
  test('takes the regular files of logs/, never a planted link, and says what it left out', async () => {
    mkdirSync(join(work, 'logs'));
    mkdirSync(join(work, 'run'));
    writeFileSync(join(work, 'logs', 'MAA_21-Nov-2026-22h57m07s.csv'), 'a;b\n1;2\n');
    writeFileSync(join(work, 'logs', 'ORD_x.csv'), 'c\n');
    symlinkSync(join(outside, 'secret.csv'), join(work, 'logs', 'planted.csv'));
    symlinkSync(outside, join(work, 'logs', 'dirlink'));
    mkdirSync(join(work, 'logs', 'sub'));
    writeFileSync(join(work, 'logs', '.hidden'), 'h');
    writeFileSync(join(work, 'run', 'MAA.sock'), '');
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files.map((f) => [f.name, f.path, f.size, f.data.toString()])).toEqual([
      ['MAA_21-Nov-2026-22h57m07s.csv', 'logs/MAA_21-Nov-2026-22h57m07s.csv', 8, 'a;b\n1;2\n'],
      ['ORD_x.csv', 'logs/ORD_x.csv', 2, 'c\n'],
    ]);
    expect(Object.fromEntries(a.skipped.map((s) => [s.name, s.reason]))).toEqual({
      '.hidden': 'name not allowed (letters, digits, _ . - only)',
      dirlink: 'not a regular file (symlink): not followed',
      'planted.csv': 'not a regular file (symlink): not followed',
      sub: 'not a regular file (dir): not followed',
    });
    expect(a.runDirLeftovers).toEqual(['MAA.sock']);
    expect(a.files.some((f) => f.data.toString().includes('host secret'))).toBe(false);
  });

  test('a logs/ that is a link is not entered', async () => {
    symlinkSync(outside, join(work, 'logs'));
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files).toEqual([]);
    expect(a.skipped).toEqual([{ name: 'logs', reason: 'logs/ is a symlink, not a directory: not followed' }]);
  });

  test('no logs/ at all gives an empty result', async () => {
    expect(await collectRunArtifacts(hostWorkDirReader, work)).toEqual({ files: [], skipped: [], runDirLeftovers: [] });
  });

  test('file count, file size and total size are bounded', async () => {
    mkdirSync(join(work, 'logs'));
    for (const [name, size] of [['a.csv', 10], ['b.csv', 60], ['c.csv', 30], ['d.csv', 30], ['e.csv', 1]] as const) {
      writeFileSync(join(work, 'logs', name), Buffer.alloc(size, 65));
    }
    const a = await collectRunArtifacts(hostWorkDirReader, work, { files: 3, fileBytes: 50, totalBytes: 45 });
    expect(a.files.map((f) => f.name)).toEqual(['a.csv', 'c.csv', 'e.csv']);
    expect(a.skipped).toEqual([
      { name: 'b.csv', reason: '60 bytes, above the 50-byte file bound' },
      { name: 'd.csv', reason: 'the 45-byte total bound is reached' },
    ]);
    const few = await collectRunArtifacts(hostWorkDirReader, work, { files: 2, fileBytes: 100, totalBytes: 1000 });
    expect(few.files.map((f) => f.name)).toEqual(['a.csv', 'b.csv']);
    expect(few.skipped.map((s) => s.reason)).toEqual(['more than 2 files', 'more than 2 files', 'more than 2 files']);
  });
});
