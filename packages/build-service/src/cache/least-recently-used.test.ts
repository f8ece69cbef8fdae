/** The build cache's bound on kept entries (least-recently-used.ts) on a real folder. */
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, statSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { SERVICE_BOUNDS } from '../limits.js';
import { GenerationCache } from './generation-cache.js';
import { CACHE_ENTRY_IDLE_MS, markUsed, removeLeastRecentlyUsed } from './least-recently-used.js';

const scratch = mkdtempSync(join(tmpdir(), 'lru-test-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));
const HOUR = 3_600_000;
const age = (path: string, ms: number) => {
  const t = (Date.now() - ms) / 1000;
  utimesSync(path, t, t);
};

describe('removeLeastRecentlyUsed', () => {
  test('removes the least recently used beyond the kept number, never one used within the idle time, nothing else', async () => {
    const dir = join(scratch, 'entries');
    mkdirSync(dir);
    const entry = (name: string, usedMsAgo: number, folder = true) => {
      const p = join(dir, name);
      if (folder) {
        mkdirSync(p);
        writeFileSync(join(p, 'contract-sim'), 'x');
      } else writeFileSync(p, 'x');
      age(p, usedMsAgo);
    };
    entry('sim-a', 40 * 60_000);
    entry('sim-b', 5 * HOUR);
    entry('sim-c', 9 * HOUR, false); // a file entry
    entry('sim-d', 7 * HOUR);
    entry('sim-e', 2 * HOUR);
    entry('other', 100 * HOUR); // not named by the pattern
    symlinkSync('/etc', join(dir, 'sim-link')); // a link: never followed nor removed
    // keep 2: a (40 min), e (2 h); b, d, c beyond it
    expect((await removeLeastRecentlyUsed(dir, /^sim-/, 2)).sort()).toEqual(['sim-b', 'sim-c', 'sim-d']);
    expect(readdirSync(dir).sort()).toEqual(['other', 'sim-a', 'sim-e', 'sim-link']);
    expect(existsSync('/etc/passwd')).toBe(true);
    // within the idle time (a, f), kept whatever the bound
    entry('sim-f', CACHE_ENTRY_IDLE_MS / 2);
    expect(await removeLeastRecentlyUsed(dir, /^sim-/, 1)).toEqual(['sim-e']);
    expect(readdirSync(dir).sort()).toEqual(['other', 'sim-a', 'sim-f', 'sim-link']);
    // under the bound: nothing; a missing folder: nothing, no throw
    expect(await removeLeastRecentlyUsed(dir, /^sim-/, 10)).toEqual([]);
    expect(await removeLeastRecentlyUsed(join(scratch, 'none'), /^sim-/, 0)).toEqual([]);
  });

  test('markUsed sets the last use to now; on a missing path it does nothing', async () => {
    const p = join(scratch, 'used');
    writeFileSync(p, 'x');
    age(p, 50 * HOUR);
    await markUsed(p);
    expect(Date.now() - statSync(p).mtimeMs).toBeLessThan(60_000);
    await markUsed(join(scratch, 'missing'));
  });
});

describe('GenerationCache keeps keptGeneratedTrees entries', () => {
  test('a new entry removes the least recently used beyond the bound and a killed writer\'s temporary file', async () => {
    const dir = join(scratch, 'generated');
    mkdirSync(dir, { mode: 0o700 });
    const kept = SERVICE_BOUNDS.keptGeneratedTrees;
    const names = Array.from({ length: kept }, (_, i) => `${i.toString(16).padStart(32, '0')}.json.gz`);
    names.forEach((n, i) => {
      writeFileSync(join(dir, n), 'an earlier tree');
      age(join(dir, n), (i === 0 ? 48 : 24) * HOUR - i * 1000);
    });
    const dead = spawnSync('true').pid!;
    const tmp = join(dir, `.${names[1]}.deadbeef.tmp-${dead}`);
    writeFileSync(tmp, 'half an entry');
    age(tmp, 20 * 60_000);
    const cache = new GenerationCache(dir);
    await cache.put('new inputs', { problems: [], written: 1, unchanged: 0, files: new Map([['a.c', { data: Buffer.from('int a;\n'), executable: false }]]) });
    const left = readdirSync(dir);
    expect(left).not.toContain(names[0]); // the least recently used
    expect(left).not.toContain(`.${names[1]}.deadbeef.tmp-${dead}`);
    expect(left.filter((n) => /^[0-9a-f]{32}\.json\.gz$/.test(n))).toHaveLength(kept);
    expect(await cache.get('new inputs')).toMatchObject({ written: 1 });
  });
});
