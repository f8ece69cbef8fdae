/**
 * Per-job cgroup v2 (unified hierarchy) for bwrap, where cgroup v1 memory + pids are not mounted
 * (most machines today; docs/sandbox.md "Memory and process limits in bwrap"). It needs a
 * delegated subtree: the service's own cgroup (from /proc/self/cgroup, `0::/path`, under the
 * cgroup2 mount found in /proc/self/mounts) must be writable by the service, with `memory` and
 * `pids` in its cgroup.controllers. That is the case for root on a cgroup2-only host, inside a
 * `systemd-run --scope --user -p Delegate=yes` scope, or on a writable cgroup2 mount.
 *
 * The "no internal processes" rule: controllers can be enabled for children only in a cgroup
 * that holds no process itself. So, once per service, the service moves itself into a leaf child
 * `<own>/contract-service` (refused when other processes share its cgroup: they are not ours to
 * move), then writes `+memory +pids` to `<own>/cgroup.subtree_control`. Each job step then gets
 * `<own>/contract-<job>-<step>` with memory.max, memory.swap.max = 0, pids.max and
 * memory.oom.group = 1 for a build (an OOM kill takes the whole step at once), 0 for a run (the
 * kernel kills the process using the most memory, as v1 does, and the run's launcher stops the
 * others so that they write their last records: host-process.ts stopOnLimit); the hits
 * are read from memory.events (`oom_kill`, `oom_group_kill`) and pids.events (`max`).
 *
 * Every path is given by a `CgroupV2Paths` (the real /proc and /sys/fs/cgroup by default), so the
 * decision logic is tested on fake trees (cgroup-v2.test.ts).
 */
import { promises as fsp, readFileSync, accessSync, constants } from 'node:fs';
import { join } from 'node:path';
import { cgroupPids, killUntilEmpty, readShmemBytes, readSmallFile, removeCgroupDir } from './cgroup-procs.js';
import { sweepStaleCgroups } from './cgroup-sweep.js';
import type { LimitCgroup } from './cgroup.js';

export interface CgroupV2Paths {
  /** /proc/self/cgroup */
  selfCgroup: string;
  /** /proc/self/mounts */
  selfMounts: string;
  /** Our pid, written into cgroup.procs when we move into the leaf. */
  pid: number;
}

export const REAL_PATHS: CgroupV2Paths = { selfCgroup: '/proc/self/cgroup', selfMounts: '/proc/self/mounts', pid: process.pid };

const NEEDED = ['memory', 'pids'] as const;
const SERVICE_LEAF = 'contract-service';

function read(path: string): string | null {
  try {
    return readFileSync(path, 'utf8');
  } catch {
    return null;
  }
}

/** The octal escapes of /proc/self/mounts fields (`\040` for a space). */
function unescapeMount(field: string): string {
  return field.replace(/\\([0-7]{3})/g, (_m, o: string) => String.fromCharCode(parseInt(o, 8)));
}

export type V2Decision = { ok: true; dir: string } | { ok: false; reason: string };

/**
 * Where the jobs' cgroups can be made: the service's own v2 cgroup, when it is delegated to us
 * (writable, memory and pids available). Read-only: nothing is changed here.
 */
export function findDelegatedV2(paths: CgroupV2Paths = REAL_PATHS): V2Decision {
  const cgroupText = read(paths.selfCgroup);
  if (cgroupText === null) return { ok: false, reason: `cannot read ${paths.selfCgroup}` };
  const unified = cgroupText.split('\n').find((l) => l.startsWith('0::'));
  if (!unified) return { ok: false, reason: 'no cgroup v2 (unified) entry in /proc/self/cgroup' };
  const own = unified.slice(3).trim() || '/';
  const mountsText = read(paths.selfMounts) ?? '';
  const mount = mountsText
    .split('\n')
    .map((l) => l.split(' '))
    .find((f) => f[2] === 'cgroup2' && f[1]);
  if (!mount) return { ok: false, reason: 'no cgroup2 file system mounted' };
  const dir = join(unescapeMount(mount[1]!), own);
  const controllers = (read(join(dir, 'cgroup.controllers')) ?? '').trim().split(/\s+/).filter(Boolean);
  const missing = NEEDED.filter((c) => !controllers.includes(c));
  if (missing.length) {
    return {
      ok: false,
      reason: `cgroup v2 at ${dir} does not offer the ${missing.join(' and ')} controller(s)${controllers.length ? ` (only ${controllers.join(' ')})` : ''} — on a hybrid host they stay bound to cgroup v1; on a systemd host run under "systemd-run --scope --user -p Delegate=yes"`,
    };
  }
  for (const f of ['cgroup.subtree_control', 'cgroup.procs']) {
    try {
      accessSync(join(dir, f), constants.W_OK);
    } catch {
      return { ok: false, reason: `cgroup v2 at ${dir} is not delegated to this service (${f} is not writable); run it under "systemd-run --scope --user -p Delegate=yes" or as root` };
    }
  }
  return { ok: true, dir };
}

/**
 * Makes `dir` able to hold job cgroups with memory + pids (see the header): moves the service
 * into its leaf when `dir` holds processes, then enables the controllers for children.
 * Throws with the reason when it cannot.
 */
export async function enableV2Controllers(dir: string, paths: CgroupV2Paths = REAL_PATHS): Promise<void> {
  const enabled = (await fsp.readFile(join(dir, 'cgroup.subtree_control'), 'utf8').catch(() => '')).split(/\s+/);
  if (NEEDED.every((c) => enabled.includes(c))) return;
  const procs = (await fsp.readFile(join(dir, 'cgroup.procs'), 'utf8').catch(() => ''))
    .split('\n')
    .filter(Boolean)
    .map(Number);
  if (procs.length) {
    const others = procs.filter((p) => p !== paths.pid);
    if (others.length) {
      throw new Error(`cgroup v2 at ${dir} also holds processes that are not this service's (${others.slice(0, 5).join(', ')}); run the service in its own delegated cgroup ("systemd-run --scope --user -p Delegate=yes")`);
    }
    const leaf = join(dir, SERVICE_LEAF);
    await fsp.mkdir(leaf).catch((e: NodeJS.ErrnoException) => {
      if (e.code !== 'EEXIST') throw e;
    });
    await fsp.writeFile(join(leaf, 'cgroup.procs'), String(paths.pid));
  }
  await fsp.writeFile(join(dir, 'cgroup.subtree_control'), NEEDED.map((c) => `+${c}`).join(' '));
}

/** The `key N` line of a flat-keyed cgroup file (memory.events, pids.events); 0 without one. */
function counterOf(text: string, key: string): number {
  const m = new RegExp(`^${key} (\\d{1,15})$`, 'm').exec(text);
  return m ? Number(m[1]) : 0;
}

/**
 * OOM kills counted in a cgroup v2 folder (memory.events `oom_kill`, or `oom_group_kill` with
 * memory.oom.group); also read for a Docker job's container (docker-cgroup.ts).
 */
export async function readV2OomKills(dir: string): Promise<number> {
  const text = await readSmallFile(join(dir, 'memory.events'));
  return Math.max(counterOf(text, 'oom_kill'), counterOf(text, 'oom_group_kill'));
}

/** One job step's cgroup v2. */
export class JobCgroupV2 implements LimitCgroup {
  readonly mechanism = 'cgroup-v2' as const;

  private constructor(readonly dir: string) {}

  static async create(parent: string, name: string, memoryBytes: number, maxProcesses: number, oomGroup = true): Promise<JobCgroupV2> {
    await sweepStaleCgroups(parent);
    const dir = join(parent, name);
    await fsp.mkdir(dir);
    try {
      await fsp.writeFile(join(dir, 'memory.max'), String(memoryBytes));
      // no swap beyond the limit where the kernel offers swap accounting
      await fsp.writeFile(join(dir, 'memory.swap.max'), '0').catch(() => {});
      await fsp.writeFile(join(dir, 'pids.max'), String(maxProcesses));
      await fsp.writeFile(join(dir, 'memory.oom.group'), oomGroup ? '1' : '0').catch(() => {});
    } catch (e) {
      await fsp.rmdir(dir).catch(() => {});
      throw e;
    }
    return new JobCgroupV2(dir);
  }

  get procsFiles(): string[] {
    return [join(this.dir, 'cgroup.procs')];
  }

  /** OOM kills in the job (memory.events `oom_kill`, or `oom_group_kill` with memory.oom.group). */
  oomKills(): Promise<number> {
    return readV2OomKills(this.dir);
  }

  memoryFiles(): Promise<number | null> {
    return readShmemBytes(this.dir);
  }

  /** Forks refused by pids.max (pids.events `max`). */
  async pidsLimitHits(): Promise<number> {
    return counterOf(await readSmallFile(join(this.dir, 'pids.events')), 'max');
  }

  async pids(): Promise<number[]> {
    return cgroupPids(this.dir);
  }

  /** cgroup.kill (Linux 5.14+) kills the whole cgroup at once; else SIGKILL each process until none is left. */
  async killAll(deadlineMs = 1500): Promise<boolean> {
    await fsp.writeFile(join(this.dir, 'cgroup.kill'), '1').catch(() => {});
    return killUntilEmpty(() => this.pids(), deadlineMs);
  }

  async destroy(): Promise<void> {
    await this.killAll();
    await removeCgroupDir(this.dir);
  }
}
