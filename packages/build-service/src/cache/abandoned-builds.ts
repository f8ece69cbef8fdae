/**
 * The build folders of processes that ended without finishing them: a runtime or simulator build
 * is made in a folder named after its process (`.building-<key>-<pid>-...`, `sim-<key>.tmp-<pid>-...`)
 * and renamed into place when done, so a build killed with SIGKILL (or a machine that lost power)
 * leaves its folder behind, never used. The next build in the same cache removes them (the
 * generator's stale temporary files are its twin for single files: codegen writer/stale-temp.ts).
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { pidAlive } from '@contract-studio/codegen/stale-temp';
import { removeTreeNoFollow } from '../util/safe-fs.js';

/** A folder changed this recently is kept even when its pid is gone: a build takes seconds, and the
 *  pid may be of another pid namespace (a container sharing the cache). */
export const ABANDONED_AFTER_MS = 10 * 60_000;

/**
 * Removes the folders of `dir` whose name matches `pattern` (its first group: the pid of the
 * process that made it) when that process no longer exists and the folder has not changed for
 * ABANDONED_AFTER_MS. Links and files are left alone, nothing is followed. Returns the names removed.
 */
export async function removeAbandonedBuilds(dir: string, pattern: RegExp, now = Date.now()): Promise<string[]> {
  const removed: string[] = [];
  let names: string[];
  try {
    names = await fsp.readdir(dir);
  } catch {
    return removed;
  }
  for (const name of names) {
    const m = pattern.exec(name);
    if (!m) continue;
    const pid = Number(m[1]);
    if (pid === process.pid || pidAlive(pid)) continue;
    const st = await fsp.lstat(join(dir, name)).catch(() => undefined);
    if (!st?.isDirectory() || now - st.mtimeMs < ABANDONED_AFTER_MS) continue;
    await removeTreeNoFollow(join(dir, name));
    removed.push(name);
  }
  return removed;
}
