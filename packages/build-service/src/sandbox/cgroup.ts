/**
 * Per-job cgroup v1 (memory + pids controllers): created as a child of the service's own cgroup in
 * each hierarchy, limits written before any job process joins it, counters read to tell which limit
 * was hit, every process in it killed at the end, then removed.
 */
import { promises as fsp, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { cgroupPids, killUntilEmpty, readShmemBytes, readSmallFile, removeCgroupDir } from './cgroup-procs.js';
import { sweepStaleCgroups } from './cgroup-sweep.js';

const CGROUP_ROOT = '/sys/fs/cgroup';
const CONTROLLERS = ['memory', 'pids'] as const;
type Controller = (typeof CONTROLLERS)[number];

/** The service's own cgroup path per v1 controller, from /proc/self/cgroup. */
function ownCgroupPaths(): Map<string, string> {
  const out = new Map<string, string>();
  let text: string;
  try {
    text = readFileSync('/proc/self/cgroup', 'utf8');
  } catch {
    return out;
  }
  for (const line of text.split('\n')) {
    const [, controllers, path] = line.split(':');
    if (!controllers || path === undefined) continue;
    for (const c of controllers.split(',')) out.set(c, path);
  }
  return out;
}

/** What the host process runner needs of a job's cgroup, v1 (this file) or v2 (cgroup-v2.ts). */
export interface LimitCgroup {
  readonly mechanism: 'cgroup-v1' | 'cgroup-v2';
  /** The cgroup.procs files a process writes its pid into to join the job (before exec). */
  readonly procsFiles: string[];
  oomKills(): Promise<number>;
  /** Bytes of the job's files in tmpfs mounts charged to it (memory.stat `shmem`; null: not said). */
  memoryFiles?(): Promise<number | null>;
  pidsLimitHits(): Promise<number>;
  pids(): Promise<number[]>;
  killAll(deadlineMs?: number): Promise<boolean>;
  destroy(): Promise<void>;
}

export class JobCgroup implements LimitCgroup {
  readonly mechanism = 'cgroup-v1' as const;

  private constructor(
    readonly dirs: Record<Controller, string>,
    private readonly baseline: { oomKills: number },
  ) {}

  /** Why cgroups cannot be used here (null when they can). Cached per process. */
  static unavailableReason(): string | null {
    if (probeCache !== undefined) return probeCache;
    probeCache = probe();
    return probeCache;
  }

  /** Creates the job's cgroups with the given limits; throws with a reason when impossible. */
  static async create(name: string, memoryBytes: number, maxProcesses: number): Promise<JobCgroup> {
    const own = ownCgroupPaths();
    const dirs = {} as Record<Controller, string>;
    try {
      for (const c of CONTROLLERS) {
        const parent = join(CGROUP_ROOT, c, own.get(c) ?? '/');
        await sweepStaleCgroups(parent);
        const dir = join(parent, name);
        await fsp.mkdir(dir);
        dirs[c] = dir;
      }
      await fsp.writeFile(join(dirs.memory, 'memory.limit_in_bytes'), String(memoryBytes));
      // no swap beyond the limit where the kernel accounts swap (memsw may not exist)
      await fsp.writeFile(join(dirs.memory, 'memory.memsw.limit_in_bytes'), String(memoryBytes)).catch(() => {});
      await fsp.writeFile(join(dirs.pids, 'pids.max'), String(maxProcesses));
    } catch (e) {
      for (const d of Object.values(dirs)) await fsp.rmdir(d).catch(() => {});
      throw e;
    }
    const cg = new JobCgroup(dirs, { oomKills: 0 });
    cg.baseline.oomKills = await cg.oomKills();
    return cg;
  }

  /** The cgroup.procs files a process writes its pid into to join the job (before exec). */
  get procsFiles(): string[] {
    return CONTROLLERS.map((c) => join(this.dirs[c], 'cgroup.procs'));
  }

  /** OOM kills inside the job since creation (memory.oom_control `oom_kill`, else memory.failcnt). */
  async oomKills(): Promise<number> {
    return (await readV1OomKills(this.dirs.memory)) - this.baseline.oomKills;
  }

  memoryFiles(): Promise<number | null> {
    return readShmemBytes(this.dirs.memory);
  }

  /** Times a fork/clone was refused by pids.max (pids.events `max`). */
  pidsLimitHits(): Promise<number> {
    return readPidsLimitHits(this.dirs.pids);
  }

  async pids(): Promise<number[]> {
    return cgroupPids(this.dirs.pids);
  }

  /** SIGKILLs every process of the job until none is left (or the deadline passes). */
  killAll(deadlineMs = 1500): Promise<boolean> {
    return killUntilEmpty(() => this.pids(), deadlineMs);
  }

  /** Kills what is left and removes the cgroup directories. */
  async destroy(): Promise<void> {
    await this.killAll();
    for (const c of CONTROLLERS) await removeCgroupDir(this.dirs[c]);
  }
}

/**
 * OOM kills counted in a cgroup v1 memory folder (memory.oom_control `oom_kill`, else
 * memory.failcnt on kernels before 4.13); also read for a Docker job's container (docker-cgroup.ts).
 */
export async function readV1OomKills(memoryDir: string): Promise<number> {
  const m = /^oom_kill (\d{1,15})$/m.exec(await readSmallFile(join(memoryDir, 'memory.oom_control')));
  if (m) return Number(m[1]);
  const fail = Number((await readSmallFile(join(memoryDir, 'memory.failcnt'), 64)).trim());
  return Number.isSafeInteger(fail) ? fail : 0;
}

/** Forks refused by pids.max in a pids cgroup folder, v1 or v2 (pids.events `max`). */
export async function readPidsLimitHits(pidsDir: string): Promise<number> {
  const m = /^max (\d{1,15})$/m.exec(await readSmallFile(join(pidsDir, 'pids.events')));
  return m ? Number(m[1]) : 0;
}

let probeCache: string | null | undefined;

function probe(): string | null {
  if (process.getuid?.() !== 0) return 'the service does not run as root (cgroup v1 directories are not writable)';
  const own = ownCgroupPaths();
  for (const c of CONTROLLERS) {
    if (!own.has(c)) return `cgroup v1 controller "${c}" is not mounted`;
    try {
      readFileSync(join(CGROUP_ROOT, c, own.get(c)!, 'cgroup.procs'));
    } catch {
      return `cgroup v1 controller "${c}" is not readable at ${join(CGROUP_ROOT, c)}`;
    }
  }
  return null;
}
