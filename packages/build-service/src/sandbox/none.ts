/**
 * No sandbox: plain host processes in the work dir, only when asked for explicitly. Time and output
 * limits still hold (the service enforces them); when the service runs as root the processes also
 * drop to the workspace's own uid with no new privileges. Nothing else holds, and every job says so.
 */
import { startHostProcess } from './host-process.js';
import { workDiskState } from './work-disk.js';
import type { RealtimeSupport, Sandbox, SandboxCommand, SandboxProbe, SandboxProcess } from './types.js';
import { join } from 'node:path';

const AS_ROOT = process.getuid?.() === 0;

export const NONE_UNENFORCED: readonly string[] = [
  'network isolation',
  'read-only root (the build can write anywhere its user can)',
  ...(AS_ROOT ? [] : ['non-root user', 'no new privileges']),
  'memory limit',
  'process limit',
  AS_ROOT ? 'disk limit outside the work dir' : 'disk limit',
];

export class NoSandbox implements Sandbox {
  readonly name = 'none' as const;
  readonly needsHostRuntime = true;
  readonly unenforced: readonly string[] = NONE_UNENFORCED;

  workPath(workDir: string): string {
    return workDir;
  }

  runtimePath(runtimeDir: string): string {
    return runtimeDir;
  }

  async probe(): Promise<SandboxProbe> {
    return { available: true, detail: `no isolation; not enforced: ${NONE_UNENFORCED.join(', ')}` };
  }

  /** Nothing would bound a runaway FIFO loop here: real-time mode is for the bwrap and docker sandboxes. */
  async realtimeSupport(): Promise<RealtimeSupport> {
    return {
      ok: false,
      reason: 'real-time mode needs the bwrap or docker sandbox, which bound a runaway SCHED_FIFO loop; the "none" sandbox bounds nothing (run without --realtime, or with --sandbox bwrap)',
    };
  }

  async start(cmd: SandboxCommand): Promise<SandboxProcess> {
    const disk = await workDiskState(cmd.workDir);
    const drop = AS_ROOT && cmd.owner
      ? ['setpriv', `--reuid=${cmd.owner.uid}`, `--regid=${cmd.owner.gid}`, '--clear-groups', '--no-new-privs', '--']
      : [];
    return startHostProcess({
      argv: [...drop, ...cmd.argv],
      cwd: join(cmd.workDir, cmd.cwd),
      env: {
        PATH: process.env.PATH ?? '/usr/local/bin:/usr/bin:/bin',
        HOME: cmd.workDir,
        TMPDIR: process.env.TMPDIR ?? '/tmp',
        LANG: 'C.UTF-8',
        ...cmd.env,
      },
      limits: cmd.limits,
      mechanisms: {
        memory: 'none',
        processes: 'none',
        network: 'none',
        filesystem: 'none',
        user: drop.length ? `host uid ${cmd.owner!.uid} (setpriv, no new privileges)` : `none (service uid ${process.getuid?.()})`,
        time: 'service-timer',
        output: 'service-counter',
        disk: disk ? 'tmpfs-size' : 'none',
      },
      cgroup: null,
      guessLimitsFromOutput: false,
      ...(disk ? { workDisk: { dir: cmd.workDir, bytes: disk.sizeBytes } } : {}),
      ...(cmd.stopOnLimit ? { stopOnLimit: cmd.stopOnLimit } : {}),
    });
  }
}
