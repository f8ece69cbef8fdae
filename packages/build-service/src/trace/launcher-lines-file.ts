/**
 * The launcher's own lines file in a run's logs folder, `contract-launch.log` (docs/runtime-api.md
 * "contract-launch"): every line contract-launch says, written there by the launcher alone (an fd
 * no module inherits) as `<mono_ns> <line>` — the records' clock —, so that a run recorded outside
 * the build service (`make run`, `contract run`) keeps how each module ended:
 * `123456789 module MAB (pid 41) died by signal 9 (Killed)`. A module's own output never reaches it
 * (the launcher forwards it tagged `[NAME]` on its stdout and stderr). Read by `contract trace
 * LOGDIR` (a module told gone at its last record, the line as the evidence) and by the IDE's
 * replay of a logs folder (GET /api/log-folder). Browser-safe.
 *
 * Hostile input: the file is read bounded (MAX_LAUNCHER_LINES_BYTES, its first bytes), only its
 * end lines are kept (launcherEndLine: a line in another shape, longer, or cut is none), at most
 * MAX_LAUNCHER_LINES of them; who reads them takes one only when its pid is the module's own, as
 * that module's `module_started` record gives it.
 */
import { launcherEndLine, type LauncherEnd } from './launcher-end-line.js';

/** Its name in the logs folder (runtime/launcher/contract-launch.c LAUNCHER_LINES_FILE). */
export const LAUNCHER_LINES_FILE = 'contract-launch.log';
/** Bytes of it read at most (the launcher writes 1 MiB at most; a run of 256 modules says far less). */
export const MAX_LAUNCHER_LINES_BYTES = 1024 * 1024;
/** End lines kept at most (a module ends once a run; 256 modules at most). */
export const MAX_LAUNCHER_LINES = 4096;

/** One of the launcher's end lines of the file, with its time. */
export interface LauncherFileLine extends LauncherEnd {
  /** When the launcher said it (CLOCK_MONOTONIC ns, as the records' mono_ns). */
  monoNs: bigint;
  /** Its text, without the `contract-launch: ` prefix. */
  line: string;
}

const FILE_LINE = /^(\d{1,19}) (.{1,600})$/;

/**
 * The end lines of the file's text (its first MAX_LAUNCHER_LINES_BYTES characters read: a last
 * line cut there, with no line end, is not taken), in time order.
 */
export function launcherLinesOfFile(text: string): LauncherFileLine[] {
  const read = text.length > MAX_LAUNCHER_LINES_BYTES ? text.slice(0, MAX_LAUNCHER_LINES_BYTES) : text;
  const lines = read.split('\n');
  lines.pop(); // the text after the last line end: empty, or a line cut
  const out: LauncherFileLine[] = [];
  for (const l of lines) {
    if (out.length >= MAX_LAUNCHER_LINES) break;
    const m = FILE_LINE.exec(l);
    const end = m ? launcherEndLine(m[2]!) : undefined;
    if (m && end) out.push({ ...end, monoNs: BigInt(m[1]!), line: m[2]! });
  }
  return out.sort((a, b) => (a.monoNs < b.monoNs ? -1 : a.monoNs > b.monoNs ? 1 : 0));
}

/** The file's end lines handed out in time order, as the records of a story are read (a record's time: those said before it). */
export class LauncherLinesQueue {
  private next = 0;

  constructor(private readonly lines: readonly LauncherFileLine[]) {}

  /** The lines said before `monoNs` (a record's mono_ns, as its text) not handed out yet. */
  before(monoNs: string): LauncherFileLine[] {
    if (this.next >= this.lines.length || !/^\d{1,20}$/.test(monoNs)) return [];
    const at = BigInt(monoNs);
    const from = this.next;
    while (this.next < this.lines.length && this.lines[this.next]!.monoNs < at) this.next++;
    return this.lines.slice(from, this.next);
  }

  /** The lines not handed out yet (after the last record). */
  rest(): LauncherFileLine[] {
    const from = this.next;
    this.next = this.lines.length;
    return this.lines.slice(from);
  }
}
