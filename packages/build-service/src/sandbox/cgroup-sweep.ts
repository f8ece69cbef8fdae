/**
 * Removes the job cgroups that dead build services left behind (docs/sandbox.md "Cgroups left by
 * a killed service"). A service (or `contract run`) killed with SIGKILL cannot remove its job's
 * cgroups: the memory and pids ones are only clutter, but a real-time run's cpu cgroup keeps its
 * budget (40 ms per 100 ms on each CPU) until the machine reboots, and after two such kills the
 * kernel has none left to give: every later real-time run was refused.
 *
 * Each job cgroup's name carries its owner: `<name>.o<pid>-<start time>-<pid namespace>`
 * (jobCgroupName, process-owner.ts). Before a service makes its first cgroup under a parent, it looks at its
 * siblings (sweepStaleCgroups):
 *   - owner in this pid namespace and dead (no such pid, or one started at another time): its
 *     processes are killed and the cgroup removed;
 *   - owner alive, or in another pid namespace: left alone;
 *   - a name without an owner (a service older than owner names): removed only when it holds no
 *     process and was made more than LEGACY_AGE_MS ago (never a process killed);
 *   - any other name: not ours, never touched.
 * planCgroupSweep decides (pure: tested with fake answers); sweepStaleCgroups acts.
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { cgroupPids, killUntilEmpty, removeCgroupDir } from './cgroup-procs.js';
import { currentProcessOwner, isProcessAlive, judgeOwnerTag, OWNER_TAG, ownerTag, type ProcessOwner } from './process-owner.js';

/** An ownerless job cgroup this old, with no process in it, is a leftover. */
export const LEGACY_AGE_MS = 60_000;

const JOB = String.raw`contract-(?:rt-)?j-[0-9a-f]{32}-[a-z]+`;
const OWNED = new RegExp(`^${JOB}\\.o${OWNER_TAG}$`);
const LEGACY = new RegExp(`^${JOB}$`);

/** `contract-j-<id>-<step>` with its owner (this process by default) appended. */
export function jobCgroupName(name: string, owner: ProcessOwner = currentProcessOwner()): string {
  return `${name}.o${ownerTag(owner)}`;
}

export interface SeenCgroup {
  name: string;
  /** Milliseconds since the folder was made (its change time). */
  ageMs: number;
  /** Processes in it now. */
  processes: number;
}

export type SweepVerdict = 'remove' | 'remove-if-empty' | 'keep';

/**
 * What to do with each sibling. `alive(pid, startTime)`: is that process running, started then?
 * `self`: this process's owner (its pid namespace says which owners can be judged).
 */
export function planCgroupSweep(seen: readonly SeenCgroup[], self: ProcessOwner, alive: (pid: number, startTime: string) => boolean): Map<string, SweepVerdict> {
  const plan = new Map<string, SweepVerdict>();
  for (const c of seen) {
    const owned = OWNED.exec(c.name);
    if (owned) {
      const [, pid, start, ns] = owned;
      plan.set(c.name, judgeOwnerTag(pid!, start!, ns!, self, alive) === 'dead' ? 'remove' : 'keep');
    } else if (LEGACY.test(c.name)) {
      plan.set(c.name, c.processes === 0 && c.ageMs >= LEGACY_AGE_MS ? 'remove-if-empty' : 'keep');
    }
  }
  return plan;
}

/** The parents already swept by this process (once each: later leftovers are its own). */
const swept = new Set<string>();

/** Sweeps `parent` once per process; returns the names removed. Never throws. */
export async function sweepStaleCgroups(parent: string, self: ProcessOwner = currentProcessOwner()): Promise<string[]> {
  if (swept.has(parent)) return [];
  swept.add(parent);
  const removed: string[] = [];
  try {
    const seen: SeenCgroup[] = [];
    for (const e of await fsp.readdir(parent, { withFileTypes: true })) {
      if (!e.isDirectory() || !e.name.startsWith('contract-')) continue;
      const dir = join(parent, e.name);
      const st = await fsp.stat(dir).catch(() => null);
      if (!st) continue;
      seen.push({ name: e.name, ageMs: Date.now() - st.ctimeMs, processes: (await cgroupPids(dir)).length });
    }
    for (const [name, verdict] of planCgroupSweep(seen, self, isProcessAlive)) {
      const dir = join(parent, name);
      if (verdict === 'keep') continue;
      if (verdict === 'remove') await killUntilEmpty(() => cgroupPids(dir), 1500);
      else if ((await cgroupPids(dir)).length) continue;
      await removeCgroupDir(dir);
      if (!(await fsp.stat(dir).catch(() => null))) removed.push(name);
    }
  } catch {
    /* a parent we cannot list: nothing swept, the job goes on */
  }
  return removed;
}

/** For tests: forget which parents were swept. */
export function forgetSweptParents(): void {
  swept.clear();
}
