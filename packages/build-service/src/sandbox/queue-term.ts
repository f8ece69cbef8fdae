/**
 * SIGTERM with a value queued (sigqueue(2)): the build service's stop of a run says why
 * (STOP_REASON_CODES), and contract-launch tells every module (their KILL records). Node has no
 * sigqueue: the system's `kill -q VALUE` does it (procps and util-linux have it), started without
 * blocking the service's event loop. Where it is missing or refused, a plain SIGTERM: the run stops
 * the same, without saying why.
 */
import { execFile } from 'node:child_process';
import { STOP_REASON_CODES, type StopReason } from '@contract-studio/conventions';

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
