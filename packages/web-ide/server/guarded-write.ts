import { lstatSync } from 'node:fs';
import { lstat } from 'node:fs/promises';
import { join } from 'node:path';
import { SRC_GEN_DIR, TREE_LOCK_NAME, projectRootOf } from '@contract-studio/conventions';
import type { WorkspacePaths } from './workspace-paths.js';
import { WorkspaceFs, type DirAt } from './workspace-fs.js';
import { writeFileAtomic } from './atomic-write.js';
import { HttpError } from './http-error.js';
import { isGeneratedFile, splitGeneratedPath } from './generated-files.js';
import { guardGeneratedWrite } from './region-guard.js';
import { finishInterruptedRename, loadRegionParser, loadTreeLock, type JournalOutcome } from './integrations.js';
import type { GeneratedTreeLock } from './generated-tree-lock.js';
import type { FileWriteResponse } from './api-types.js';
import { fileVersion } from './file-version.js';
import { FileLocks } from './file-locks.js';
import { undecodableLine, undecodableRefusal } from './undecodable.js';

const MAX_COMPARED_BYTES = 8 * 1024 * 1024;

async function readIfPresent(dir: DirAt, name: string, rel: string): Promise<Buffer | undefined> {
  let handle;
  let st;
  try {
    ({ handle, stats: st } = await WorkspaceFs.openFile(dir, name, rel));
  } catch (e) {
    if ((e as NodeJS.ErrnoException).code === 'ENOENT') return undefined;
    throw e;
  }
  try {
    if (!st.isFile()) throw new HttpError(409, 'a folder has that name');
    // a tab never loaded more (GET /api/file refuses it): it cannot be the base of a save
    if (st.size > MAX_COMPARED_BYTES) throw new HttpError(409, `${rel} on disk is larger than 8 MiB: not overwritten`);
    return await handle.readFile();
  } finally {
    await handle.close();
  }
}

async function written(rel: string, file: string, bytes: Buffer, extra: Partial<FileWriteResponse> = {}): Promise<FileWriteResponse> {
  return { path: rel, mtimeMs: (await lstat(file)).mtimeMs, version: fileVersion(bytes), ...extra };
}

/**
 * A save made on a base that is not the file on disk is never written blindly: 409 with the disk's
 * text and version, from which the client merges (src/workspace/three-way-merge.ts). A file that
 * no longer exists is written (nothing on disk to lose: the tab recreates it).
 */
function checkBase(rel: string, base: string | undefined, disk: Buffer | undefined): void {
  if (base === undefined || disk === undefined) return;
  const version = fileVersion(disk);
  if (version === base) return;
  throw new HttpError(409, `${rel} changed on disk since this text was loaded`, { stale: true, version, content: disk.toString('utf8') });
}

export interface SaveOptions {
  /** The version (fileVersion) of the text the save was made on: `If-Match`. Undefined: a blind write. */
  base?: string;
  /** The per-file queue of the server (one per IDE server, shared by every request). */
  fileLocks?: FileLocks;
}

/**
 * The save of PUT /api/file. A file the generator owns (generated-files.ts) is guarded
 * (region-guard.ts): only its protected regions are taken from `body`; the generated code around
 * them stays the disk's (answer `merged`), and a write that cannot be merged is refused with 409.
 * Every other file is written as given. Before either, a save naming its base version (`If-Match`)
 * is compared with the disk: a stale base is refused with 409 and the disk's text (checkBase).
 * Writes are atomic; every save of a file runs in that file's queue (FileLocks), guarded ones also
 * under the tree lock, so that Generate All cannot rewrite the file between the read and the write.
 */
export async function saveWorkspaceFile(
  paths: WorkspacePaths, rel: string, body: Buffer, lock: GeneratedTreeLock, options: SaveOptions = {},
): Promise<FileWriteResponse> {
  // the parent folder is opened from the workspace root without following links (workspace-fs.ts);
  // the temp file is created O_EXCL in it and renamed over the entry, never through a link
  const save = (): Promise<FileWriteResponse> => paths.fs.withParent(rel, true, async (dir, name) => {
    const file = dir.at(name);
    const entry = await WorkspaceFs.entry(dir, name);
    if (entry?.isDirectory()) throw new HttpError(409, 'a folder has that name');
    // a FIFO, socket or device is not replaced by a file behind the user's back
    if (entry && !entry.isFile() && !entry.isSymbolicLink()) throw new HttpError(409, `${rel} is not a regular file (a FIFO, socket or device): not overwritten`);
    // the version check comes first, for every file; a generated file's save that passes it then
    // goes through the region guard (docs/ide.md, "Saves, versions and merges")
    const diskBytes = entry?.isFile() || options.base !== undefined || splitGeneratedPath(rel) ? await readIfPresent(dir, name, rel) : undefined;
    checkBase(rel, options.base, diskBytes);
    if (options.base !== undefined && diskBytes === undefined && splitGeneratedPath(rel)) throw goneGenerated(rel);
    // bytes that are not UTF-8 are never overwritten by the editor's text of them (undecodable.ts)
    const badLine = diskBytes === undefined ? undefined : undecodableLine(diskBytes);
    if (badLine !== undefined && !diskBytes!.equals(body)) throw new HttpError(409, undecodableRefusal(rel, badLine), { undecodableLine: badLine });
    if (!splitGeneratedPath(rel)) {
      await writeFileAtomic(file, body);
      return written(rel, file, body);
    }
    return guardedSave(paths, rel, file, diskBytes, body);
  });
  // a generated file edited from a version whose folder is gone: refused before any folder of its
  // path is made again (goneGenerated)
  if (options.base !== undefined && splitGeneratedPath(rel)) {
    const there = await paths.fs.withParent(rel, false, async (dir, name) => !!(await WorkspaceFs.entry(dir, name))).catch(() => false);
    if (!there) throw goneGenerated(rel);
  }
  // the whole read-compare-write of one file runs in its queue; generated files also in the tree
  // lock, and in the tree's write lock that `contract generate` and `contract rename` take in
  // another process (codegen tree-lock.ts): a terminal's generate cannot write the file between
  // this save's read and its write
  const generated = splitGeneratedPath(rel);
  // a model or scenario file of a project that has a src-gen: a terminal's `contract rename` holds
  // that tree's lock while it rewrites them (the .contract files it loaded, renamed): this save then
  // waits for it, and finds the renamed file (409 stale: the tab merges), never writes under it
  const model = generated ? undefined : projectTreeOf(paths, rel);
  const locked = () => (generated ? lock.run(() => withTreeWriteLock(paths, generated.srcGen, save)) : model !== undefined ? withTreeWriteLock(paths, model, save) : save());
  return (options.fileLocks ?? new FileLocks()).run(rel, locked);
}

async function guardedSave(paths: WorkspacePaths, rel: string, file: string, diskBytes: Buffer | undefined, body: Buffer): Promise<FileWriteResponse> {
  const disk = diskBytes?.toString('latin1');
  if (disk === undefined || !(await isGeneratedFile(paths.root, rel, disk))) {
    await writeFileAtomic(file, body);
    return written(rel, file, body);
  }
  const decision = guardGeneratedWrite(body.toString('latin1'), disk, rel, await loadRegionParser());
  if (decision.kind === 'refuse') {
    throw new HttpError(409, decision.message, { region: decision.region, line: decision.line, generated: true });
  }
  const bytes = Buffer.from(decision.text, 'latin1');
  if (decision.text !== disk) await writeFileAtomic(file, bytes);
  if (decision.kind === 'write') return written(rel, file, bytes);
  return written(rel, file, bytes, { merged: true, reason: decision.reason, content: bytes.toString('utf8') });
}

/**
 * Runs `work` holding the write lock of the generated tree in folder `srcGen` (a path that names it
 * through an opened folder), taken without blocking the event loop; a lock still held by another
 * writer after the wait is a 503 (`prefix` then the wait's message), which a tab retries (a 4xx it
 * keeps without retrying). Released while the folder is still open: the lock's path names it
 * through its descriptor.
 */
async function holdingTreeLock<T>(srcGen: string, what: string, prefix: string, work: () => Promise<T>): Promise<T> {
  const lockTree = await loadTreeLock();
  let release: () => void;
  try {
    release = await lockTree(srcGen, what);
  } catch (e) {
    throw new HttpError(503, `${prefix}${(e as Error).message}`);
  }
  try {
    return await work();
  } finally {
    release();
  }
}

/**
 * The src-gen (workspace-relative) of the project that `.contract` or `.scenario` file `rel`
 * belongs to, by the project rule (conventions' project-root.ts: that of the outermost folder
 * above it holding one, a real folder, not a link), or undefined when none does.
 */
function projectTreeOf(paths: WorkspacePaths, rel: string): string | undefined {
  if (!/\.(contract|scenario)$/.test(rel)) return undefined;
  const hasTree = (folder: string) => lstatSync(join(paths.root, folder, SRC_GEN_DIR), { throwIfNoEntry: false })?.isDirectory() ?? false;
  const { root } = projectRootOf(rel, hasTree, []);
  return hasTree(root) ? (root ? `${root}/${SRC_GEN_DIR}` : SRC_GEN_DIR) : undefined;
}

/** Runs `write` (a save) holding the write lock of generated tree `srcGen` (a workspace-relative folder), taken from its opened folder. */
function withTreeWriteLock<T>(paths: WorkspacePaths, srcGen: string, write: () => Promise<T>): Promise<T> {
  return paths.fs.withParent(`${srcGen}/${TREE_LOCK_NAME}`, true, (dir) => holdingTreeLock(dir.at('.'), srcGen, 'not saved yet: ', write));
}

/**
 * Runs `work` (Generate All, a rename's carry-over) holding the write lock of the generated tree of
 * project folder `dir` (an opened folder's path): the generator's own take in writeTree then finds
 * it held by this process (re-entrant) and does not wait — it waited with a sleeping thread, and a
 * terminal's generate holding the lock froze the whole server for up to 30 s. A src-gen that is
 * not there (Generate All makes it) or not a real folder (the generator refuses it) is not locked.
 */
export function withProjectTreeLock<T>(dir: string, work: (journal: JournalOutcome) => Promise<T>, shown: (path: string) => string = (p) => p): Promise<T> {
  const srcGen = join(dir, SRC_GEN_DIR);
  if (!lstatSync(srcGen, { throwIfNoEntry: false })?.isDirectory()) return work({});
  // a `contract rename` killed half-way is finished first, lock held (codegen rename-journal.ts)
  return holdingTreeLock(srcGen, SRC_GEN_DIR, '', async () => work(await finishInterruptedRename(dir, srcGen, shown)));
}

/**
 * A generated file edited from a version that is no longer on disk at all: its module was renamed
 * or removed since (a terminal's contract rename, Generate All). Recreated, it would be a stale copy
 * outside the build with its old region IDs (typing during a rename went there, unseen).
 */
function goneGenerated(rel: string): HttpError {
  return new HttpError(409, `${rel} no longer exists (its module was renamed or removed since this text was loaded): not recreated, as a copy outside the build; your text is kept in this browser — copy your code into the file's new place`, { gone: true });
}
