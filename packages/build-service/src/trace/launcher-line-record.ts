/**
 * The launcher's end lines in a trace file (`contract run --trace FILE.jsonl`, docs/runtime-api.md
 * "Trace file"): a JSON line of kind `launcher_line` — `{"kind":"launcher_line","monoNs":"N",
 * "line":"module MAB (pid 41) died by signal 9 (Killed)"}` —, written only by the CLI from the
 * launcher's own lines (the job's `line` events of source `launcher`, the logs folder's
 * `contract-launch.log`: launcher-lines-file.ts), in time order among the records. A module's own
 * record can never be one: a record's JSON line is written from its CSV line, and an event a module
 * names `launcher_line` is read as kind `user`. The file is hostile all the same: its readers take
 * such a line only as the logs folder's (launcherEndLine's shape, and only when its pid is the
 * module's own, as its `module_started` record gives it). Browser-safe.
 */
import { launcherEndLine } from './launcher-end-line.js';
import type { LauncherFileLine } from './launcher-lines-file.js';

export const LAUNCHER_LINE_KIND = 'launcher_line';

/** A launcher end line as a trace file's JSON object (written by JSON lines writers as any record). */
export interface LauncherLineJson {
  kind: typeof LAUNCHER_LINE_KIND;
  /** When the launcher said it (CLOCK_MONOTONIC ns, as the records' monoNs). */
  monoNs: string;
  /** Its text, without the `contract-launch: ` prefix. */
  line: string;
}

/** A launcher end line read back from a trace file (`launcher: true` tells it from a record). */
export interface LauncherLineItem extends LauncherFileLine {
  kind: typeof LAUNCHER_LINE_KIND;
  launcher: true;
}

export function launcherLineJson(l: { monoNs: bigint | string; line: string }): LauncherLineJson {
  return { kind: LAUNCHER_LINE_KIND, monoNs: String(l.monoNs), line: l.line };
}

/** Whether a trace file's item is a launcher line (not a record). */
export function isLauncherLine(x: object): x is LauncherLineItem {
  return (x as { launcher?: unknown }).launcher === true && (x as { kind?: unknown }).kind === LAUNCHER_LINE_KIND;
}

/** A parsed JSON object of kind `launcher_line` as the line it holds, or why it is none. */
export function launcherLineOfJson(r: Record<string, unknown>): LauncherLineItem | { problem: string } {
  const { monoNs, line } = r;
  if (typeof monoNs !== 'string' || !/^\d{1,19}$/.test(monoNs)) return { problem: 'a launcher_line needs monoNs, a string of digits' };
  if (typeof line !== 'string') return { problem: 'a launcher_line needs its line, a string' };
  const end = launcherEndLine(line);
  if (!end) return { problem: 'a launcher_line that is none of the launcher\'s end lines' };
  return { kind: LAUNCHER_LINE_KIND, launcher: true, ...end, monoNs: BigInt(monoNs), line };
}
