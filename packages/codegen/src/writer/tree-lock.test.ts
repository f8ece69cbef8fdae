/**
 * The write lock of a generated tree (tree-lock.ts): taken and released, waited for while another
 * live process holds it, taken over from a writer killed mid-write, never followed through a link.
 */
import { describe, it, expect, afterAll } from 'vitest';
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { hostname, tmpdir } from 'node:os';
import { join } from 'node:path';
import { TREE_LOCK_NAME, lockTree, lockTreeSync, tryTreeLock } from './tree-lock.js';

const base = mkdtempSync(join(tmpdir(), 'tree-lock-'));
afterAll(() => rmSync(base, { recursive: true, force: true }));
const folder = (name: string) => {
  const dir = join(base, name);
  spawnSync('mkdir', ['-p', dir]);
  return dir;
};

describe('the write lock of a generated tree', () => {
  it('is a file holding the pid and host, removed when released; re-entrant in its process', () => {
    const dir = folder('plain');
    const release = lockTreeSync(dir, 'plain');
    expect(readFileSync(join(dir, TREE_LOCK_NAME), 'utf8')).toBe(`${process.pid} ${hostname()}\n`);
    // re-entrant in the process that holds it: taken again, released once per take
    const again = tryTreeLock(dir);
    expect(typeof again).toBe('function');
    (again as () => void)();
    expect(existsSync(join(dir, TREE_LOCK_NAME))).toBe(true);
    release();
    expect(existsSync(join(dir, TREE_LOCK_NAME))).toBe(false);
  });

  it('is taken over from a writer that no longer runs, another machine\'s, or a lock with no pid for long (a young one is being written)', () => {
    const dir = folder('stale');
    const dead = spawnSync(process.execPath, ['-e', 'process.stdout.write(String(process.pid))'], { encoding: 'utf8' }).stdout;
    writeFileSync(join(dir, TREE_LOCK_NAME), `${dead}\n`);
    lockTreeSync(dir, 'stale', 1000)();
    // garbage (no lock of ours): taken over
    writeFileSync(join(dir, TREE_LOCK_NAME), 'garbage');
    lockTreeSync(dir, 'stale', 1000)();
    // an empty lock: one being written while young (waited for), stale once older than 2 s
    writeFileSync(join(dir, TREE_LOCK_NAME), '');
    expect(tryTreeLock(dir)).toEqual({ holder: undefined });
    utimesSync(join(dir, TREE_LOCK_NAME), new Date(Date.now() - 5000), new Date(Date.now() - 5000));
    lockTreeSync(dir, 'stale', 1000)();
    // another machine's lock (a src-gen committed with one in it): its pid, alive here or not, means nothing
    writeFileSync(join(dir, TREE_LOCK_NAME), `${process.ppid} another-host\n`);
    lockTreeSync(dir, 'stale', 1000)();
    expect(existsSync(join(dir, TREE_LOCK_NAME))).toBe(false);
  });

  it('is waited for while a live process holds it, then taken; past the wait, the error names the holder', async () => {
    const dir = folder('held');
    const holder = spawn(process.execPath, ['-e', 'setTimeout(() => {}, 60000)']);
    writeFileSync(join(dir, TREE_LOCK_NAME), `${holder.pid}\n`);
    try {
      await expect(lockTree(dir, 'robot/src-gen', 300)).rejects.toThrow(`robot/src-gen is being written by another process (pid ${holder.pid}: a contract generate or rename, or the IDE server) for more than 0.3 s: try again when it has finished (or remove its .contract-lock if no such process runs)`);
      const started = Date.now();
      setTimeout(() => rmSync(join(dir, TREE_LOCK_NAME)), 200);
      const release = await lockTree(dir, 'robot/src-gen', 5000);
      expect(Date.now() - started).toBeGreaterThanOrEqual(150);
      release();
    } finally {
      holder.kill();
    }
  });

  it('is never taken through a link planted in its place (the link is not followed, the file it names untouched)', () => {
    const dir = folder('linked');
    writeFileSync(join(base, 'victim'), 'victim\n');
    symlinkSync(join(base, 'victim'), join(dir, TREE_LOCK_NAME));
    lockTreeSync(dir, 'linked', 1000)(); // a link with no pid in it: removed as stale, never written through
    expect(readFileSync(join(base, 'victim'), 'utf8')).toBe('victim\n');
  });

  it('is held by writeTree while it writes, and released after (no lock file left in the tree)', async () => {
    const dir = folder('tree');
    const held = spawn(process.execPath, ['-e', 'setTimeout(() => {}, 60000)']);
    writeFileSync(join(dir, TREE_LOCK_NAME), `${held.pid}\n`);
    try {
      // a generate in another process: loaded, it says so, then writes (waiting for the other writer)
      const child = spawn(process.execPath, ['--input-type=module', '-e', `
        const { writeTree } = await import(${JSON.stringify(new URL('../../dist/index.js', import.meta.url).pathname)});
        console.log('ready'); const t = Date.now(); writeTree(process.argv[1], [{ path: 'generated/a.c', content: 'int a;\\n' }]); console.log(Date.now() - t);`, dir]);
      let out = '';
      const exited = new Promise<number | null>((resolve) => child.on('exit', resolve));
      await new Promise<void>((resolve) => child.stdout.on('data', (d: Buffer) => { out += d.toString(); if (out.includes('ready')) resolve(); }));
      await new Promise((r) => setTimeout(r, 300)); // the other writer ends 300 ms on
      rmSync(join(dir, TREE_LOCK_NAME));
      expect(await exited).toBe(0);
      expect(Number(out.split('\n')[1])).toBeGreaterThanOrEqual(250);
      expect(readFileSync(join(dir, 'generated', 'a.c'), 'utf8')).toBe('int a;\n');
      expect(existsSync(join(dir, TREE_LOCK_NAME))).toBe(false);
    } finally {
      held.kill();
    }
  });

  it('keeps writers out of each other: 4 processes taking it 300 times each never overlap (an empty lock taken for stale let 8,700 in 180,000 overlap)', async () => {
    const dir = folder('mutex');
    const worker = `
      const { lockTreeSync } = await import(${JSON.stringify(new URL('../../dist/index.js', import.meta.url).pathname)});
      const { openSync, closeSync, unlinkSync, constants } = await import('node:fs');
      const [dir, rounds] = [process.argv[1], Number(process.argv[2])];
      let overlaps = 0;
      for (let i = 0; i < rounds; i++) {
        const release = lockTreeSync(dir, 'mutex', 20000);
        let fd;
        try { fd = openSync(dir + '/inside', constants.O_CREAT | constants.O_EXCL | constants.O_WRONLY); } catch { overlaps++; release(); continue; }
        for (let k = 0; k < 2000; k++); // a little work inside
        closeSync(fd); unlinkSync(dir + '/inside');
        release();
      }
      console.log(overlaps);`;
    const runs = Array.from({ length: 4 }, () => new Promise<number>((resolve) => {
      const child = spawn(process.execPath, ['--input-type=module', '-e', worker, dir, '300']);
      let out = '';
      child.stdout.on('data', (d: Buffer) => { out += d.toString(); });
      child.on('exit', () => resolve(Number(out.trim())));
    }));
    expect(await Promise.all(runs)).toEqual([0, 0, 0, 0]);
    expect(existsSync(join(dir, TREE_LOCK_NAME))).toBe(false);
  }, 120_000);
});
