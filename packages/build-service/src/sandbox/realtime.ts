/**
 * The opt-in real-time mode of the bwrap sandbox (docs/sandbox.md, "Real-time mode"): how a job's
 * modules get their SCHED_FIFO priorities although they run as an unprivileged uid in a user
 * namespace, and what bounds a runaway FIFO loop.
 *
 *   grant   'rlimit-rtprio':  RLIMIT_RTPRIO raised to the ceiling (needs CAP_SYS_RESOURCE or a hard
 *                             limit that high): any module may take any priority up to it.
 *           'inherited-fifo': the run starts at SCHED_FIFO <ceiling> (chrt by the service, which has
 *                             CAP_SYS_NICE); a process may always lower its own real-time priority,
 *                             so every module takes its own, but none can raise it later.
 *   budget  'cgroup-v1-rt':   a per-job cpu cgroup with cpu.rt_runtime_us / cpu.rt_period_us (kernels
 *                             with CONFIG_RT_GROUP_SCHED: there, a FIFO task needs such a budget).
 *           'global-rt-throttling': kernel.sched_rt_runtime_us (the 95 % default) only.
 *   always  RLIMIT_RTTIME:    SIGXCPU, then SIGKILL, after that much CPU time without blocking.
 * The decision (planRealtime) is pure; readRealtimeFacts reads what it needs from /proc and /sys.
 */
import { accessSync, constants, existsSync, promises as fsp, readFileSync } from 'node:fs';
import { join } from 'node:path';
import type { RealtimeBounds } from '../limits.js';
import { cgroupPids, killUntilEmpty, removeCgroupDir } from './cgroup-procs.js';
import { sweepStaleCgroups } from './cgroup-sweep.js';

const CPU_HIERARCHY = '/sys/fs/cgroup/cpu';
const CAP_SYS_NICE = 23;
const CAP_SYS_RESOURCE = 24;

/** What the host lets the service do, as far as real-time scheduling goes. */
export interface RealtimeFacts {
  capSysNice: boolean;
  capSysResource: boolean;
  /** Hard RLIMIT_RTPRIO of the service (Infinity: unlimited). */
  rtprioHard: number;
  /** The service's own cgroup folder in the v1 cpu hierarchy, null without one. */
  cpuCgroupDir: string | null;
  /** Its cpu.rt_runtime_us; null when the file is absent (no CONFIG_RT_GROUP_SCHED, or no v1 cpu hierarchy). */
  cpuCgroupRtRuntimeUs: number | null;
  /** Whether the service may create a child folder there. */
  cpuCgroupWritable: boolean;
  /** kernel.sched_rt_runtime_us: -1 = no global throttling; null = unreadable. */
  globalRtRuntimeUs: number | null;
}

export type PriorityGrant = 'rlimit-rtprio' | 'inherited-fifo';
export type RealtimeBudget = 'cgroup-v1-rt' | 'global-rt-throttling';

export type RealtimePlan =
  | { ok: true; grant: PriorityGrant; budget: RealtimeBudget; cpuCgroupDir: string | null }
  | { ok: false; reason: string };

/** Decides how real-time mode is granted and bounded on this host, or why it cannot be. */
export function planRealtime(facts: RealtimeFacts, bounds: RealtimeBounds): RealtimePlan {
  let grant: PriorityGrant;
  if (facts.capSysResource || facts.rtprioHard >= bounds.priorityCeiling) grant = 'rlimit-rtprio';
  else if (facts.capSysNice) grant = 'inherited-fifo';
  else {
    return {
      ok: false,
      reason:
        `the build service may not grant SCHED_FIFO: its RLIMIT_RTPRIO hard limit is ${facts.rtprioHard} (below ${bounds.priorityCeiling}) ` +
        'and it has neither CAP_SYS_RESOURCE nor CAP_SYS_NICE. Run the service as root, or give its user ' +
        `"<user> - rtprio ${bounds.priorityCeiling}" in /etc/security/limits.d/ and log in again`,
    };
  }
  if (facts.cpuCgroupRtRuntimeUs !== null) {
    // CONFIG_RT_GROUP_SCHED: a FIFO task needs a real-time budget in its cpu cgroup
    if (facts.cpuCgroupRtRuntimeUs === 0) {
      return {
        ok: false,
        reason: `the build service's cpu cgroup ${facts.cpuCgroupDir} has no real-time budget (cpu.rt_runtime_us = 0): run the service in a cpu cgroup with one (e.g. the root cgroup)`,
      };
    }
    if (!facts.cpuCgroupWritable || !facts.cpuCgroupDir) {
      return {
        ok: false,
        reason: `the kernel gives real-time tasks a budget per cpu cgroup (CONFIG_RT_GROUP_SCHED) and the build service may not create one under ${facts.cpuCgroupDir}: run the service as root`,
      };
    }
    return { ok: true, grant, budget: 'cgroup-v1-rt', cpuCgroupDir: facts.cpuCgroupDir };
  }
  if (facts.globalRtRuntimeUs === null || facts.globalRtRuntimeUs < 0) {
    return {
      ok: false,
      reason:
        'real-time throttling is off on this host (kernel.sched_rt_runtime_us = -1 or unreadable): a runaway SCHED_FIFO loop could freeze it. ' +
        'Turn it on with "sysctl kernel.sched_rt_runtime_us=950000"',
    };
  }
  return { ok: true, grant, budget: 'global-rt-throttling', cpuCgroupDir: null };
}

function capabilityBit(capEffHex: string | undefined, bit: number): boolean {
  if (!capEffHex) return false;
  return ((BigInt(`0x${capEffHex}`) >> BigInt(bit)) & 1n) === 1n;
}

function readNumber(path: string): number | null {
  try {
    const n = Number(readFileSync(path, 'utf8').trim());
    return Number.isFinite(n) ? n : null;
  } catch {
    return null;
  }
}

/** The service's own real-time facts (read each time: cheap, and capabilities may differ per process). */
export function readRealtimeFacts(): RealtimeFacts {
  const status = readFileSync('/proc/self/status', 'utf8');
  const capEff = /^CapEff:\s*([0-9a-f]+)$/m.exec(status)?.[1];
  const limits = readFileSync('/proc/self/limits', 'utf8');
  const hard = /^Max realtime priority\s+\S+\s+(\S+)/m.exec(limits)?.[1];
  let cpuCgroupDir: string | null = null;
  const own = /^\d+:(?:[^:]*,)?cpu(?:,[^:]*)?:(.*)$/m.exec(readFileSync('/proc/self/cgroup', 'utf8'));
  if (own && existsSync(CPU_HIERARCHY)) cpuCgroupDir = join(CPU_HIERARCHY, own[1]!);
  let writable = false;
  if (cpuCgroupDir) {
    try {
      accessSync(cpuCgroupDir, constants.W_OK);
      writable = true;
    } catch {
      writable = false;
    }
  }
  return {
    capSysNice: capabilityBit(capEff, CAP_SYS_NICE),
    capSysResource: capabilityBit(capEff, CAP_SYS_RESOURCE),
    rtprioHard: hard === undefined ? 0 : hard === 'unlimited' ? Infinity : Number(hard),
    cpuCgroupDir,
    cpuCgroupRtRuntimeUs: cpuCgroupDir ? readNumber(join(cpuCgroupDir, 'cpu.rt_runtime_us')) : null,
    cpuCgroupWritable: writable,
    globalRtRuntimeUs: readNumber('/proc/sys/kernel/sched_rt_runtime_us'),
  };
}

/** The run's argv prefix (before setpriv/bwrap) that grants the priorities and sets RLIMIT_RTTIME. */
export function realtimePrefix(grant: PriorityGrant, bounds: RealtimeBounds): { chrt: string[]; prlimit: string[] } {
  const prlimit = [`--rttime=${bounds.cpuWithoutBlockingSoftUs}:${bounds.cpuWithoutBlockingHardUs}`];
  if (grant === 'rlimit-rtprio') prlimit.push(`--rtprio=${bounds.priorityCeiling}`);
  return { chrt: grant === 'inherited-fifo' ? ['chrt', '--fifo', String(bounds.priorityCeiling)] : [], prlimit };
}

/** "SCHED_FIFO up to 99 (inherited-fifo); cpu.rt_runtime_us 40000 per 100000 (cgroup-v1-rt); RLIMIT_RTTIME 0.5 s / 1 s" */
export function describeRealtime(grant: PriorityGrant, budget: RealtimeBudget, bounds: RealtimeBounds, globalRtRuntimeUs: number | null = null): string {
  const budgetText =
    budget === 'cgroup-v1-rt'
      ? `cpu.rt_runtime_us ${bounds.cpuRuntimeUs} per ${bounds.cpuPeriodUs} on each CPU (cgroup-v1-rt)`
      : `kernel.sched_rt_runtime_us ${globalRtRuntimeUs ?? '?'} (global-rt-throttling)`;
  return (
    `SCHED_FIFO up to ${bounds.priorityCeiling} (${grant}); ${budgetText}; ` +
    `RLIMIT_RTTIME ${bounds.cpuWithoutBlockingSoftUs / 1e6} s / ${bounds.cpuWithoutBlockingHardUs / 1e6} s`
  );
}

/** A job's cpu cgroup with its real-time budget; its processes join through procsFile before exec. */
export class RealtimeCgroup {
  private constructor(readonly dir: string) {}

  get procsFile(): string {
    return join(this.dir, 'cgroup.procs');
  }

  /** Creates `<parent>/<name>` with the budget; throws a user-readable error when the host refuses it. */
  static async create(parent: string, name: string, bounds: RealtimeBounds): Promise<RealtimeCgroup> {
    // a killed service's run keeps its budget until its cgroup is removed (cgroup-sweep.ts); the
    // kernel gives a removed group's budget back a little later (its offlining is deferred), so
    // after a sweep that removed one, a refusal is tried again for a while
    const sweptSome = (await sweepStaleCgroups(parent)).length > 0;
    const dir = join(parent, name);
    await fsp.mkdir(dir);
    try {
      await fsp.writeFile(join(dir, 'cpu.rt_period_us'), String(bounds.cpuPeriodUs));
      for (let tries = sweptSome ? 100 : 1; ; tries--) {
        try {
          await fsp.writeFile(join(dir, 'cpu.rt_runtime_us'), String(bounds.cpuRuntimeUs));
          break;
        } catch (e) {
          if (tries <= 1 || (e as NodeJS.ErrnoException).code !== 'EINVAL') throw e;
          await new Promise((r) => setTimeout(r, 20));
        }
      }
    } catch (e) {
      await fsp.rmdir(dir).catch(() => {});
      const code = (e as NodeJS.ErrnoException).code;
      if (code === 'EBUSY' || code === 'EINVAL') {
        throw new Error(
          `no real-time budget left under ${parent} for ${bounds.cpuRuntimeUs} µs per ${bounds.cpuPeriodUs} µs (${code}): ` +
            'other real-time jobs or groups hold it; try again when they have ended',
        );
      }
      throw e;
    }
    return new RealtimeCgroup(dir);
  }

  /** Kills what is left in it and removes it. */
  async destroy(): Promise<void> {
    await killUntilEmpty(() => cgroupPids(this.dir), 1500);
    await removeCgroupDir(this.dir);
  }
}
