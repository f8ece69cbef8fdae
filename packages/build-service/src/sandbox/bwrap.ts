/**
 * bubblewrap sandbox: new user/pid/net/ipc/uts (and cgroup) namespaces, host toolchain read-only,
 * the work dir read-write at /work, a private /tmp, the prebuilt runtime read-only at
 * /opt/contract/runtime, --die-with-parent, --new-session, a non-root uid (a distinct host uid per
 * job when the service runs as root; uid 1000 inside), no new privileges.
 * Memory and process limits: a per-job cgroup v1 when the service may create one, else a cgroup
 * v2 in a delegated subtree (cgroup-choice.ts), otherwise RLIMIT_AS / RLIMIT_NPROC set with
 * prlimit under the job's own non-root host uid.
 * Disk: the work dir is the workspace's tmpfs of workDiskMiB (work-disk.ts), watched for a full disk.
 * Real-time mode (opt-in): SCHED_FIFO granted and bounded as realtime.ts decides.
 */
import { execFile } from 'node:child_process';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { memoryBytes, REALTIME_BOUNDS, tmpBytes } from '../limits.js';
import type { LimitCgroup } from './cgroup.js';
import { cgroupChoice, createJobCgroup } from './cgroup-choice.js';
import { jobCgroupName } from './cgroup-sweep.js';
import { startHostProcess } from './host-process.js';
import { toolchainBinds as toolchainArgs } from './toolchain-binds.js';
import { workDiskState } from './work-disk.js';
import { describeRealtime, planRealtime, readRealtimeFacts, RealtimeCgroup, realtimePrefix } from './realtime.js';
import type { Mechanisms, RealtimeSupport, Sandbox, SandboxCommand, SandboxProbe, SandboxProcess } from './types.js';
import { SANDBOX_GID, SANDBOX_RUNTIME_DIR, SANDBOX_UID } from '@contract-studio/conventions';

const run = promisify(execFile);

export const SANDBOX_WORK = '/work';
export const SANDBOX_RUNTIME = SANDBOX_RUNTIME_DIR;

export type LimitMechanismChoice = 'auto' | 'cgroup' | 'rlimit';

export interface BwrapOptions {
  bwrapPath?: string;
  /** 'auto' (default): cgroups when possible, else rlimits. Tests force 'rlimit'. */
  limitMechanism?: LimitMechanismChoice;
}

export class BwrapSandbox implements Sandbox {
  readonly name = 'bwrap' as const;
  readonly needsHostRuntime = true;
  readonly unenforced: readonly string[] = [];
  private readonly bwrap: string;
  private readonly limitMechanism: LimitMechanismChoice;

  constructor(options: BwrapOptions = {}) {
    this.bwrap = options.bwrapPath ?? 'bwrap';
    this.limitMechanism = options.limitMechanism ?? 'auto';
  }

  workPath(): string {
    return SANDBOX_WORK;
  }

  runtimePath(): string {
    return SANDBOX_RUNTIME;
  }

  async probe(): Promise<SandboxProbe> {
    try {
      const { stdout } = await run(this.bwrap, ['--version']);
      const cg = cgroupChoice();
      const limits = this.limitMechanism === 'rlimit' ? 'rlimits (forced)' : cg.kind === 'none' ? `rlimits (${cg.reason})` : cg.kind;
      // user namespaces must work for the unprivileged job uid
      await run(this.bwrap, ['--unshare-all', ...toolchainArgs(), '--', '/bin/true']);
      return { available: true, detail: `${stdout.trim()}; memory/process limits via ${limits}` };
    } catch (e) {
      return {
        available: false,
        detail: `bubblewrap unusable: ${(e as Error).message.split('\n')[0]} — install it with "apt-get install bubblewrap" (Debian/Ubuntu) or "dnf install bubblewrap", and allow unprivileged user namespaces`,
      };
    }
  }

  async realtimeSupport(): Promise<RealtimeSupport> {
    const facts = readRealtimeFacts();
    const plan = planRealtime(facts, REALTIME_BOUNDS);
    if (!plan.ok) return plan;
    return {
      ok: true,
      detail: describeRealtime(plan.grant, plan.budget, REALTIME_BOUNDS, facts.globalRtRuntimeUs),
      ...(plan.budget === 'cgroup-v1-rt' ? { budget: { runtimeUs: REALTIME_BOUNDS.cpuRuntimeUs, periodUs: REALTIME_BOUNDS.cpuPeriodUs } } : {}),
    };
  }

  async start(cmd: SandboxCommand): Promise<SandboxProcess> {
    const isRoot = process.getuid?.() === 0;
    const facts = cmd.realtime ? readRealtimeFacts() : null;
    const plan = facts ? planRealtime(facts, REALTIME_BOUNDS) : null;
    if (plan && !plan.ok) throw new Error(`real-time mode refused: ${plan.reason}`);
    let cgroup: LimitCgroup | null = null;
    let cgroupError = '';
    if (this.limitMechanism !== 'rlimit') {
      const choice = cgroupChoice();
      if (choice.kind !== 'none') {
        try {
          // a run stops its modules at an OOM kill (stopOnLimit): only the process the kernel picks is killed by it
          cgroup = await createJobCgroup(choice, jobCgroupName(`contract-${cmd.name}`), memoryBytes(cmd.limits), cmd.limits.processes, undefined, !cmd.stopOnLimit);
        } catch (e) {
          cgroupError = (e as Error).message;
        }
      } else cgroupError = choice.reason;
      if (!cgroup && this.limitMechanism === 'cgroup') throw new Error(`cgroups required but unavailable: ${cgroupError}`);
    }
    let realtime: { chrt: string[]; prlimit: string[]; cgroup: RealtimeCgroup | null; detail: string } | null = null;
    if (plan?.ok) {
      let rtCgroup: RealtimeCgroup | null = null;
      try {
        if (plan.cpuCgroupDir) rtCgroup = await RealtimeCgroup.create(plan.cpuCgroupDir, jobCgroupName(`contract-rt-${cmd.name}`), REALTIME_BOUNDS);
      } catch (e) {
        await cgroup?.destroy();
        throw new Error(`real-time mode refused: ${(e as Error).message}`);
      }
      realtime = {
        ...realtimePrefix(plan.grant, REALTIME_BOUNDS),
        cgroup: rtCgroup,
        detail: describeRealtime(plan.grant, plan.budget, REALTIME_BOUNDS, facts!.globalRtRuntimeUs),
      };
    }
    const owner = cmd.owner;
    const disk = await workDiskState(cmd.workDir);
    const hostUser = isRoot && owner ? `host uid ${owner.uid}` : `host uid ${process.getuid?.()}`;
    const mechanisms: Mechanisms = {
      memory: cgroup ? cgroup.mechanism : 'rlimit-as',
      processes: cgroup ? cgroup.mechanism : 'rlimit-nproc',
      network: 'netns',
      filesystem: 'bwrap-ro-binds',
      user: `uid ${SANDBOX_UID} in a user namespace (${hostUser})`,
      time: 'service-timer',
      output: 'service-counter',
      disk: disk ? 'tmpfs-size' : 'none',
      ...(realtime ? { realtime: realtime.detail } : {}),
    };

    const env: Record<string, string> = {
      PATH: '/usr/local/bin:/usr/bin:/bin',
      HOME: SANDBOX_WORK,
      TMPDIR: '/tmp',
      LANG: 'C.UTF-8',
      ...cmd.env,
    };
    const bwrapArgs = [
      '--unshare-user',
      '--unshare-pid',
      '--unshare-net',
      '--unshare-ipc',
      '--unshare-uts',
      '--unshare-cgroup-try',
      '--disable-userns', // no nested user namespaces: no way to regain capabilities inside
      '--as-pid-1', // the command is the namespace's init: no bwrap init left to PID 1 when bwrap exits
      '--uid', String(SANDBOX_UID),
      '--gid', String(SANDBOX_GID),
      '--hostname', 'contract-sandbox',
      ...toolchainArgs(),
      '--proc', '/proc',
      // /dev read-only (its tmpfs was writable, bounded by nothing but the memory limit), and its
      // shm a tmpfs of its own, bounded as /tmp is
      '--dev', '/dev',
      '--remount-ro', '/dev',
      '--size', String(tmpBytes(cmd.limits)), '--tmpfs', '/dev/shm',
      '--size', String(tmpBytes(cmd.limits)), '--tmpfs', '/tmp',
      '--bind', cmd.workDir, SANDBOX_WORK,
      ...(cmd.runtimeDir ? ['--ro-bind', cmd.runtimeDir, SANDBOX_RUNTIME] : []),
      '--remount-ro', '/',
      '--chdir', join(SANDBOX_WORK, cmd.cwd),
      '--die-with-parent',
      '--new-session',
      '--clearenv',
      ...Object.entries(env).flatMap(([k, v]) => ['--setenv', k, v]),
      '--',
      ...cmd.argv,
    ];
    const prefix: string[] = [...(realtime?.chrt ?? [])];
    const rlimits = [...(cgroup ? [] : [`--as=${memoryBytes(cmd.limits)}`, `--nproc=${cmd.limits.processes}`]), ...(realtime?.prlimit ?? [])];
    if (rlimits.length) prefix.push('prlimit', ...rlimits, '--');
    if (isRoot && owner) {
      prefix.push('setpriv', `--reuid=${owner.uid}`, `--regid=${owner.gid}`, '--clear-groups', '--no-new-privs', '--');
    }
    return startHostProcess({
      argv: [...prefix, this.bwrap, ...bwrapArgs],
      cwd: '/',
      env: { PATH: '/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' },
      limits: cmd.limits,
      mechanisms,
      cgroup,
      ...(realtime?.cgroup ? { joinProcsFiles: [realtime.cgroup.procsFile] } : {}),
      guessLimitsFromOutput: !cgroup,
      cleanup: cgroup || realtime?.cgroup ? async () => {
        await cgroup?.destroy();
        await realtime?.cgroup?.destroy();
      } : undefined,
      ...(disk ? { workDisk: { dir: cmd.workDir, bytes: disk.sizeBytes } } : {}),
      ...(cmd.stopOnLimit ? { stopOnLimit: cmd.stopOnLimit } : {}),
    });
  }
}
