/**
 * What says a module has ended although its log wrote no end. Records that say it is no longer running although its log wrote no end (it was killed
 * from outside: a SIGKILL leaves no record of its own): ORD's, or a supervisor's, request to it
 * that found its mailbox stale (`START request to SRT: module not running (its mailbox is stale)
 * (Connection refused)`), a request not sent because it has ended (`STOP request to ORD: not
 * sent, it has ended (...)`), and ORD's stuck record saying so (`stuck: SRT has not finished
 * release #1484 after 200 periods: it is no longer running (it crashed or was killed)`: the
 * check `contract trace` makes, stuckSaysGone). And the launcher's own line of the job's output
 * saying how it ended (`contract-launch: module SRT (pid 41) died by signal 9 (Killed)`, `... exited
 * with status 3`): it comes as the module is reaped, whether or not any other module sends it a
 * request (launcherGoneSign).
 */
import { endedOnItsOwn, launcherEndLine, receiverGone, stuckSaysGone, type KnownRecord } from '@contract-studio/build-service/trace';

export interface GoneSign {
  /** The module the record says is gone. */
  module: string;
  /** What says it, in the record's words: `ORD: START request to SRT: module not running ...`. */
  words: string;
}

/** A module's name, as the runtime gives it (a gone receiver's name in another shape is not taken). */
const MODULE_NAME = /^[A-Za-z_][A-Za-z0-9_]{0,63}$/;

/** Longest record text a sign keeps (a forged line can be 4 KiB). */
const MAX_WORDS = 200;

/** The module record `k` says is gone, or undefined. */
export function goneModuleSign(k: KnownRecord): GoneSign | undefined {
  let module: string | undefined;
  if (k.kind === 'error') {
    // `<REQUEST> request to M: module not running ...` / `... request to M: not sent, it has ended ...`
    const gone = receiverGone(k.detail);
    if (gone && gone.way !== 'unknown' && MODULE_NAME.test(gone.module)) module = gone.module;
  }
  else if (k.kind === 'scheduler' && k.fields?.['what'] === 'stuck' && stuckSaysGone(k.detail) && typeof k.fields['module'] === 'string') module = k.fields['module'];
  if (!module || module === k.module) return undefined;
  return { module, words: `${k.module}: ${k.detail}`.slice(0, MAX_WORDS) };
}

/** Whether the launcher's words say the module ended on its own (build-service trace/launcher-end-line.ts). */
export { endedOnItsOwn };

/**
 * The module one of the launcher's own lines says ended (`line`: its text without the
 * `contract-launch: ` prefix: a `line` event of source `launcher`, on its stderr, of the run step),
 * or undefined. Hostile text: a module's own output comes tagged with its name (`[SRT] ...`: source
 * SRT, never `launcher`), so it cannot pass for the launcher's line; and the line's pid must be the
 * module's own, as its `module_started` record gives it (`pidOf`), so a line naming a module with
 * another pid, or one whose start was not read, is not taken.
 */
export function launcherGoneSign(line: string, pidOf: (module: string) => number | undefined): GoneSign | undefined {
  const end = launcherEndLine(line);
  if (!end || !endedOnItsOwn(end.how) || !MODULE_NAME.test(end.module) || pidOf(end.module) !== end.pid) return undefined;
  return { module: end.module, words: `contract-launch: ${line}`.slice(0, MAX_WORDS) };
}
