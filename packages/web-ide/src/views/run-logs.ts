/**
 * The CSV logs a timeline draws: either the files of a local run (`contract run` writes them to the
 * project's `logs/`, `make run` to its `src-gen/generated/architecture/logs/`) or those the build
 * service collected from a sandboxed Build & Run job (`GET /api/jobs/:id/artifacts[/<name>]`,
 * docs/build-service-api.md), or a trace file of the workspace read as the logs it was written from.
 */
import { TWIN_LOGS_WHY, isLogHeaderIn, traceFileToLogsSteps, twinLogs, type TraceFileLogs } from '@contract-studio/build-service/trace';
import { runSliced } from '../util/sliced.js';
import { api, ApiError, getOk, responsePieces } from '../api.js';
import { activationsFromCsv, type Activation, type ModelModules } from './activation-log.js';
import { fetchLauncherLines, type LauncherLine } from '../monitor/job-launcher-lines.js';

export interface LogFile {
  name: string;
  /** The whole text (for a downloaded log, its pieces joined each time it is read). */
  readonly text: string;
  /**
   * A downloaded log's text in pieces of whole lines (api.ts responsePieces), which the Monitor's
   * reader reads piece by piece: joining a long log into one string held the page's frames.
   */
  readonly pieces?: readonly string[];
}

/** A downloaded log: its pieces, and its text when a reader needs it whole (joined then). */
export function piecedLog(name: string, pieces: readonly string[]): LogFile {
  return {
    name,
    pieces,
    get text() {
      return pieces.join('');
    },
  };
}

/** Characters of a text in pieces. */
export const piecesLength = (pieces: readonly string[]): number => pieces.reduce((n, p) => n + p.length, 0);

export interface RunLogs {
  /** Where the files come from, shown to the user (e.g. `Build & Run job 12`). */
  label: string;
  files: LogFile[];
  /** Files that could not be had, with why (left out by the service, download failed). */
  problems: string[];
  /** A job's crash sites the build service mapped after its run (GET /api/jobs/:id/artifacts `crashSites`: contract trace's lines). */
  crashSites?: string[];
  /** A job's: the launcher's own lines of its log, each with its time (ms epoch), which say how its modules ended (job-launcher-lines.ts). */
  launcherLines?: LauncherLine[];
}

/**
 * The folders of project `project` (workspace-relative, '' = the root) where local runs write
 * their CSV logs, in this order: `logs/` (`contract run`'s default, packages/cli run.ts: DIR/logs;
 * the logs of the runs before are moved to `logs/previous/`, left out here) and
 * `src-gen/generated/architecture/logs/` (`make run`'s LOG_DIR) — each with its `*.csv` files
 * (direct children only) among the workspace's `files`.
 */
export function localLogFolders(project: string, files: readonly string[]): Array<{ folder: string; csvs: string[] }> {
  const pre = project ? `${project}/` : '';
  return [`${pre}logs`, `${pre}src-gen/generated/architecture/logs`].map((folder) => ({
    folder,
    csvs: files.filter((f) => f.endsWith('.csv') && f.startsWith(`${folder}/`) && !f.includes('/', folder.length + 1)),
  }));
}

/** Whether a file's first line is the runtime's header (an empty file too: it holds nothing). */
function beginsAsLog(f: LogFile): boolean {
  const head = f.pieces?.[0] ?? f.text;
  const nl = head.indexOf('\n');
  return head === '' || isLogHeaderIn(head, 0, nl < 0 ? head.length : nl);
}

/**
 * Every activation of the given logs, sorted by start; a file that is not a runtime log is a problem, not a crash.
 * `model`: what the project's model says of the modules, when the IDE has it (activationsFromCsv).
 */
export function activationsFromLogs(files: LogFile[], model?: ModelModules): { acts: Activation[]; errors: string[] } {
  const acts: Activation[] = [];
  const errors: string[] = [];
  // two logs of one module are said, as the Monitor and `contract trace` say them (a file that is
  // no log, its first line not the runtime's header, is none of its module's logs: said below)
  for (const [m, names] of twinLogs(files.filter(beginsAsLog).map((f) => f.name))) errors.push(`${m}: ${names.length} logs of it (${names.slice(0, 3).join(', ')}${names.length > 3 ? ', ...' : ''}), read as one: ${TWIN_LOGS_WHY}`);
  for (const f of files) {
    try {
      const unreadable = { n: 0 };
      for (const a of activationsFromCsv(f.text, f.name, unreadable, model)) acts.push(a); // not push(...): a long run's hundreds of thousands overflow the stack
      if (unreadable.n) errors.push(`${f.name}: ${unreadable.n} line(s) of activations or engine activity that are no record, or whose time is not believed (\`contract trace\` names each), left out`);
    } catch (e) {
      errors.push(`${f.name}: ${(e as Error).message}`);
    }
  }
  return { acts: acts.sort((a, b) => a.start - b.start), errors };
}

interface ArtifactListing {
  status: string;
  artifacts: { files: Array<{ name: string; size: number; capped?: string | null }>; skipped: Array<{ name: string; reason: string }>; crashSites?: unknown };
}

/** Lines of a job's mapped crash sites kept, at most, and characters of one (the service's: bounded all the same). */
const MAX_CRASH_SITE_LINES = 8 * 50;
const MAX_CRASH_SITE_CHARS = 2000;

/** The listing's `crashSites`, when it is a list of lines; bounded. */
function crashSitesOf(v: unknown): string[] {
  if (!Array.isArray(v)) return [];
  return v.filter((l): l is string => typeof l === 'string').slice(0, MAX_CRASH_SITE_LINES).map((l) => l.slice(0, MAX_CRASH_SITE_CHARS));
}

/**
 * Bytes of a run's CSV logs the page reads in all, a job's or a workspace folder's: it holds them
 * and their records (the service keeps up to 2 GiB of a job's files).
 */
export const MAX_RUN_LOG_BYTES = 512 * 1024 * 1024;

/**
 * The order a replay reads a run's logs in under MAX_RUN_LOG_BYTES, so that what it keeps tells the
 * run right: ORD's log and the supervisors' first (they carry the rules, the actions and the
 * schemas' activations, and are small), then the others; each group smallest first (a module's log
 * at 1 kHz is the large one), a log whose size is not known last, equal ones as listed (by name). `logs`:
 * each log's file name (`SUP_6-Dec-2026-10h00m00s.csv`, the module before the first `_`) and
 * size; `supervisors`: the model's supervisors' names (none known: the smallest first keeps them,
 * a supervisor's log being small).
 */
export function replayOrder<T extends { name: string; size?: number }>(logs: readonly T[], supervisors: ReadonlySet<string> = new Set()): T[] {
  const first = (l: T): boolean => {
    const module = l.name.slice(l.name.lastIndexOf('/') + 1).split(/[_.]/)[0]!;
    return module === 'ORD' || supervisors.has(module);
  };
  const size = (l: T): number => (l.size !== undefined && Number.isFinite(l.size) ? l.size : Infinity);
  return logs.map((l, i) => ({ l, i, first: first(l) })).sort((a, b) =>
    a.first !== b.first ? (a.first ? -1 : 1) : size(a.l) !== size(b.l) ? size(a.l) - size(b.l) : a.i - b.i).map((x) => x.l);
}

/** A size as the replay says it: `256.0 MiB`, `12.5 KiB`, `189 bytes`. */
const sizeText = (bytes: number): string =>
  bytes >= 1048576 ? `${(bytes / 1048576).toFixed(1)} MiB` : bytes >= 1024 ? `${(bytes / 1024).toFixed(1)} KiB` : `${bytes} bytes`;

/**
 * What a replay says of a log read only in part (longer than the IDE server sends of one: its first
 * bytes, whole lines): how much, and where the rest is.
 */
export function partlyReadText(name: string, path: string, log: { read: number; size: number; sent: number }): string {
  return `${name}: only its first ${sizeText(log.read)} of ${sizeText(log.size)} read (the IDE reads ${sizeText(log.sent)} of a log for a replay): ` +
    `its later records are not shown; the whole log is ${path} in the workspace (\`contract trace\` reads it whole)`;
}

/**
 * Reads the workspace's CSV logs `paths` (GET /api/log), `maxBytes` in all: each file under the
 * name `nameOf(path)`; a log that cannot be read or is past the bound is a problem naming why, not
 * downloaded (`tooLarge`: one was past a bound); a log longer than the server sends of one is read in
 * part, its first lines, and said in `partly` (partlyReadText). With `sizes` (each path's, GET /api/log-folder),
 * they are read in replayOrder (`supervisors`: the model's), so that the bound leaves out the
 * large module logs, never the supervisors' nor ORD's; the files come back in the paths' order.
 */
export async function readWorkspaceLogs(paths: readonly string[], nameOf: (path: string) => string, maxBytes = MAX_RUN_LOG_BYTES,
  order?: { sizes?: readonly number[]; supervisors?: ReadonlySet<string> }): Promise<{ files: LogFile[]; problems: string[]; partly: string[]; tooLarge: boolean }> {
  const read = new Map<string, LogFile>();
  const problems: string[] = [];
  const partly: string[] = [];
  let tooLarge = false;
  let room = maxBytes;
  const sizes = order?.sizes;
  const ordered = sizes || order?.supervisors
    ? replayOrder(paths.map((p, i) => ({ name: nameOf(p), path: p, size: sizes?.[i] })), order.supervisors).map((x) => x.path)
    : paths;
  for (const p of ordered) {
    const name = nameOf(p);
    try {
      const log = await api.readLog(p, room);
      room -= log.read;
      read.set(p, piecedLog(name, log.pieces));
      if (log.read < log.size) {
        partly.push(partlyReadText(name, p, log));
        tooLarge = true;
      }
    } catch (e) {
      problems.push(`${name}: ${(e as Error).message}`);
      tooLarge ||= e instanceof ApiError && e.status === 413;
    }
  }
  const files = paths.flatMap((p) => read.get(p) ?? []);
  return { files, problems, partly, tooLarge };
}

/**
 * A trace file of the workspace (`*.jsonl`: `contract run --trace`) read through GET /api/log and
 * turned into the logs it was written from (build-service trace/jsonl.ts): `problems` says what
 * could not be read (the file itself, then its lines that are no record).
 */
export async function readTraceFile(path: string, nameOf: (path: string) => string, maxBytes = MAX_RUN_LOG_BYTES): Promise<TraceFileLogs & { tooLarge: boolean }> {
  const { files: read, problems: unread, partly, tooLarge } = await readWorkspaceLogs([path], nameOf, maxBytes);
  const problems = [...unread, ...partly];
  if (!read[0]) return { files: [], problems, skipped: 0, unreadable: 0, order: new Uint16Array(0), tooLarge };
  // its JSON lines parsed in slices: the page draws and answers keys meanwhile
  const logs = await runSliced(traceFileToLogsSteps(path, read[0].text));
  return { ...logs, problems: [...problems, ...logs.problems], tooLarge };
}

/**
 * Downloads the CSV logs the build service collected from job `id` (only `.csv` files,
 * MAX_RUN_LOG_BYTES in all, taken in replayOrder: ORD's and the supervisors' first, then the
 * smallest), in the listing's order.
 */
export async function fetchJobLogs(id: string, fetchFn: typeof fetch = fetch, maxBytes = MAX_RUN_LOG_BYTES, supervisors: ReadonlySet<string> = new Set()): Promise<RunLogs> {
  const base = `/api/jobs/${encodeURIComponent(id)}/artifacts`;
  const listing = (await (await getOk(base, fetchFn)).json()) as ArtifactListing;
  // a skipped artifact that is not a CSV log (a core file, an output too large) is no hole in the logs
  const problems = (listing.artifacts?.skipped ?? []).filter((s) => s.name.endsWith('.csv')).map((s) => `${s.name}: ${s.reason}`);
  const listed = (listing.artifacts?.files ?? []).filter((f) => f.name.endsWith('.csv'));
  const kept = new Set<string>();
  let room = maxBytes;
  for (const f of replayOrder(listed, supervisors)) {
    if (f.size > room) {
      problems.push(`${f.name}: left out (${f.size} bytes, past the ${maxBytes} bytes a replay reads in all)`);
      continue;
    }
    room -= f.size;
    kept.add(f.name);
  }
  const files: LogFile[] = [];
  for (const f of listed) {
    if (!kept.has(f.name)) continue;
    if (f.capped) problems.push(`${f.name}: not whole: ${f.capped}`); // a log-capped record ends it (docs/build-service-api.md, GET /api/jobs/:id/artifacts)
    try {
      files.push(piecedLog(f.name, await responsePieces(await getOk(`${base}/${encodeURIComponent(f.name)}`, fetchFn))));
    } catch (e) {
      problems.push((e as Error).message);
    }
  }
  const crashSites = crashSitesOf(listing.artifacts?.crashSites);
  return { label: `Build & Run job ${id}`, files, problems, ...(crashSites.length ? { crashSites } : {}), launcherLines: await fetchLauncherLines(id, fetchFn) };
}
