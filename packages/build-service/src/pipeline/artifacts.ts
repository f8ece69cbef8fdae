/**
 * A finished run's artifacts: the CSV logs the modules wrote to the work dir's `logs/` (Seam 5,
 * LOG_DIR), collected out of every sandbox before the workspace is released, so they outlive it.
 * Host side rules (docs/sandbox.md): the sandbox is stopped first; only regular files are taken,
 * never through a link the sandboxed code planted (no-follow host reads; Docker's archive API,
 * whose tar reports links as links); names are plain (`[A-Za-z0-9_.-]`, no leading dot); the
 * number of entries looked at, of files, each file's size and the total are bounded, the modules' own
 * logs (named as the runtime names them) taken before any other file, so that a module writing
 * thousands of files there cannot push the others' logs out. What is left out is listed with why.
 *
 * A log is never dropped for its size (docs/build-service-api.md "Artifacts"): one above the file
 * bound, or past the total bound, is kept up to the bound, cut after its last whole record, with a
 * `log-capped` record saying so. The bounds are large enough for the logs of an hour of the
 * mobile-robot example (the soak benchmark: 141 MiB of CSV in 10 min, 28 MiB for its biggest module): the
 * runtime bounds each module's file itself (CONTRACT_LOG_MAX_BYTES, docs/runtime-api.md: 3/4 of the
 * work dir's room, at most limits.ts RUN_LOG_MAX_BYTES), a run's collection keeps that much of a file
 * when it is more than the 256 MiB default (artifactBoundsFor), and the service keeps every
 * collected file gzip-compressed in memory.
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { gunzipSync, gzip as gzipCb } from 'node:zlib';
import { formatBytes, RUN_LOG_MAX_BYTES, RUNTIME_LOG_MAX_BYTES, SERVICE_BOUNDS } from '../limits.js';
import { readFileHeadNoFollow } from '../util/safe-fs.js';
import type { TarEntryKind } from '../util/tar-reader.js';
import { moduleOfLog } from '../trace/parse.js';
import { LAUNCHER_LINES_FILE } from '../trace/launcher-lines-file.js';

const gzip = promisify(gzipCb);

export interface ArtifactBounds {
  /** Entries of a folder looked at (a run may leave millions): the rest is not listed. */
  entries: number;
  files: number;
  /** Bytes kept of one file (the runtime's own per-module bound, CONTRACT_LOG_MAX_BYTES' default; a run's own bound when larger: artifactBoundsFor). */
  fileBytes: number;
  /** Bytes kept over all the files (uncompressed). */
  totalBytes: number;
}

export const ARTIFACT_BOUNDS: ArtifactBounds = { entries: SERVICE_BOUNDS.listedEntries, files: 256, fileBytes: RUNTIME_LOG_MAX_BYTES, totalBytes: 2 * 1024 * 1024 * 1024 };

/**
 * The bounds of a run whose modules were given `logMaxBytes` (CONTRACT_LOG_MAX_BYTES; null: none
 * given): a file is kept up to that bound when it is above the default, so that a large work dir's
 * longer logs (ORD's) are collected whole, never more than RUN_LOG_MAX_BYTES. The default
 * otherwise: a small run's collection reads no more than before (a sparse file of a terabyte costs
 * a read of the bound).
 */
export function artifactBoundsFor(logMaxBytes: number | null): ArtifactBounds {
  if (logMaxBytes === null || !(logMaxBytes > ARTIFACT_BOUNDS.fileBytes)) return ARTIFACT_BOUNDS;
  return { ...ARTIFACT_BOUNDS, fileBytes: Math.min(RUN_LOG_MAX_BYTES, Math.floor(logMaxBytes)) };
}

/** The runtime's marker event (runtime/src/csvlog.c) and the one the service appends to a cut file. */
export const LOG_CAPPED_EVENT = 'log-capped';
/** A log-capped record's size column (the log's bound, or what the disk took), and its detail's head, in the log's tail. */
const CAPPED_SIZE = /,log-capped,[^,\n]{0,64},[^,\n]{0,16},(\d{1,15}),([^\n]{0,120})/;
/**
 * A log-capped record's detail when the disk refused a write (runtime/src/csvlog.c write_all, and
 * write_cap_final at exit: `K records not written after the log could not be written past N bytes
 * (...)`), not the bound: its size column is then what the disk took.
 */
const DISK_REFUSED = /^(?:\d{1,20} records not written after the )?log could not be written past /;
/** A log the logs' disk reserve stopped (CONTRACT_LOG_DISK_RESERVE_BYTES: the work dir nearly full). */
const DISK_RESERVE = /^(?:\d{1,20} records not written after the )?log stopped at \d{1,20} bytes/;

/** The folders of the work dir a run leaves things in: `logs/` (collected) and `run/` (names only). */
export const LOG_DIR = 'logs';
export const RUN_DIR = 'run';

/** One entry of a work-dir folder as the sandbox reports it, without following links. */
export interface DirEntryInfo {
  name: string;
  kind: TarEntryKind;
  size: number;
  /**
   * The first maxBytes bytes of a regular file, all of it when smaller (null when it is gone, not
   * regular, or the signal aborted the read).
   */
  read(maxBytes: number, signal?: AbortSignal): Promise<Buffer | null>;
}

/**
 * A folder listing: null when the folder does not exist; `notDirectory` when something else sits
 * there; `more` when the folder has more than the bound of entries looked at (not listed).
 */
export type DirListing = { entries: DirEntryInfo[]; more?: boolean } | { notDirectory: TarEntryKind } | null;

export interface Artifact {
  /** File name (unique; the URL segment of GET /api/jobs/:id/artifacts/<name>). */
  name: string;
  /** Path in the work dir, e.g. `logs/MSC_21-Nov-2026-22h57m07s.csv`. */
  path: string;
  /** Bytes of the collected file (uncompressed; after the cut, if it was cut). */
  size: number;
  /** Those bytes, gzip-compressed (artifactBytes() gives them back). */
  gzip: Buffer;
  /** Why the log is not whole (a `log-capped` record marks where), or null when it is. */
  capped: string | null;
}

/** The collected bytes of an artifact. */
export function artifactBytes(a: Artifact): Buffer {
  return gunzipSync(a.gzip);
}

export interface SkippedArtifact {
  name: string;
  reason: string;
  /** Left out because a bound (file count, total bytes) was reached: records were lost. */
  bound?: true;
}

export interface RunArtifacts {
  files: Artifact[];
  skipped: SkippedArtifact[];
  /** Names left in the run directory after the launcher ended (should be none). */
  runDirLeftovers: string[];
}

/** The names of files the collector takes (and the live trace tails). */
export const SAFE_NAME = /^[A-Za-z0-9_-][A-Za-z0-9_.-]{0,199}$/;

/** Room kept under a bound for the service's `log-capped` record. */
const MARKER_ROOM = 512;

/** Bytes of the tail searched for the runtime's `log-capped` records (it writes them last). */
const TAIL_BYTES = 4096;

/**
 * The mono_ns of the last record of `kept` (whole lines), undefined when it has none (a header
 * alone, a file of zeros): the time of the service's log-capped record, so that it is read as a
 * record (a trace reader needs a time) and sorts after what was kept, where the cut is.
 */
function lastMonoNs(kept: Buffer): string | undefined {
  const start = kept.lastIndexOf(10, kept.length - 2) + 1;
  const comma = kept.indexOf(44, start);
  const first = comma === -1 ? '' : kept.subarray(start, comma).toString('latin1');
  return /^\d{1,19}$/.test(first) ? first : undefined;
}

/**
 * A CSV record (docs/runtime-api.md columns) saying the service cut the file, at `mono` (the last
 * kept record's time; for a file that kept none, the latest record of the run's other logs: a time
 * of 0 would make the run begin at the machine's boot, hours before its records).
 */
function cutRecord(name: string, keptBytes: number, size: number, bound: number, mono: string): string {
  // the log's module (a runtime log's name says it whole, `MSC_2_6-Dec-…`; another name up to its first `_<digit>`)
  const module = moduleOfLog(name) ?? /^([A-Za-z0-9_]+?)_\d/.exec(name)?.[1] ?? '';
  return `${mono},${new Date().toISOString()},${module},${LOG_CAPPED_EVENT},build-service,,${size},collected the first ${keptBytes} of ${size} bytes (the ${bound}-byte bound of the build service)\n`;
}

/** The later of two mono_ns texts (digits only: compared as numbers, a leading zero too). */
const laterMono = (a: string | undefined, b: string | undefined): string | undefined =>
  a === undefined ? b : b === undefined ? a : BigInt(a) >= BigInt(b) ? a : b;

/** A collected file's entry, its bytes compressed. */
const artifactOf = async (name: string, kept: Buffer, capped: string | null): Promise<Artifact> =>
  ({ name, path: `${LOG_DIR}/${name}`, size: kept.length, gzip: await gzip(kept), capped });

/** Sees the bytes of each collected file before they are compressed (run-issues.ts). */
export type ArtifactInspector = (name: string, data: Buffer) => void;

export interface CollectOptions {
  /** Modules the run's launcher started (run-issues.ts): their logs are taken first. */
  launchedModules?: ReadonlySet<string>;
  /** A cancel: the files not read yet are left out (listed in `skipped`), a read under way is stopped. */
  signal?: AbortSignal;
  /**
   * What filled the work dir (work-usage.ts describeWorkUsage: `bigfile 253 MiB (of 255 MiB in 12
   * file(s))`), asked once, only when a log stopped at the logs' disk reserve: its reason names it
   * rather than guessing that the logs filled it. Null: not measured.
   */
  workFilledBy?: () => Promise<string | null>;
}

/** Why a file was not read: the job was cancelled while its logs were collected. */
export const CANCELLED_REASON = 'not read: the job was cancelled during the collection';

/**
 * Which entries of logs/ are taken first when there are more than the bounds allow (one rule for
 * every sandbox): 0 the runtime's log of a module the launcher started (`<MODULE>_<date>.csv`) and the
 * launcher's own lines (`contract-launch.log`), 1
 * another name the runtime gives its logs, 2 anything else; by name within each rank. A program
 * that fills logs/ with files of its own does not push the modules' logs out.
 */
export function collectionRank(name: string, launchedModules?: ReadonlySet<string>): number {
  if (name === LAUNCHER_LINES_FILE) return 0; // the launcher's own lines (how each module ended): small, written by it alone
  const module = moduleOfLog(name);
  if (module === undefined) return 2;
  return launchedModules?.has(module) ? 0 : 1;
}

/** The entries in collection order (collectionRank, then name). */
export function inCollectionOrder<T extends { name: string }>(entries: readonly T[], launchedModules?: ReadonlySet<string>): T[] {
  const ranked = entries.map((e) => ({ e, rank: collectionRank(e.name, launchedModules) }));
  ranked.sort((a, b) => a.rank - b.rank || (a.e.name < b.e.name ? -1 : a.e.name > b.e.name ? 1 : 0));
  return ranked.map((r) => r.e);
}

/** Picks the artifacts of a `logs/` listing under the bounds. */
export async function selectArtifacts(
  listing: DirListing,
  bounds: ArtifactBounds = ARTIFACT_BOUNDS,
  inspect?: ArtifactInspector,
  options: CollectOptions = {},
): Promise<Pick<RunArtifacts, 'files' | 'skipped'>> {
  const files: Artifact[] = [];
  const skipped: SkippedArtifact[] = [];
  if (listing === null) return { files, skipped };
  if ('notDirectory' in listing) return { files, skipped: [{ name: LOG_DIR, reason: `${LOG_DIR}/ is a ${listing.notDirectory}, not a directory: not followed` }] };
  let total = 0;
  /** The latest record of the logs collected, and the cut files that kept none (their record waits for it). */
  let latest: string | undefined;
  const timeless: { index: number; name: string; kept: Buffer; size: number; bound: number; capped: string }[] = [];
  /** What filled the work dir (options.workFilledBy), asked at the first log stopped at the disk reserve; null: not known. */
  let filledBy: string | null | undefined;
  // the sandbox decides how many entries there are: only a bounded number is looked at, the modules' logs first
  const all = inCollectionOrder(listing.entries, options.launchedModules);
  const sorted = all.slice(0, bounds.entries);
  for (const e of sorted) {
    const skip = (reason: string, bound?: true): void => void skipped.push({ name: e.name, reason, ...(bound ? { bound } : {}) });
    const room = Math.min(bounds.fileBytes, bounds.totalBytes - total);
    if (options.signal?.aborted) skip(CANCELLED_REASON);
    else if (e.kind !== 'file') skip(`not a regular file (${e.kind}): not followed`);
    else if (!SAFE_NAME.test(e.name)) skip('name not allowed (letters, digits, _ . - only)');
    else if (files.length >= bounds.files) skip(`more than ${bounds.files} files`, true);
    else if (e.size > room && room <= MARKER_ROOM)
      skip(room < bounds.fileBytes ? `the ${bounds.totalBytes}-byte total bound is reached` : `${e.size} bytes, above the ${bounds.fileBytes}-byte file bound`, true);
    else {
      const cut = e.size > room;
      const data = await e.read(cut ? room - MARKER_ROOM : room, options.signal);
      if (!data) {
        skip(options.signal?.aborted ? CANCELLED_REASON : 'not readable as a regular file');
        continue;
      }
      let kept = data;
      let capped: string | null = null;
      if (cut) {
        const end = data.lastIndexOf(10) + 1; // whole records only
        const bound = room === bounds.fileBytes ? bounds.fileBytes : bounds.totalBytes;
        capped = `${e.size} bytes: the first ${end} kept (the ${bound}-byte ${bound === bounds.fileBytes ? 'file' : 'total'} bound of the build service)`;
        const mono = lastMonoNs(data.subarray(0, end));
        latest = laterMono(latest, mono);
        if (mono === undefined) {
          // its record's time is the run's latest, known once every log was read
          // a copy of the kept bytes: a view would hold the whole read (up to the file bound, of a sparse file) until the end
          timeless.push({ index: files.length, name: e.name, kept: Buffer.from(data.subarray(0, end)), size: e.size, bound, capped });
          files.push({ name: e.name, path: `${LOG_DIR}/${e.name}`, size: end, gzip: Buffer.alloc(0), capped });
          total += end + MARKER_ROOM;
          continue;
        }
        kept = Buffer.concat([data.subarray(0, end), Buffer.from(cutRecord(e.name, end, e.size, bound, mono))]);
      } else {
        latest = laterMono(latest, lastMonoNs(data));
        const tail = data.subarray(Math.max(0, data.length - TAIL_BYTES));
        if (tail.includes(`,${LOG_CAPPED_EVENT},`)) {
          // the bound is the log-capped record's size column (docs/runtime-api.md); a write the disk
          // refused ends the log the same way, its size column then what the disk took
          const m = CAPPED_SIZE.exec(tail.toString('latin1'));
          if (m && DISK_RESERVE.test(m[2]!)) filledBy ??= (await options.workFilledBy?.().catch(() => null)) ?? null;
          capped = m && DISK_REFUSED.test(m[2]!)
            ? `the disk refused its module's writes past ${formatBytes(Number(m[1]))} (the work dir was full): later records were not written`
            : m && DISK_RESERVE.test(m[2]!)
              ? `its module stopped writing at ${formatBytes(Number(m[1]))}: the work dir was nearly full${filledBy ? `, filled by ${filledBy}` : ''} (the logs' disk reserve, CONTRACT_LOG_DISK_RESERVE_BYTES, keeps its last room): later records were not written`
              : `the module reached its CSV log bound${m ? ` of ${formatBytes(Number(m[1]))}` : ''} (CONTRACT_LOG_MAX_BYTES): later records were not written`;
        }
      }
      inspect?.(e.name, kept);
      total += kept.length;
      files.push(await artifactOf(e.name, kept, capped));
    }
  }
  for (const t of timeless) {
    const kept = Buffer.concat([t.kept, Buffer.from(cutRecord(t.name, t.kept.length, t.size, t.bound, latest ?? '0'))]);
    inspect?.(t.name, kept);
    files[t.index] = await artifactOf(t.name, kept, t.capped);
  }
  if (listing.more || all.length > sorted.length) {
    skipped.push({ name: `${LOG_DIR}/`, reason: `more than ${bounds.entries} entries: the others were not looked at` });
  }
  return { files, skipped };
}

function kindOfStats(st: { isFile(): boolean; isDirectory(): boolean; isSymbolicLink(): boolean }): TarEntryKind {
  return st.isFile() ? 'file' : st.isDirectory() ? 'dir' : st.isSymbolicLink() ? 'symlink' : 'other';
}

/**
 * Lists workDir/rel on the host (bwrap, none) with lstat only, at most `maxEntries` entries (the
 * folder is read as a stream, never whole); reads with O_NOFOLLOW. The entries named as the
 * runtime names its logs come first (as in Docker's listing, docker-folder-list.ts): a first pass
 * over the folder's names (at most SERVICE_BOUNDS.scannedLogNames of them, nothing kept but those
 * names) finds them, so that thousands of files a program left beside them do not push them out of
 * the entries looked at; then the folder's other entries, in its order.
 */
export async function listHostDir(workDir: string, rel: string, maxEntries = ARTIFACT_BOUNDS.entries): Promise<DirListing> {
  const dir = join(workDir, rel);
  let st;
  try {
    st = await fsp.lstat(dir);
  } catch {
    return null;
  }
  if (!st.isDirectory()) return { notDirectory: kindOfStats(st) };
  const logs = await readNames(dir, SERVICE_BOUNDS.scannedLogNames, maxEntries, (name) => moduleOfLog(name) !== undefined);
  if (!logs) return null;
  const chosen = new Set(logs.names);
  const rest = await readNames(dir, Number.MAX_SAFE_INTEGER, maxEntries - chosen.size, (name) => !chosen.has(name));
  if (!rest) return null;
  const names = [...logs.names, ...rest.names];
  const more = rest.more || logs.more;
  const entries: DirEntryInfo[] = [];
  for (const name of names) {
    const est = await fsp.lstat(join(dir, name)).catch(() => null);
    if (!est) continue;
    entries.push({
      name,
      kind: kindOfStats(est),
      size: est.size,
      read: (maxBytes) => readFileHeadNoFollow(workDir, `${rel}/${name}`, maxBytes).catch(() => null),
    });
  }
  return { entries, ...(more ? { more } : {}) };
}

/**
 * The names of `dir` that `keep` takes, at most `maxKept` of them, out of at most `maxRead` names
 * read (the folder read as a stream); `more` when a name past either bound was left. Null when the
 * folder cannot be opened.
 */
async function readNames(dir: string, maxRead: number, maxKept: number, keep: (name: string) => boolean): Promise<{ names: string[]; more: boolean } | null> {
  // the folder is the sandbox's: read a bounded number of its entries, not all of them at once
  const handle = await fsp.opendir(dir, { bufferSize: 64 }).catch(() => null);
  if (!handle) return null;
  const names: string[] = [];
  let read = 0;
  let more = false;
  try {
    for await (const d of handle) {
      if (!keep(d.name)) {
        if (++read >= maxRead) break; // leaving the loop closes the handle
        continue;
      }
      if (names.length >= maxKept) {
        more = true;
        break;
      }
      names.push(d.name);
      read++;
    }
  } catch {
    /* the folder changed or went away while it was read: what was read is listed */
  }
  return { names, more };
}

/** How a sandbox lists work-dir folders (docker: through the archive API of its volume). */
export type WorkDirReader = (workDir: string, rels: string[], maxBytes: number, maxEntries: number) => Promise<Map<string, DirListing>>;

export const hostWorkDirReader: WorkDirReader = async (workDir, rels, _maxBytes, maxEntries) => {
  const out = new Map<string, DirListing>();
  for (const rel of rels) out.set(rel, await listHostDir(workDir, rel, maxEntries));
  return out;
};

/** Collects the run's artifacts; call only once every process of the run is gone. */
export async function collectRunArtifacts(
  read: WorkDirReader,
  workDir: string,
  bounds: ArtifactBounds = ARTIFACT_BOUNDS,
  inspect?: ArtifactInspector,
  options: CollectOptions = {},
): Promise<RunArtifacts> {
  const listings = await read(workDir, [LOG_DIR, RUN_DIR], bounds.totalBytes, bounds.entries);
  const { files, skipped } = await selectArtifacts(listings.get(LOG_DIR) ?? null, bounds, inspect, options);
  const run = listings.get(RUN_DIR) ?? null;
  const runDirLeftovers = run && 'entries' in run ? run.entries.map((e) => e.name).sort().slice(0, bounds.entries) : [];
  return { files, skipped, runDirLeftovers };
}
