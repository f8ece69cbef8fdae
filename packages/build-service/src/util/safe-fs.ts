/**
 * Host file operations on directories that sandboxed code may have written to.
 *
 * Rule (Judge0 CVE-2024-28185/28189): never open, chown or delete a host path through a link the
 * sandboxed code could have planted. Every function here:
 *   - reads open each folder below the trusted root from its opened parent (openFileUnder:
 *     `/proc/self/fd/N/name`, O_DIRECTORY|O_NOFOLLOW), so a folder swapped for a link between two
 *     steps is refused, never followed; writes check each component below the root with lstat (a
 *     symlink or a non-directory component is refused),
 *   - opens files with O_NOFOLLOW and changes owners with fchown on the opened descriptor or lchown,
 *   - removes trees without following symlinks (a link is unlinked, never traversed), with
 *     descriptor-relative walks that work at any depth.
 * They are only called while no process of the job is alive (the sandbox is stopped first), so the
 * checks cannot race with the sandboxed code. The exception, openDirNoFollow / openRegularFileIn,
 * is made for folders a running job changes (the live trace): it holds the folder by descriptor and
 * checks what it opened, not a path.
 */
import { spawn } from 'node:child_process';
import { constants, promises as fsp } from 'node:fs';
import type { FileHandle } from 'node:fs/promises';
import { dirname, join, relative, resolve, sep } from 'node:path';
import { relativePathProblem } from '@contract-studio/conventions';

export class UnsafePathError extends Error {}

export interface Owner {
  uid: number;
  gid: number;
}

/** `rel` must be a relative POSIX path without `..`, NUL, or empty components. */
export function checkRelativePath(rel: string): string {
  const problem = relativePathProblem(rel);
  if (problem) throw new UnsafePathError(problem);
  return rel;
}

/**
 * Creates the directories of `rel` (relative to the trusted `root`) one by one, refusing any
 * existing component that is not a real directory. Returns the absolute path.
 */
export async function ensureDirNoFollow(root: string, rel: string, owner?: Owner): Promise<string> {
  let current = root;
  if (rel === '' || rel === '.') return root;
  for (const part of checkRelativePath(rel).split('/')) {
    current = join(current, part);
    let st;
    try {
      st = await fsp.lstat(current);
    } catch (e) {
      if ((e as NodeJS.ErrnoException).code !== 'ENOENT') throw e;
      await fsp.mkdir(current, { mode: 0o755 });
      if (owner) await fsp.lchown(current, owner.uid, owner.gid);
      continue;
    }
    if (!st.isDirectory()) throw new UnsafePathError(`refusing to use ${current}: not a directory (symlink or file)`);
  }
  return current;
}

/**
 * Writes `content` to root/rel unless the file already holds exactly these bytes (then its mtime
 * is kept, so make sees nothing new). Never follows a symlink. Returns true when it wrote.
 */
export async function syncFileNoFollow(
  root: string,
  rel: string,
  content: Buffer,
  owner?: Owner,
  mode = 0o644,
): Promise<boolean> {
  const clean = checkRelativePath(rel);
  const dir = await ensureDirNoFollow(root, dirname(clean) === '.' ? '' : dirname(clean), owner);
  const path = join(dir, clean.split('/').pop()!);
  let st;
  try {
    st = await fsp.lstat(path);
  } catch (e) {
    if ((e as NodeJS.ErrnoException).code !== 'ENOENT') throw e;
  }
  if (st && !st.isFile()) {
    // something else sits there (maybe planted): remove it without following it
    await removeTreeNoFollow(path);
    st = undefined;
  }
  if (st && st.size === content.length) {
    const fh = await fsp.open(path, constants.O_RDONLY | constants.O_NOFOLLOW);
    try {
      const old = await fh.readFile();
      if (old.equals(content)) return false;
    } finally {
      await fh.close();
    }
  }
  const fh = await fsp.open(path, constants.O_WRONLY | constants.O_CREAT | constants.O_TRUNC | constants.O_NOFOLLOW, mode);
  try {
    await fh.writeFile(content);
    if (owner) await fh.chown(owner.uid, owner.gid);
    await fh.chmod(mode);
  } finally {
    await fh.close();
  }
  return true;
}

/**
 * Opens root/rel as a regular file for reading without following a link anywhere below `root`,
 * with no check-then-use gap: each folder is opened from its opened parent
 * (`/proc/self/fd/N/name`, O_DIRECTORY|O_NOFOLLOW; Node has no openat) and the file from the last
 * one (O_NOFOLLOW|O_NONBLOCK, then fstat). A folder swapped for a link between two steps is refused,
 * never followed. Null, with nothing left open, when a component is missing, a link, or not a
 * folder, or the file is not a regular file.
 */
export async function openFileUnder(root: string, rel: string): Promise<{ fh: FileHandle; size: number } | null> {
  const parts = checkRelativePath(rel).split('/');
  let dir: FileHandle;
  try {
    dir = await fsp.open(root, constants.O_RDONLY | constants.O_DIRECTORY);
  } catch {
    return null;
  }
  try {
    for (const part of parts.slice(0, -1)) {
      const next = await openDirNoFollow(entryPath(dir, part));
      await dir.close();
      dir = next;
    }
    return await openRegularFileIn(dir, parts[parts.length - 1]!, constants.O_RDONLY);
  } catch {
    return null;
  } finally {
    await dir.close().catch(() => {});
  }
}

/**
 * Reads up to `limit` bytes of an opened file from its start, into a buffer of the size `expected`
 * (its size when opened) plus one byte, grown only if the file grew meanwhile: a 16 MiB bound costs
 * nothing for a 2 kB file (a buffer of the bound's size for each file made hashing the runtime's
 * 130 sources take 0.7 s).
 */
export async function readUpTo(fh: FileHandle, limit: number, expected = limit): Promise<Buffer> {
  let buf = Buffer.allocUnsafe(Math.max(1, Math.min(limit, expected + 1)));
  let off = 0;
  while (off < limit) {
    if (off === buf.length) {
      const bigger = Buffer.allocUnsafe(Math.min(limit, buf.length * 2));
      buf.copy(bigger, 0, 0, off);
      buf = bigger;
    }
    const { bytesRead } = await fh.read(buf, off, buf.length - off, off);
    if (bytesRead === 0) break;
    off += bytesRead;
  }
  return off === buf.length ? buf : buf.subarray(0, off);
}

/**
 * Reads root/rel without following symlinks in any component (openFileUnder); null if absent, not
 * a regular file, or larger than `maxBytes` (also when it grows past it while read).
 */
export async function readFileNoFollow(root: string, rel: string, maxBytes = 16 * 1024 * 1024): Promise<Buffer | null> {
  const opened = await openFileUnder(root, rel);
  if (!opened) return null;
  try {
    if (opened.size > maxBytes) return null;
    const data = await readUpTo(opened.fh, maxBytes + 1, opened.size);
    return data.length > maxBytes ? null : data;
  } finally {
    await opened.fh.close();
  }
}

/**
 * The first `maxBytes` bytes of root/rel (all of it when smaller), opened like readFileNoFollow
 * (openFileUnder); null if absent or not a regular file.
 */
export async function readFileHeadNoFollow(root: string, rel: string, maxBytes: number): Promise<Buffer | null> {
  const opened = await openFileUnder(root, rel);
  if (!opened) return null;
  try {
    return await readUpTo(opened.fh, Math.min(opened.size, maxBytes));
  } finally {
    await opened.fh.close();
  }
}

/**
 * Removes a tree without ever following a symlink, whatever shape the sandbox gave it: GNU `rm -rf`
 * walks with openat/unlinkat relative to directory descriptors (no path length limit, so 1,000s of
 * nested folders are fine), unlinks links and fifos without opening them, and with
 * `--one-file-system` never descends into a mount it meets (docs/sandbox.md, "Host clean-up").
 * Folders the sandbox made unreadable (chmod 000) stop a non-root service: then `chmod -R u+rwx`
 * (which never follows links met in its walk) opens them and rm runs again.
 */
export async function removeTreeNoFollow(path: string): Promise<void> {
  let st;
  try {
    st = await fsp.lstat(path);
  } catch (e) {
    if ((e as NodeJS.ErrnoException).code === 'ENOENT') return;
    throw e;
  }
  if (!st.isDirectory()) {
    await fsp.unlink(path).catch((e: NodeJS.ErrnoException) => {
      if (e.code !== 'ENOENT') throw e;
    });
    return;
  }
  const first = await runTool('rm', ['-rf', '--one-file-system', '--', path]);
  if (first.code === 0) return;
  await runTool('chmod', ['-R', 'u+rwx', '--', path]);
  const again = await runTool('rm', ['-rf', '--one-file-system', '--', path]);
  if (again.code !== 0) throw new Error(`cannot remove ${path}: ${again.stderr.split('\n')[0] || `rm exit ${again.code}`}`);
}

/**
 * Removes root/rel (a file, or whatever sits there, without following it) when every folder on the
 * way below `root` is a real folder; a missing component, a link or a non-folder on the way: nothing
 * is removed (what a link points to is never reached).
 */
export async function removeFileNoFollow(root: string, rel: string): Promise<void> {
  const parts = checkRelativePath(rel).split('/');
  let current = root;
  for (const part of parts.slice(0, -1)) {
    current = join(current, part);
    const st = await fsp.lstat(current).catch(() => null);
    if (!st?.isDirectory()) return;
  }
  await removeTreeNoFollow(join(current, parts[parts.length - 1]!));
}

/** Runs a coreutils tool; keeps the first 4 KiB of its stderr for the error message. */
function runTool(cmd: string, args: string[]): Promise<{ code: number | null; stderr: string }> {
  return new Promise((resolvePromise) => {
    const child = spawn(cmd, args, { stdio: ['ignore', 'ignore', 'pipe'] });
    let stderr = '';
    child.stderr.on('data', (c: Buffer) => {
      if (stderr.length < 4096) stderr += c.toString();
    });
    child.on('error', (e) => resolvePromise({ code: null, stderr: `cannot start ${cmd}: ${e.message}` }));
    child.on('close', (code) => resolvePromise({ code, stderr: stderr.trim() }));
  });
}

/**
 * Lists regular files under root (relative POSIX paths), never entering symlinked dirs; an entry
 * that is neither a file nor a folder (a link, a FIFO, a device) is not listed, and given to
 * `notListed` when set.
 */
export async function listFilesNoFollow(
  root: string,
  accept: (rel: string, isDir: boolean) => boolean = () => true,
  rel = '',
  notListed?: (rel: string, kind: 'symlink' | 'other') => void,
): Promise<string[]> {
  const out: string[] = [];
  const dir = rel ? join(root, rel) : root;
  let entries;
  try {
    entries = await fsp.readdir(dir, { withFileTypes: true });
  } catch {
    return out;
  }
  entries.sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
  for (const e of entries) {
    const childRel = rel ? `${rel}/${e.name}` : e.name;
    if (e.isDirectory()) {
      if (accept(childRel, true)) out.push(...(await listFilesNoFollow(root, accept, childRel, notListed)));
    } else if (e.isFile()) {
      if (accept(childRel, false)) out.push(childRel);
    } else notListed?.(childRel, e.isSymbolicLink() ? 'symlink' : 'other'); // never followed nor opened: said to the caller
  }
  return out;
}

/** True when `child` (already resolved) is `parent` or inside it. */
export function isInside(parent: string, child: string): boolean {
  const rel = relative(resolve(parent), resolve(child));
  return rel === '' || (!rel.startsWith('..') && !rel.startsWith(sep) && rel !== '..');
}

/**
 * A folder the sandbox may still be changing (a running job's logs/, a work volume), opened once
 * without following a link (O_DIRECTORY | O_NOFOLLOW); its entries are then reached through the
 * descriptor (`entryPath`), so a folder renamed or replaced by a link later is never walked
 * through. Throws the open's error (ENOENT; ENOTDIR for a link or a file; EACCES).
 */
export function openDirNoFollow(path: string): Promise<FileHandle> {
  return fsp.open(path, constants.O_RDONLY | constants.O_DIRECTORY | constants.O_NOFOLLOW);
}

/** The path of a folder opened by openDirNoFollow, through its descriptor (for listing and watching it). */
export function openedDirPath(dir: FileHandle): string {
  return `/proc/self/fd/${dir.fd}`;
}

/** The path of entry `name` of a folder opened by openDirNoFollow, through its descriptor. */
export function entryPath(dir: FileHandle, name: string): string {
  return `${openedDirPath(dir)}/${name}`;
}

/**
 * Opens entry `name` of `dir` (openDirNoFollow) with `access` (O_RDONLY, O_RDWR) as a regular file:
 * a link is refused (O_NOFOLLOW), a FIFO does not block the open (O_NONBLOCK); null, with nothing
 * left open, when it is not a regular file (a FIFO, a socket, a device, a folder). Throws the open's
 * error (ELOOP for a link, ENOENT, EACCES).
 */
export async function openRegularFileIn(dir: FileHandle, name: string, access: number): Promise<{ fh: FileHandle; size: number } | null> {
  const fh = await fsp.open(entryPath(dir, name), access | constants.O_NOFOLLOW | constants.O_NONBLOCK);
  const st = await fh.stat().catch(() => null);
  if (!st?.isFile()) {
    await fh.close().catch(() => {});
    return null;
  }
  return { fh, size: st.size };
}
