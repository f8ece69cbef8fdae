/**
 * SIGTERM with a value queued (sigqueue(2)): the build service's stop of a run says why
 * (STOP_REASON_CODES), and contract-launch tells every module (their KILL records). Node has no
 * sigqueue: the system's `kill -q VALUE` does it (procps and util-linux have it). Where it is
 * missing or refused, a plain SIGTERM: the run stops the same, without saying why.
 */
import { spawnSync } from 'node:child_process';
import { STOP_REASON_CODES, type StopReason } from '@contract-studio/conventions';

/** SIGTERM to `pid`, with `reason`'s code queued when it can be; throws as process.kill does when the plain signal fails. */
export function queueTerm(pid: number, reason: StopReason | undefined): void {
  if (reason !== undefined) {
    const r = spawnSync('kill', ['-s', 'TERM', '-q', String(STOP_REASON_CODES[reason]), String(pid)], { stdio: 'ignore', timeout: 2000 });
    if (r.status === 0) return;
  }
  process.kill(pid, 'SIGTERM');
}
