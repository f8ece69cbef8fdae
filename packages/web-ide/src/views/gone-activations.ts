/**
 * The Timeline's bars of modules the launcher's own end lines say ended (docs/ide.md "Timeline"): a
 * module killed from outside (SIGKILL) writes no `run_finished`, so its last bar would run to the
 * run's end; the launcher's line (`module SRT (pid 41) died by signal 9 (Killed)`, with its time on
 * the records' clock: a logs folder's contract-launch.log, GET /api/log-folder `launcherLines`, a
 * trace file's `launcher_line` items, or a Build & Run job's log lines put on that clock by
 * launcherLinesOnRecordClock, monitor/job-launcher-lines.ts) ends it at the line's time, said in its
 * tooltip — as the Monitor's replay of the same folder, file or job shows the module gone then. The same rule as there
 * (launcherGoneSign): only a line whose pid is the one the module's own `module_started` record gave.
 */
import { LogClocks, parseRecordLine, type KnownRecord } from '@contract-studio/build-service/trace';
import { launcherGoneSign } from '../monitor/gone-signs.js';
import type { Activation } from './activation-log.js';
import type { LogFile } from './run-logs.js';

/** Launcher lines taken, at most (the server and the trace reader bound them too). */
const MAX_LINES = 4096;

/** Each module's pid, as its last `module_started` record in `files` gives it. */
export function startedPids(files: readonly LogFile[]): Map<string, number> {
  const pids = new Map<string, number>();
  for (const f of files) {
    const text = f.text;
    if (!text.includes(',module_started,')) continue;
    const clocks = new LogClocks();
    const lines = text.split(/\r?\n/);
    for (let n = 1; n < lines.length; n++) {
      const l = lines[n]!;
      if (!l.includes(',module_started,')) continue;
      const r = parseRecordLine(f.name, n + 1, l, clocks.of(l.split(',')[2] ?? ''));
      if (r.kind !== 'module_started') continue;
      const pid = Number((r as KnownRecord).fields?.['pid']);
      if (Number.isSafeInteger(pid) && pid > 0) pids.set((r as KnownRecord).module, pid);
    }
  }
  return pids;
}

/** A module the launcher's own line says ended: when (the line's time, on the records' clock), and the line. */
export interface GoneAt {
  module: string;
  at: number;
  words: string;
}

/**
 * The modules the launcher's end lines say ended on their own (killed, crashed, exited before the
 * run's end: launcherGoneSign), each with the line's time; a line whose pid is not the module's own
 * (its `module_started` in `files`) is not taken. The first line of a module only.
 */
export function goneFromLauncherLines(files: readonly LogFile[], lines: readonly { monoNs: string; line: string }[] | undefined): GoneAt[] {
  if (!lines?.length) return [];
  const pids = startedPids(files);
  const out = new Map<string, GoneAt>();
  for (const l of lines.slice(0, MAX_LINES)) {
    if (typeof l?.line !== 'string' || typeof l.monoNs !== 'string' || !/^\d{1,20}$/.test(l.monoNs)) continue;
    const sign = launcherGoneSign(l.line, (m) => pids.get(m));
    if (sign && !out.has(sign.module)) out.set(sign.module, { module: sign.module, at: Number(l.monoNs), words: sign.words });
  }
  return [...out.values()];
}

/**
 * Ends, at its gone time, the bar of each module of `gone` that was still running then (its log has
 * no end of it), and notes the line on it (`gone`). `acts` sorted by start. Returns how many bars
 * were ended.
 */
export function endGoneActivations(acts: Activation[], gone: readonly GoneAt[]): number {
  let ended = 0;
  for (const g of gone) {
    // its last bar begun by then
    for (let i = acts.length - 1; i >= 0; i--) {
      const a = acts[i]!;
      if (a.module !== g.module || a.start > g.at) continue;
      if (a.end === undefined) {
        a.end = g.at;
        a.gone = g.words;
        ended++;
      }
      break;
    }
  }
  return ended;
}
