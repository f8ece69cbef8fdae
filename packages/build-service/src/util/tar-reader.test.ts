import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { firstTarEntry, readTar } from './tar-reader.js';

const dir = mkdtempSync(join(tmpdir(), 'tar-reader-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

function tarOf(args: string[]): Buffer {
  const r = spawnSync('tar', ['-C', dir, '-cf', '-', ...args], { maxBuffer: 64 * 1024 * 1024 });
  expect(r.status, r.stderr?.toString()).toBe(0);
  return r.stdout;
}

describe('readTar on archives made by GNU tar', () => {
  const long = `${'x'.repeat(150)}.csv`;
  mkdirSync(join(dir, 'logs'));
  writeFileSync(join(dir, 'logs', 'MSC_1.csv'), 'time;value\n1;2\n');
  writeFileSync(join(dir, 'logs', long), 'long name\n');
  writeFileSync(join(dir, 'logs', 'big.bin'), Buffer.alloc(3000, 7));
  symlinkSync('/etc/passwd', join(dir, 'logs', 'planted.csv'));

  test('lists files with their bytes, directories, and links as links (never their target)', () => {
    for (const format of ['gnu', 'posix', 'ustar']) {
      const args = format === 'ustar' ? ['--format=ustar', 'logs/MSC_1.csv', 'logs/planted.csv'] : [`--format=${format}`, 'logs'];
      const entries = readTar(tarOf(args));
      const byName = new Map(entries.map((e) => [e.name, e]));
      expect(byName.get('logs/MSC_1.csv')).toMatchObject({ kind: 'file', size: 15 });
      expect(byName.get('logs/MSC_1.csv')!.data!.toString()).toBe('time;value\n1;2\n');
      expect(byName.get('logs/planted.csv')).toMatchObject({ kind: 'symlink', data: null });
      if (format !== 'ustar') {
        expect(byName.get('logs')).toMatchObject({ kind: 'dir' });
        expect(byName.get(`logs/${long}`)!.data!.toString()).toBe('long name\n');
        expect(byName.get('logs/big.bin')!.data!.equals(Buffer.alloc(3000, 7))).toBe(true);
      }
    }
  });

  test('a cut archive lists the complete entries and the cut one without data', () => {
    const full = tarOf(['--format=gnu', 'logs/MSC_1.csv', 'logs/big.bin']);
    const cut = readTar(full.subarray(0, 512 * 2 + 512 + 1000));
    expect(cut.map((e) => [e.name, e.data === null])).toEqual([
      ['logs/MSC_1.csv', false],
      ['logs/big.bin', true],
    ]);
  });

  test('a header it cannot read ends the listing (the entries before it stay), never a throw', () => {
    const tar = Buffer.from(tarOf(['--format=ustar', 'logs/MSC_1.csv', 'logs/big.bin']));
    // the second header starts after the first's 512-byte header and one 512-byte data block
    tar.write('9z9z9z9z9z9\0', 1024 + 124, 'latin1');
    let entries: ReturnType<typeof readTar> = [];
    expect(() => (entries = readTar(tar))).not.toThrow();
    expect(entries.map((e) => e.name)).toEqual(['logs/MSC_1.csv']);
  });

  test('firstTarEntry: the first file of a one-file archive read only partly, with the part of it held (a long PAX name too)', () => {
    for (const [format, name] of [['gnu', 'logs/big.bin'], ['pax', `logs/${long}`]] as const) {
      const full = tarOf([`--format=${format}`, name]);
      const whole = firstTarEntry(full)!;
      expect(whole).toMatchObject({ name, kind: 'file' });
      expect(whole.data!.length).toBe(whole.size);
      // cut a few bytes into the body: those bytes, the declared size kept
      const headers = full.indexOf(whole.data!);
      const held = Math.min(5, whole.size - 1);
      const cut = firstTarEntry(full.subarray(0, headers + held))!;
      expect(cut).toMatchObject({ name, kind: 'file', size: whole.size });
      expect(cut.data!.equals(whole.data!.subarray(0, held))).toBe(true);
    }
    expect(firstTarEntry(Buffer.alloc(100))).toBeNull();
    expect(firstTarEntry(tarOf(['--format=gnu', 'logs/planted.csv']))).toMatchObject({ kind: 'symlink', data: null });
  });
});
