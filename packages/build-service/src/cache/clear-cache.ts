/**
 * Empties a build cache folder (`contract cache clear`): each kept project workspace is taken
 * under its lock (a build using it finishes first), its work tmpfs unmounted (a root service keeps
 * work trees mounted between commands: docs/sandbox.md "The disk limit"; plain `rm -rf` would stop
 * at them with EBUSY), then the whole folder is removed without following links.
 */
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { unmountWorkDisk } from '../sandbox/work-disk.js';
import { removeTreeNoFollow } from '../util/safe-fs.js';
import { checkCacheEntry } from './cache-dir.js';
import { acquireProjectLock } from './project-lock.js';

/** Removes `dir` (a cache folder); `onWait` is told when a build still uses one of its projects. */
export async function clearCache(dir: string, onWait: (holder: string) => void = () => {}): Promise<void> {
  const problem = checkCacheEntry(dir);
  if (problem) throw new Error(problem);
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
  await removeTreeNoFollow(dir);
}
