/**
 * Whether the Docker engine says a job's container was killed for memory (State.OOMKilled).
 * The engine learns of an OOM kill and of the container's exit by two events that race (the
 * runtime's OOM and exit notices): right after the exit the flag may not be set yet, and a job
 * killed for memory would read as `run failed (make exit 2)`. So an exit that looks like a kill is
 * asked about again for a while; any other exit is asked once.
 */

/** How long an exit that looks like a kill waits for the engine's OOM flag, and how often it asks. */
export const OOM_FLAG_WAIT_MS = 2000;
export const OOM_FLAG_POLL_MS = 50;

/** A line a shell or make writes when a child was killed by a signal (`make: *** [Makefile:6: run] Killed`). */
export const KILLED_LINE = /\bKilled\b/;

/**
 * Whether a container's exit looks like a kill from outside the program: 137 (SIGKILL, as the
 * container's init reports it), or any failure after a shell or make said a child was killed.
 */
export function looksKilled(exitCode: number | null, sawKilledLine: boolean): boolean {
  return exitCode === 137 || (exitCode !== null && exitCode !== 0 && sawKilledLine);
}

interface InspectedState {
  State?: { OOMKilled?: boolean };
}

/**
 * Whether the engine's inspection says OOMKilled; with `maybeLate`, asks again every `pollMs`
 * until it does or `waitMs` have passed. A failed inspection (the container gone) ends the wait.
 */
export async function engineSaysOomKilled(
  inspect: () => Promise<InspectedState>,
  maybeLate: boolean,
  waitMs = OOM_FLAG_WAIT_MS,
  pollMs = OOM_FLAG_POLL_MS,
): Promise<boolean> {
  const deadline = Date.now() + (maybeLate ? waitMs : 0);
  for (;;) {
    const info = await inspect().catch(() => null);
    if (info?.State?.OOMKilled) return true;
    if (!info || Date.now() >= deadline) return false;
    await new Promise((r) => setTimeout(r, pollMs));
  }
}
