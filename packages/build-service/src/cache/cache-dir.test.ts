/**
 * Where the build cache is (option, environment, XDG, home, root's default) and when a cache
 * folder is refused: a link, another owner, writable by others, a link planted in place of one of
 * its entries, a folder the job uids cannot reach (docs/getting-started.md "The build cache").
 */
import { chmodSync, chownSync, mkdirSync, mkdtempSync, rmSync, symlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { checkCacheEntry, prepareCacheDir, resolveCacheDir } from './cache-dir.js';

const scratch = mkdtempSync(join(tmpdir(), 'cache-dir-test-'));
chmodSync(scratch, 0o711);
afterAll(() => rmSync(scratch, { recursive: true, force: true }));
let n = 0;
const fresh = (): string => join(scratch, `c${n++}`);
const isRoot = process.getuid?.() === 0;

describe('resolveCacheDir', () => {
  test('an option wins, then CONTRACT_CACHE_DIR, then XDG_CACHE_HOME, then ~/.cache (root: /var/cache)', () => {
    const env = { CONTRACT_CACHE_DIR: '/env/cache', XDG_CACHE_HOME: '/xdg' };
    expect(resolveCacheDir('rel/c', env, 1000, '/home/u', '/work')).toEqual({ dir: '/work/rel/c', source: 'option' });
    expect(resolveCacheDir(undefined, env, 1000, '/home/u')).toEqual({ dir: '/env/cache', source: 'env' });
    expect(resolveCacheDir(undefined, { XDG_CACHE_HOME: '/xdg' }, 1000, '/home/u')).toEqual({ dir: '/xdg/contract-studio', source: 'xdg' });
    expect(resolveCacheDir(undefined, {}, 1000, '/home/u')).toEqual({ dir: '/home/u/.cache/contract-studio', source: 'home' });
    expect(resolveCacheDir(undefined, {}, 0, '/root')).toEqual({ dir: '/var/cache/contract-studio', source: 'root default' });
    // a relative XDG_CACHE_HOME is invalid (XDG Base Directory) and ignored
    expect(resolveCacheDir(undefined, { XDG_CACHE_HOME: 'rel' }, 1000, '/home/u').source).toBe('home');
  });
});

describe('prepareCacheDir', () => {
  test('creates a missing folder and accepts it', () => {
    const dir = join(fresh(), 'a', 'b');
    expect(prepareCacheDir(dir, false)).toBeNull();
    expect(checkCacheEntry(dir)).toBeNull();
  });

  test('refuses a link as the cache folder', () => {
    const real = fresh();
    mkdirSync(real);
    const link = fresh();
    symlinkSync(real, link);
    expect(prepareCacheDir(link, false)).toMatch(/is a symbolic link/);
  });

  test('refuses a folder writable by others, naming the mode and the fix', () => {
    const dir = fresh();
    mkdirSync(dir);
    chmodSync(dir, 0o777);
    const msg = prepareCacheDir(dir, false);
    expect(msg).toMatch(/writable by every user \(mode 777\)/);
    expect(msg).toMatch(/--cache-dir DIR or CONTRACT_CACHE_DIR=DIR/);
  });

  test.runIf(isRoot)('refuses a folder of another user', () => {
    const dir = fresh();
    mkdirSync(dir, { mode: 0o755 });
    chownSync(dir, 4242, 4242);
    expect(prepareCacheDir(dir, false)).toMatch(/belongs to uid 4242, not to you/);
  });

  test('refuses a link planted in place of runtime/, projects/ or sim/ (the simulator\'s harnesses)', () => {
    for (const entry of ['runtime', 'projects', 'sim']) {
      const dir = fresh();
      mkdirSync(dir, { mode: 0o711 });
      symlinkSync('/etc', join(dir, entry));
      expect(prepareCacheDir(dir, false)).toMatch(new RegExp(`${entry} is a symbolic link \\(planted\\?\\)`));
    }
  });

  test('refuses a folder the sandboxed job uids cannot reach', () => {
    const parent = fresh();
    mkdirSync(parent, { mode: 0o700 });
    chmodSync(parent, 0o700);
    const msg = prepareCacheDir(join(parent, 'cache'), true);
    expect(msg).toMatch(new RegExp(`cannot reach the cache folder .*\\(${parent} is not searchable by others\\)`));
    expect(prepareCacheDir(join(parent, 'cache'), false)).toBeNull();
  });
});
