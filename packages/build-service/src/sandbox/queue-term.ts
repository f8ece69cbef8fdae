/**
 * SIGTERM with a value queued (sigqueue(2)): the build service's stop of a run says why
 * (STOP_REASON_CODES), and contract-launch tells every module (their KILL records). Node has no
 * sigqueue: the system's `kill -q VALUE` does it (procps and util-linux have it), started without
 * blocking the service's event loop. Where it is missing or refused, a plain SIGTERM: the run stops
 * the same, without saying why. terminateNamedOnHost asks the job's processes of one name so.
 */
import { execFile } from 'node:child_process';
import { join } from 'node:path';
import { STOP_REASON_CODES, type StopReason } from '@contract-studio/conventions';
import { readSmallFile } from './cgroup-procs.js';

/** How long `kill -q` may take before the plain signal is sent instead. */
const QUEUE_TIMEOUT_MS = 2000;

/** SIGTERM to `pid`, with `reason`'s code queued when it can be; rejects as process.kill throws when the plain signal fails. */
export async function queueTerm(pid: number, reason: StopReason | undefined): Promise<void> {
  if (reason !== undefined) {
    const queued = await new Promise<boolean>((resolve) => {
      execFile('kill', ['-s', 'TERM', '-q', String(STOP_REASON_CODES[reason]), String(pid)], { timeout: QUEUE_TIMEOUT_MS }, (e) => resolve(!e));
    });
    if (queued) return;
  }
  process.kill(pid, 'SIGTERM');
}

/** The kernel keeps a process's name (comm) to this many characters. */
const COMM_MAX = 15;

/**
 * SIGTERM (`reason` queued with it: queueTerm), from this host, to each of `pids` named `name`
 * (/proc/<pid>/comm): true when one was asked, false when none is so named, null when this service
 * may not signal them (not root: Docker's caller then asks inside the container). bwrap's and
 * `none`'s stop and Docker's ask the job's processes through it.
 */
export async function terminateNamedOnHost(pids: readonly number[], name: string, procRoot = '/proc', reason?: StopReason): Promise<boolean | null> {
  const comm = name.slice(0, COMM_MAX);
  let asked = false;
  let denied = false;
  for (const pid of pids) {
    if ((await readSmallFile(join(procRoot, String(pid), 'comm'), 64)).replace(/\n$/, '') !== comm) continue;
    try {
      await queueTerm(pid, reason);
      asked = true;
    } catch (e) {
      if ((e as NodeJS.ErrnoException).code === 'EPERM') denied = true;
    }
  }
  return asked ? true : denied ? null : false;
}
