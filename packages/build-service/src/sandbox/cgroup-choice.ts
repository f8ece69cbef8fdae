/**
 * Which cgroup hierarchy limits a bwrap job's memory and processes (docs/sandbox.md "Memory and
 * process limits in bwrap"): cgroup v1 memory + pids when the service may use them (root, both
 * mounted), else a delegated cgroup v2 subtree (cgroup-v2.ts), else none (the caller falls back
 * to rlimits and says why). Decided once per process.
 */
import { JobCgroup, type LimitCgroup } from './cgroup.js';
import { enableV2Controllers, findDelegatedV2, JobCgroupV2, REAL_PATHS, type CgroupV2Paths, type V2Decision } from './cgroup-v2.js';

export type CgroupChoice = { kind: 'cgroup-v1' } | { kind: 'cgroup-v2'; dir: string } | { kind: 'none'; reason: string };

/** The decision from the two probes (pure: tested with fake answers). */
export function chooseCgroup(v1Unavailable: string | null, v2: V2Decision): CgroupChoice {
  if (v1Unavailable === null) return { kind: 'cgroup-v1' };
  if (v2.ok) return { kind: 'cgroup-v2', dir: v2.dir };
  return { kind: 'none', reason: `cgroup v1: ${v1Unavailable}; cgroup v2: ${v2.reason}` };
}

let cached: CgroupChoice | undefined;
let v2Ready: Promise<void> | undefined;

export function cgroupChoice(): CgroupChoice {
  cached ??= chooseCgroup(JobCgroup.unavailableReason(), findDelegatedV2());
  return cached;
}

/**
 * A job step's cgroup under the chosen hierarchy; throws with the reason when it cannot be made.
 * `oomGroup` (cgroup v2): an OOM kill takes every process of the step at once (a build); without
 * it the kernel kills the process using the most memory, as cgroup v1 does, and the service stops
 * the rest (a run: its launcher stops the modules, SandboxCommand.stopOnLimit).
 */
export async function createJobCgroup(choice: CgroupChoice, name: string, memoryBytes: number, maxProcesses: number, paths: CgroupV2Paths = REAL_PATHS, oomGroup = true): Promise<LimitCgroup> {
  if (choice.kind === 'cgroup-v1') return JobCgroup.create(name, memoryBytes, maxProcesses);
  if (choice.kind === 'cgroup-v2') {
    v2Ready ??= enableV2Controllers(choice.dir, paths);
    await v2Ready;
    return JobCgroupV2.create(choice.dir, name, memoryBytes, maxProcesses, oomGroup);
  }
  throw new Error(choice.reason);
}
