/**
 * A finished job's launcher lines, for the replay of its CSV logs: the launcher's own lines of the
 * job's log (`GET /api/jobs/:id/log`: `<t ISO> run launcher stderr | module SRT (pid 41) died by
 * signal 9 (Killed)`, docs/build-service-api.md "full log"), each with its time. A module's lines
 * there name the module as their source (the service's field, from the launcher's `[NAME]` tag),
 * never `launcher`, and every control character of a line is escaped, so none can pass for one.
 * Each end line is applied to the replay at its wall time on the run's time line (the run's first
 * record's wall_time: both are the host's clock), as a live run takes it (MonitorModel.launcherLine).
 */
import { getOk } from '../api.js';
import type { LogFile } from '../views/run-logs.js';
import type { MonitorModel } from './monitor-model.js';

export interface LauncherLine {
  /** When the service got it (ms epoch). */
  wallMs: number;
  /** Its text, without the `contract-launch: ` prefix. */
  line: string;
}

/** A launcher's line of the run step in the job's log. */
const LAUNCHER_LINE = /^(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(?:\.\d{1,9})?Z) run launcher stderr \| (.{1,600})$/;
/** Launcher lines kept (a run of 256 modules says far fewer). */
const MAX_LINES = 4096;
/** Bytes of the job's log read (its lines come in order: the launcher's end lines are in the run step's). */
const MAX_LOG_CHARS = 32 * 1024 * 1024;

/** The launcher's lines of the job's log, with their times; none when the log cannot be read (the replay then has none of them). */
export async function fetchLauncherLines(id: string, fetchFn: typeof fetch = fetch): Promise<LauncherLine[]> {
  let text: string;
  try {
    text = await (await getOk(`/api/jobs/${encodeURIComponent(id)}/log`, fetchFn)).text();
  } catch {
    return [];
  }
  return launcherLinesOf(text.length > MAX_LOG_CHARS ? text.slice(0, MAX_LOG_CHARS) : text);
}

/** The launcher's lines of a job's log text (`<t ISO> <step> <source> <stream> | <line>` a line). */
export function launcherLinesOf(text: string): LauncherLine[] {
  const out: LauncherLine[] = [];
  for (const l of text.split('\n')) {
    if (out.length >= MAX_LINES) break;
    if (!l.includes(' run launcher stderr | ')) continue;
    const m = LAUNCHER_LINE.exec(l);
    const wallMs = m ? Date.parse(m[1]!) : NaN;
    if (m && Number.isFinite(wallMs)) out.push({ wallMs, line: m[2]! });
  }
  return out;
}

/** A record line's mono_ns and wall_time (ms epoch), or undefined. */
function firstRecord(text: string): { mono: bigint; wallMs: number } | undefined {
  const start = text.indexOf('\n') + 1;
  const end = text.indexOf('\n', start);
  const m = /^(\d{1,20}),(\d{4}-\d\d-\d\dT[\d:.]{8,20}Z),/.exec(text.slice(start, end < 0 ? start + 200 : Math.min(end, start + 200)));
  const wallMs = m ? Date.parse(m[2]!) : NaN;
  return m && Number.isFinite(wallMs) ? { mono: BigInt(m[1]!), wallMs } : undefined;
}

/**
 * The launcher's lines of a job on the records' clock (mono_ns, as a logs folder's
 * contract-launch.log gives them): each at its wall time less that of the run's first record (the
 * earliest first record of the logs `files`: both are the host's clock), from that record's
 * mono_ns. None when no log begins with a record (no time line to put them on). The one mapping of
 * a job's lines, for the Monitor's replay of its logs (applyLauncherLines) and the Timeline's
 * (gone-activations.ts).
 */
export function launcherLinesOnRecordClock(files: readonly LogFile[], lines: readonly LauncherLine[] | undefined): Array<{ monoNs: string; line: string }> {
  if (!lines?.length) return [];
  let first: { mono: bigint; wallMs: number } | undefined;
  for (const f of files) {
    const r = firstRecord(f.pieces ? f.pieces[0] ?? '' : f.text);
    if (r && (!first || r.mono < first.mono)) first = r;
  }
  if (!first) return [];
  const out: Array<{ monoNs: string; line: string }> = [];
  for (const l of lines.slice(0, MAX_LINES)) {
    if (typeof l?.line !== 'string' || !Number.isFinite(l.wallMs)) continue;
    const mono = first.mono + BigInt(Math.round((l.wallMs - first.wallMs) * 1e6));
    out.push({ monoNs: String(mono < 0n ? 0n : mono), line: l.line });
  }
  return out;
}

/**
 * Applies the launcher's end lines of job to `model`, the replay of its logs `files`: each at its
 * time on the records' clock (launcherLinesOnRecordClock), on the run's time line.
 */
export function applyLauncherLines(model: MonitorModel, files: readonly LogFile[], lines: readonly LauncherLine[] | undefined): void {
  applyFolderLauncherLines(model, launcherLinesOnRecordClock(files, lines));
}

/**
 * Applies a logs folder's launcher end lines (GET /api/log-folder `launcherLines`: its
 * contract-launch.log, which the launcher alone writes, each line with its time on the records'
 * clock) to `model`, the replay of that folder's logs, each at its own time (MonitorModel.launcherLineAtMono).
 */
export function applyFolderLauncherLines(model: MonitorModel, lines: readonly { monoNs: string; line: string }[] | undefined): void {
  for (const l of (lines ?? []).slice(0, MAX_LINES)) {
    if (typeof l?.monoNs !== 'string' || typeof l.line !== 'string' || !/^\d{1,20}$/.test(l.monoNs)) continue;
    model.launcherLineAtMono(l.line, Number(l.monoNs));
  }
}
