/**
 * The status a job's end gives the build panel and the status bar (app/run-controller.ts draws
 * `✓ succeeded: …`, `■ failed: …`), from its `end` event's result (build-service JobResult: `ok`,
 * `message`) and the last status its stream said (the service says `cancelled` just before the
 * end of a job it cancelled). A job cancelled (Stop) ends with ok false, most often with the
 * message `cancelled`: its status is `cancelled` (`■ cancelled`, as the Monitor says `ended:
 * cancelled`), not a failure with the message "cancelled".
 */
export function jobEndStatus(result: { ok?: unknown; message?: unknown } | null | undefined, lastStatus?: string): { status: 'succeeded' | 'failed' | 'cancelled'; message: string | undefined } {
  const message = typeof result?.message === 'string' && result.message ? result.message : undefined;
  if (result?.ok === true) return { status: 'succeeded', message };
  if (message === 'cancelled') return { status: 'cancelled', message: undefined };
  if (lastStatus === 'cancelled') return { status: 'cancelled', message };
  return { status: 'failed', message };
}

/** The status bar's words for a job's status: `⟳ running`, `✓ succeeded: run finished (exit 0)`, `■ failed: …`, `■ cancelled`. */
export function jobStatusText(status: string, message: string | undefined, running: boolean): string {
  return `${running ? '⟳' : status === 'succeeded' ? '✓' : '■'} ${status}${message ? `: ${message}` : ''}`;
}

/** How a job the IDE server no longer knows ended, for every tab alike (the Monitor's run list says it too). */
export const LOST_WITH_SERVER = 'lost with the IDE server (it was stopped or restarted, which ends its jobs)';

/**
 * What the build panel says of job `jobId` when the build service no longer knows it: after a
 * reload, or when the server answers again after the job's stream was lost.
 */
export function goneJobText(jobId: string): string {
  return `job ${jobId.slice(0, 8)}… is no longer known to the build service: the IDE server was restarted, which ends its jobs: their logs and a run's CSV logs went with them (a Build & Run writes nothing into the workspace); run it again`;
}
