/**
 * The bound of the build cache's kept entries (docs/getting-started.md "The build cache"): built
 * simulators (`sim/sim-<key>/`) and generated trees (`generated/<key>.json.gz`) get a new key for
 * every model a user builds or simulates, so without a bound the cache grows with every edit (a
 * simulator is about 0.6 MB). Each use marks its entry (markUsed: its mtime set to now); each
 * new entry first removes the least recently used beyond the kept number (removeLeastRecentlyUsed),
 * never one used in the last CACHE_ENTRY_IDLE_MS (another process may be about to run it). Links and
 * other names are left alone, nothing is followed.
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { removeTreeNoFollow } from '../util/safe-fs.js';

/** An entry used this recently is kept whatever the bound: a process may hold its path. */
export const CACHE_ENTRY_IDLE_MS = 60 * 60_000;

/** Marks `path` (a cache entry: folder or file) as used now. Never throws. */
export async function markUsed(path: string, now = new Date()): Promise<void> {
  await fsp.utimes(path, now, now).catch(() => {});
}

/**
 * Removes the entries of `dir` named by `pattern` beyond the `keep` most recently used (last use =
 * mtime), unless used within CACHE_ENTRY_IDLE_MS. Returns the names removed. Never throws.
 */
export async function removeLeastRecentlyUsed(dir: string, pattern: RegExp, keep: number, now = Date.now()): Promise<string[]> {
  let names: string[];
  try {
    names = (await fsp.readdir(dir)).filter((n) => pattern.test(n));
  } catch {
    return [];
  }
  if (names.length <= keep) return [];
  const entries: Array<{ name: string; used: number; folder: boolean }> = [];
  for (const name of names) {
    const st = await fsp.lstat(join(dir, name)).catch(() => undefined);
    if (st && (st.isDirectory() || st.isFile())) entries.push({ name, used: st.mtimeMs, folder: st.isDirectory() });
  }
  entries.sort((a, b) => b.used - a.used || (a.name < b.name ? -1 : 1));
  const removed: string[] = [];
  for (const e of entries.slice(keep)) {
    if (now - e.used < CACHE_ENTRY_IDLE_MS) continue;
    try {
      if (e.folder) await removeTreeNoFollow(join(dir, e.name));
      else await fsp.unlink(join(dir, e.name));
      removed.push(e.name);
    } catch {
      /* left: the next new entry tries again */
    }
  }
  return removed;
}
