/**
 * Empties a build cache folder (`contract cache clear`): each kept project workspace is taken
 * under its lock (a build using it finishes first), its work tmpfs unmounted (a root service keeps
 * work trees mounted between commands: docs/sandbox.md "The disk limit"; plain `rm -rf` would stop
 * at them with EBUSY), then the whole folder is removed without following links — only when it
 * holds nothing but what a build cache holds: a folder named by mistake (`--cache-dir "$UNSET"`
 * was the current folder) is refused, nothing removed.
 */
import { readdirSync, rmdirSync } from 'node:fs';
import { join } from 'node:path';
import { unmountWorkDisk } from '../sandbox/work-disk.js';
import { removeTreeNoFollow } from '../util/safe-fs.js';
import { CACHE_ENTRIES, checkCacheEntry } from './cache-dir.js';
import { acquireProjectLock } from './project-lock.js';

/** What the top of a build cache holds: its entries, and `ws` (a service's one-off work trees, removed when it stops). */
const CACHE_TOP: ReadonlySet<string> = new Set([...CACHE_ENTRIES, 'ws']);

/**
 * Removes `dir` (a cache folder); `onWait` is told when a build still uses one of its projects.
 * Throws, having removed nothing, when `dir` holds anything a build cache does not.
 */
export async function clearCache(dir: string, onWait: (holder: string) => void = () => {}): Promise<void> {
  const problem = checkCacheEntry(dir);
  if (problem) throw new Error(problem);
  const strangers = readdirSync(dir).filter((name) => !CACHE_TOP.has(name));
  if (strangers.length) {
    const named = strangers.slice(0, 5).map((n) => JSON.stringify(n.slice(0, 80))).join(', ') + (strangers.length > 5 ? ` and ${strangers.length - 5} more` : '');
    throw new Error(`refusing to clear ${dir}: it holds what a build cache does not (${named}), so it is not one; a build cache holds ${[...CACHE_TOP].join('/, ')}/ only. Nothing was removed`);
  }
  const projects = join(dir, 'projects');
  let ids: string[] = [];
  try {
    ids = readdirSync(projects);
  } catch {
    /* no kept project */
  }
  for (const id of ids) {
    const root = join(projects, id);
    if (checkCacheEntry(root)) continue; // not one of ours: removed below without being followed
    const lock = await acquireProjectLock(join(root, 'lock'), onWait);
    try {
      await unmountWorkDisk(join(root, 'work'));
    } finally {
      await lock.release();
    }
  }
  for (const name of readdirSync(dir)) if (CACHE_TOP.has(name)) await removeTreeNoFollow(join(dir, name));
  // the folder itself once empty (a build that made an entry meanwhile keeps it)
  try {
    rmdirSync(dir);
  } catch {
    /* not empty any more */
  }
}
