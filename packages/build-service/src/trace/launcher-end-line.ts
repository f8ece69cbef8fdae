/**
 * The launcher's line saying how a module ended (runtime/launcher/contract-launch.c reap,
 * docs/runtime-api.md "contract-launch"), its `contract-launch: ` prefix removed: `module SRT (pid
 * 41) died by signal 9 (Killed)`, `... exited with status 3`, `... exited with status 0 before the
 * run's end`, `... terminated by signal 15 (Terminated)` (its own SIGTERM at the stop). Read by the
 * build service's reader of failures (pipeline/launcher-crashes.ts) and by the IDE's Monitor, which
 * takes it as a sign of the module's end (web-ide monitor/gone-signs.ts). Browser-safe.
 */

const END_LINE = /^module ([A-Za-z_]\w{0,63}) \(pid (\d{1,10})\) (exited with status \d{1,3}(?: while the run stopped| before the run's end)?|(?:died|terminated) by signal \d{1,3} \([^()]{0,100}\)(?:: ran .{1,300})?(?: while the run stopped)?)$/;

/** Longest line read (the launcher's are far shorter; a longer one is no end line). */
const MAX_CHARS = 600;

export interface LauncherEnd {
  module: string;
  /** Its pid, as the launcher gives it (the sandbox's pid namespace: that of the module's `module_started` record). */
  pid: number;
  /** How it ended, in the launcher's words: `died by signal 9 (Killed)`, `exited with status 3 while the run stopped`. */
  how: string;
}

/** The module line `text` says ended, its pid and how; undefined for any other line. */
export function launcherEndLine(text: string): LauncherEnd | undefined {
  if (text.length > MAX_CHARS) return undefined;
  const m = END_LINE.exec(text);
  return m ? { module: m[1]!, pid: Number(m[2]), how: m[3]! } : undefined;
}

/**
 * Whether the launcher's words say the module ended on its own, not by the run's stop: a signal it
 * did not send (`died by signal 9 (Killed)`), an exit with a status (`exited with status 3`), or
 * with 0 before the run's end (its code's `exit(0)`). A module ending on the stop's KILL request
 * (`exited with status 0`, `... while the run stopped`) or terminated by the launcher's own SIGTERM
 * (`terminated by signal 15`) ended as the run did: no sign (its exit record says the same).
 */
export function endedOnItsOwn(how: string): boolean {
  if (how.startsWith('died by signal')) return true;
  const status = /^exited with status (\d{1,3})( before the run's end)?/.exec(how);
  return !!status && (status[1] !== '0' || status[2] !== undefined);
}
