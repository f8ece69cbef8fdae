/**
 * The files of a workspace's work/ that prepare copied there from the stage (the project's sources
 * and its generated tree), as opposed to what the build made beside them (objects, programs, logs).
 * They are listed in the stage after each copy, so that the next prepare removes from work/ those
 * the project no longer has (a header the user deleted was still found by `#include`, and the build
 * succeeded), while the build products stay for an incremental build.
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { checkRelativePath, removeFileNoFollow } from '../util/safe-fs.js';

const LIST_NAME = 'work-sources.txt';

async function listed(stageDir: string): Promise<string[]> {
  const text = await fsp.readFile(join(stageDir, LIST_NAME), 'utf8').catch(() => '');
  return text.split('\n').filter((rel) => rel !== '');
}

/**
 * Removes from `workDir` the files the last copy put there that `current` (this copy's files, paths
 * relative to work/) no longer holds, then records `current`. Returns how many were removed.
 */
export async function dropStaleWorkSources(stageDir: string, workDir: string, current: readonly string[]): Promise<number> {
  const now = new Set(current);
  let removed = 0;
  for (const rel of await listed(stageDir)) {
    if (now.has(rel)) continue;
    await removeFileNoFollow(workDir, checkRelativePath(rel));
    removed++;
  }
  await fsp.writeFile(join(stageDir, LIST_NAME), current.map((rel) => `${rel}\n`).join(''));
  return removed;
}
