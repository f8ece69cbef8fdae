/**
 * What a limit hit (memory, processes, disk) does to a run in every sandbox (host-process.ts for
 * bwrap and none, docker.ts): its launcher is asked to stop the modules (SIGTERM: it fits its stop
 * in its budget, as for Stop), so that every module the limit left running writes its last records
 * and its exit record; what still runs `graceMs` later is killed. The limit is the run's end
 * either way. SandboxCommand.stopOnLimit; a build has none and is killed at once.
 */
import type { LimitHit } from '../limits.js';
import type { StopOnLimit } from './types.js';
import type { StopReason } from '@contract-studio/conventions';

/** The parts of a running sandbox command the stop uses. */
export interface StoppableCommand {
  terminateNamed(name: string, reason?: StopReason): Promise<boolean>;
  /** Resolves when the command's main process has exited. */
  exited: Promise<void>;
  kill(): Promise<void>;
}

export async function stopThenKill(stop: StopOnLimit, hit: LimitHit, cmd: StoppableCommand): Promise<void> {
  // the launcher tells the modules why (their KILL records): the limit's name is its reason's
  const reason: StopReason | undefined = hit.name === 'memory' || hit.name === 'processes' || hit.name === 'workDiskMiB' ? hit.name : undefined;
  // told before asking: what the launcher prints as it stops comes after it in the job's log
  tellSafely(() => stop.stopping?.(hit));
  const asked = await cmd.terminateNamed(stop.processName, reason).catch(() => false);
  if (!asked) tellSafely(() => stop.unanswered?.(hit));
  if (asked) {
    let timer: NodeJS.Timeout | undefined;
    await Promise.race([cmd.exited, new Promise((r) => (timer = setTimeout(r, stop.graceMs)))]);
    clearTimeout(timer);
  }
  await cmd.kill();
}

function tellSafely(tell: () => void): void {
  try {
    tell();
  } catch {
    /* the teller's fault: the stop goes on */
  }
}
