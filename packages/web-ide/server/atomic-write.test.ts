import { describe, it, expect, beforeEach, afterEach } from 'vitest';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync, chmodSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { writeFileAtomic, isAtomicTempFile } from './atomic-write.js';

let dir: string;
beforeEach(() => {
  dir = mkdtempSync(join(tmpdir(), 'ide-atomic-'));
});
afterEach(() => {
  chmodSync(dir, 0o755);
  rmSync(dir, { recursive: true, force: true });
});

describe('writeFileAtomic', () => {
  it('creates a file and its parent folders', async () => {
    await writeFileAtomic(join(dir, 'a', 'b', 'c.contract'), 'datatype T {int x};');
    expect(readFileSync(join(dir, 'a', 'b', 'c.contract'), 'utf8')).toBe('datatype T {int x};');
  });

  it('replaces existing content and leaves no temp file behind', async () => {
    const f = join(dir, 'x.contract');
    writeFileSync(f, 'old');
    await writeFileAtomic(f, 'new content');
    expect(readFileSync(f, 'utf8')).toBe('new content');
    expect(readdirSync(dir)).toEqual(['x.contract']);
  });

  it('keeps the old content intact when the write fails', async () => {
    const f = join(dir, 'keep.contract');
    writeFileSync(f, 'precious user text');
    chmodSync(dir, 0o555); // folder not writable: the temp file cannot be created
    if (process.getuid?.() === 0) {
      // root ignores permissions: make the target a folder's child of a file instead
      chmodSync(dir, 0o755);
      await expect(writeFileAtomic(join(f, 'child'), 'x')).rejects.toThrow();
    } else {
      await expect(writeFileAtomic(f, 'new')).rejects.toThrow();
    }
    expect(readFileSync(f, 'utf8')).toBe('precious user text');
    expect(readdirSync(dir).filter(isAtomicTempFile)).toEqual([]);
  });

  it('concurrent writes each produce one complete version, never a mix', async () => {
    const f = join(dir, 'race.txt');
    const a = 'A'.repeat(200_000);
    const b = 'B'.repeat(200_000);
    await Promise.all([writeFileAtomic(f, a), writeFileAtomic(f, b), writeFileAtomic(f, a)]);
    const text = readFileSync(f, 'utf8');
    expect(text === a || text === b).toBe(true);
    expect(readdirSync(dir)).toEqual(['race.txt']);
  });

  it('removes the temp file a killed server left for the same target (its writer gone), not a live writer\'s nor another file\'s', async () => {
    const f = join(dir, 'big.txt');
    writeFileSync(f, 'old');
    const dead = spawnSync(process.execPath, ['-e', 'process.stdout.write(String(process.pid))'], { encoding: 'utf8' }).stdout;
    writeFileSync(join(dir, `.big.txt.tmp-${dead}`), 'half a save');
    writeFileSync(join(dir, `.big.txt.tmp-${process.pid + 0}x`), 'not a temp name');
    writeFileSync(join(dir, `.other.txt.tmp-${dead}`), 'another target: left to its own save');
    writeFileSync(join(dir, `.big.txt.tmp-${process.ppid}`), 'a live writer');
    await writeFileAtomic(f, 'new');
    expect(readFileSync(f, 'utf8')).toBe('new');
    expect(readdirSync(dir).sort()).toEqual([`.big.txt.tmp-${process.pid}x`, `.big.txt.tmp-${process.ppid}`, `.other.txt.tmp-${dead}`, 'big.txt'].sort());
  });

  it('looks for leftover temp files of a file once per process, not at every save', async () => {
    const f = join(dir, 'often.txt');
    await writeFileAtomic(f, 'first');
    const dead = spawnSync(process.execPath, ['-e', 'process.stdout.write(String(process.pid))'], { encoding: 'utf8' }).stdout;
    writeFileSync(join(dir, `.often.txt.tmp-${dead}`), 'left after this process looked');
    await writeFileAtomic(f, 'second');
    expect(readFileSync(f, 'utf8')).toBe('second');
    expect(readdirSync(dir).sort()).toEqual([`.often.txt.tmp-${dead}`, 'often.txt']); // the next server's first save removes it
  });

  it('recognises its own temp names only', () => {
    expect(isAtomicTempFile('.x.contract.tmp-123')).toBe(true);
    expect(isAtomicTempFile('x.contract')).toBe(false);
    expect(isAtomicTempFile('.hidden')).toBe(false);
  });
});
