/**
 * A finished run's artifacts: the CSV logs the modules wrote to the work dir's `logs/` (Seam 5,
 * LOG_DIR), collected out of every sandbox before the workspace is released, so they outlive it.
 * Host side rules (docs/sandbox.md): the sandbox is stopped first; only regular files are taken,
 * never through a link the sandboxed code planted (no-follow host reads; Docker's archive API,
 * whose tar reports links as links); names are plain (`[A-Za-z0-9_.-]`, no leading dot); the
 * number of files, each file's size and the total are bounded. What is left out is listed with why.
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { readFileNoFollow } from '../util/safe-fs.js';
import type { TarEntryKind } from '../util/tar-reader.js';

export interface ArtifactBounds {
  files: number;
  fileBytes: number;
  totalBytes: number;
}

export const ARTIFACT_BOUNDS: ArtifactBounds = { files: 256, fileBytes: 16 * 1024 * 1024, totalBytes: 64 * 1024 * 1024 };

/** The folders of the work dir a run leaves things in: `logs/` (collected) and `run/` (names only). */
export const LOG_DIR = 'logs';
export const RUN_DIR = 'run';

/** One entry of a work-dir folder as the sandbox reports it, without following links. */
export interface DirEntryInfo {
  name: string;
  kind: TarEntryKind;
  size: number;
  /** The bytes of a regular file (null when it is gone, grew past maxBytes, or is not regular). */
  read(maxBytes: number): Promise<Buffer | null>;
}

/** A folder listing: null when the folder does not exist; `notDirectory` when something else sits there. */
export type DirListing = { entries: DirEntryInfo[] } | { notDirectory: TarEntryKind } | null;

export interface Artifact {
  /** File name (unique; the URL segment of GET /api/jobs/:id/artifacts/<name>). */
  name: string;
  /** Path in the work dir, e.g. `logs/MSC_21-Nov-2026-22h57m07s.csv`. */
  path: string;
  size: number;
  data: Buffer;
}

export interface SkippedArtifact {
  name: string;
  reason: string;
}

export interface RunArtifacts {
  files: Artifact[];
  skipped: SkippedArtifact[];
  /** Names left in the run directory after the launcher ended (should be none). */
  runDirLeftovers: string[];
}

const SAFE_NAME = /^[A-Za-z0-9_-][A-Za-z0-9_.-]{0,199}$/;

/** Picks the artifacts of a `logs/` listing under the bounds. */
export async function selectArtifacts(listing: DirListing, bounds: ArtifactBounds = ARTIFACT_BOUNDS): Promise<Pick<RunArtifacts, 'files' | 'skipped'>> {
  const files: Artifact[] = [];
  const skipped: SkippedArtifact[] = [];
  if (listing === null) return { files, skipped };
  if ('notDirectory' in listing) return { files, skipped: [{ name: LOG_DIR, reason: `${LOG_DIR}/ is a ${listing.notDirectory}, not a directory: not followed` }] };
  let total = 0;
  const sorted = [...listing.entries].sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
  for (const e of sorted) {
    const skip = (reason: string): void => void skipped.push({ name: e.name, reason });
    if (e.kind !== 'file') skip(`not a regular file (${e.kind}): not followed`);
    else if (!SAFE_NAME.test(e.name)) skip('name not allowed (letters, digits, _ . - only)');
    else if (files.length >= bounds.files) skip(`more than ${bounds.files} files`);
    else if (e.size > bounds.fileBytes) skip(`${e.size} bytes, above the ${bounds.fileBytes}-byte file bound`);
    else if (total + e.size > bounds.totalBytes) skip(`the ${bounds.totalBytes}-byte total bound is reached`);
    else {
      const data = await e.read(bounds.fileBytes);
      if (!data) skip('not readable as a regular file');
      else if (total + data.length > bounds.totalBytes) skip(`the ${bounds.totalBytes}-byte total bound is reached`);
      else {
        total += data.length;
        files.push({ name: e.name, path: `${LOG_DIR}/${e.name}`, size: data.length, data });
      }
    }
  }
  return { files, skipped };
}

function kindOfStats(st: { isFile(): boolean; isDirectory(): boolean; isSymbolicLink(): boolean }): TarEntryKind {
  return st.isFile() ? 'file' : st.isDirectory() ? 'dir' : st.isSymbolicLink() ? 'symlink' : 'other';
}

/** Lists workDir/rel on the host (bwrap, none) with lstat only; reads with O_NOFOLLOW. */
export async function listHostDir(workDir: string, rel: string): Promise<DirListing> {
  const dir = join(workDir, rel);
  let st;
  try {
    st = await fsp.lstat(dir);
  } catch {
    return null;
  }
  if (!st.isDirectory()) return { notDirectory: kindOfStats(st) };
  const entries: DirEntryInfo[] = [];
  for (const name of await fsp.readdir(dir)) {
    const est = await fsp.lstat(join(dir, name)).catch(() => null);
    if (!est) continue;
    entries.push({
      name,
      kind: kindOfStats(est),
      size: est.size,
      read: (maxBytes) => readFileNoFollow(workDir, `${rel}/${name}`, maxBytes).catch(() => null),
    });
  }
  return { entries };
}

/** How a sandbox lists work-dir folders (docker: through the archive API of its volume). */
export type WorkDirReader = (workDir: string, rels: string[], maxBytes: number) => Promise<Map<string, DirListing>>;

export const hostWorkDirReader: WorkDirReader = async (workDir, rels) => {
  const out = new Map<string, DirListing>();
  for (const rel of rels) out.set(rel, await listHostDir(workDir, rel));
  return out;
};

/** Collects the run's artifacts; call only once every process of the run is gone. */
export async function collectRunArtifacts(read: WorkDirReader, workDir: string, bounds: ArtifactBounds = ARTIFACT_BOUNDS): Promise<RunArtifacts> {
  const listings = await read(workDir, [LOG_DIR, RUN_DIR], bounds.totalBytes);
  const { files, skipped } = await selectArtifacts(listings.get(LOG_DIR) ?? null, bounds);
  const run = listings.get(RUN_DIR) ?? null;
  const runDirLeftovers = run && 'entries' in run ? run.entries.map((e) => e.name).sort() : [];
  return { files, skipped, runDirLeftovers };
}
