import { appendFileSync, constants, existsSync, mkdirSync, mkdtempSync, readFileSync, renameSync, rmSync, symlinkSync, writeFileSync, lstatSync, promises as fsp } from 'node:fs';
import { execFileSync, spawn } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { hostileTreeScript } from '../test-support/hostile-tree.js';
import { checkRelativePath, entryPath, openDirNoFollow, openRegularFileIn, readFileNoFollow, readUpTo, removeTreeNoFollow, syncFileNoFollow, UnsafePathError } from './safe-fs.js';

let root: string;
let outside: string;
beforeEach(() => {
  root = mkdtempSync(join(tmpdir(), 'safefs-root-'));
  outside = mkdtempSync(join(tmpdir(), 'safefs-outside-'));
  writeFileSync(join(outside, 'secret'), 'host');
});
afterEach(() => {
  rmSync(root, { recursive: true, force: true });
  rmSync(outside, { recursive: true, force: true });
});

describe('safe fs (planted links never followed)', () => {
  test('a symlinked file is replaced, its target untouched', async () => {
    symlinkSync(join(outside, 'secret'), join(root, 'main.c'));
    expect(await syncFileNoFollow(root, 'main.c', Buffer.from('int x;'))).toBe(true);
    expect(readFileSync(join(outside, 'secret'), 'utf8')).toBe('host');
    expect(lstatSync(join(root, 'main.c')).isFile()).toBe(true);
  });

  test('a symlinked directory component is refused', async () => {
    symlinkSync(outside, join(root, 'src'));
    await expect(syncFileNoFollow(root, 'src/secret', Buffer.from('x'))).rejects.toThrow(UnsafePathError);
    expect(readFileSync(join(outside, 'secret'), 'utf8')).toBe('host');
    expect(await readFileNoFollow(root, 'src/secret')).toBeNull();
  });

  test('reads whole files of any size up to the bound, none past it; a file that grew while read is read to its new end', async () => {
    for (const size of [0, 1, 4096, 70_001]) {
      const data = Buffer.from(Array.from({ length: size }, (_, i) => i % 251));
      writeFileSync(join(root, `f${size}`), data);
      expect((await readFileNoFollow(root, `f${size}`))?.equals(data)).toBe(true);
      expect((await readFileNoFollow(root, `f${size}`, size))?.equals(data)).toBe(true); // exactly the bound
      if (size > 0) expect(await readFileNoFollow(root, `f${size}`, size - 1)).toBeNull();
    }
    // opened at 10 bytes, 5,000 more appended before the read: the buffer grows to hold them
    writeFileSync(join(root, 'grows'), 'x'.repeat(10));
    const fh = await fsp.open(join(root, 'grows'), 'r');
    try {
      appendFileSync(join(root, 'grows'), 'y'.repeat(5000));
      expect((await readUpTo(fh, 1_000_000, 10)).toString()).toBe('x'.repeat(10) + 'y'.repeat(5000));
      expect((await readUpTo(fh, 4001, 10)).length).toBe(4001); // never past the limit
    } finally {
      await fh.close();
    }
  });

  test('unchanged content is not rewritten (mtime kept for make)', async () => {
    await syncFileNoFollow(root, 'a/b.c', Buffer.from('same'));
    const before = lstatSync(join(root, 'a/b.c')).mtimeMs;
    await new Promise((r) => setTimeout(r, 20));
    expect(await syncFileNoFollow(root, 'a/b.c', Buffer.from('same'))).toBe(false);
    expect(lstatSync(join(root, 'a/b.c')).mtimeMs).toBe(before);
  });

  test('removing a tree unlinks links without entering them, even in unwritable dirs', async () => {
    mkdirSync(join(root, 'd/e'), { recursive: true });
    symlinkSync(outside, join(root, 'd/e/link'));
    symlinkSync(join(outside, 'secret'), join(root, 'filelink'));
    writeFileSync(join(root, 'd/e/f'), 'x');
    const { chmodSync } = await import('node:fs');
    chmodSync(join(root, 'd/e'), 0o500);
    await removeTreeNoFollow(root);
    expect(existsSync(root)).toBe(false);
    expect(readFileSync(join(outside, 'secret'), 'utf8')).toBe('host');
  });

  test('removes a 500-level tree (path of 5,500 bytes > PATH_MAX) with chmod 000 folders, fifos and links out', async () => {
    // the shape a sandboxed program can leave (docs/sandbox.md, "Host clean-up"); a path-based
    // walk fails here with ENAMETOOLONG and leaves the tree on the host
    execFileSync('/bin/sh', ['-c', hostileTreeScript(500, outside)], { cwd: root });
    await removeTreeNoFollow(root);
    expect(existsSync(root)).toBe(false);
    expect(readFileSync(join(outside, 'secret'), 'utf8')).toBe('host');
  });

  test.each(['../x', '/abs', 'a//b', 'a/./b', '', 'a\\b'])('rejects path %j', (p) => {
    expect(() => checkRelativePath(p)).toThrow(UnsafePathError);
  });

  test('a folder opened without following: its entries by descriptor, regular files only, a link refused, a FIFO not blocking', async () => {
    mkdirSync(join(root, 'logs'));
    writeFileSync(join(root, 'logs', 'A.csv'), 'abc');
    symlinkSync(join(outside, 'secret'), join(root, 'logs', 'link.csv'));
    execFileSync('mkfifo', [join(root, 'logs', 'fifo.csv')]);
    symlinkSync(outside, join(root, 'logs-link'));
    await expect(openDirNoFollow(join(root, 'logs-link'))).rejects.toMatchObject({ code: 'ENOTDIR' }); // Linux: O_DIRECTORY meets the link itself
    const dir = await openDirNoFollow(join(root, 'logs'));
    try {
      // the folder renamed and replaced by a link to the outside: the descriptor still names the folder
      renameSync(join(root, 'logs'), join(root, 'logs.old'));
      symlinkSync(outside, join(root, 'logs'));
      const a = await openRegularFileIn(dir, 'A.csv', constants.O_RDONLY);
      expect(a?.size).toBe(3);
      await a?.fh.close();
      expect(await openRegularFileIn(dir, 'fifo.csv', constants.O_RDONLY)).toBeNull();
      await expect(openRegularFileIn(dir, 'link.csv', constants.O_RDONLY)).rejects.toMatchObject({ code: 'ELOOP' });
      await expect(openRegularFileIn(dir, 'secret', constants.O_RDONLY)).rejects.toMatchObject({ code: 'ENOENT' });
      expect(readFileSync(entryPath(dir, 'A.csv'), 'utf8')).toBe('abc');
    } finally {
      await dir.close();
    }
  });

  test('a folder swapped for a link while reads go on is never followed (no check-then-use gap)', async () => {
    // lib/ and a link to the host folder trade places as fast as a process can rename
    mkdirSync(join(root, 'lib'));
    writeFileSync(join(root, 'lib', 'f.contract'), 'project');
    writeFileSync(join(outside, 'f.contract'), 'host');
    symlinkSync(outside, join(root, 'lib_link'));
    const swapper = spawn('python3', ['-c', [
      'import os, sys, time', `os.chdir(${JSON.stringify(root)})`, 'end = time.time() + 3',
      'while time.time() < end:',
      "    os.rename('lib', 'lib_real'); os.rename('lib_link', 'lib'); os.rename('lib', 'lib_link'); os.rename('lib_real', 'lib')",
    ].join('\n')], { stdio: 'ignore' });
    const done = new Promise((r) => swapper.on('exit', r));
    let leaks = 0;
    let reads = 0;
    let exited = false;
    void done.then(() => { exited = true; });
    while (!exited) {
      const data = await readFileNoFollow(root, 'lib/f.contract');
      if (data?.toString() === 'host') leaks++;
      else if (data) reads++;
    }
    expect(leaks).toBe(0);
    expect(reads).toBeGreaterThan(0); // the race was run: reads went through between swaps
  }, 20_000);
});
