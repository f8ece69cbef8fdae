import { constants, existsSync, type Stats } from 'node:fs';
import { open, mkdir, lstat, readdir, unlink, rmdir, type FileHandle } from 'node:fs/promises';
import { HttpError } from './http-error.js';

const { O_RDONLY, O_DIRECTORY, O_NOFOLLOW, O_NONBLOCK } = constants;
const PROC_FD = '/proc/self/fd';

/** A folder opened by WorkspaceFs: `at(name)` names an entry of that folder, whatever its path now is. */
export interface DirAt {
  at(name: string): string;
}

function pathAt(handle: FileHandle): DirAt {
  return { at: (name) => `${PROC_FD}/${handle.fd}/${name}` };
}

/**
 * File operations anchored at the workspace root without check-then-use (docs/ide.md, "Localhost
 * hardening"). Node has no openat(2), so each folder on a path is opened from the previous one
 * through /proc/self/fd/N/<name>: the kernel resolves that relative to the opened folder, not by
 * path, so renaming a folder or swapping it for a symlink while a request runs cannot redirect it.
 * Every component is opened with O_NOFOLLOW|O_DIRECTORY (a symlink anywhere is refused) and the
 * final entry is only ever opened O_NOFOLLOW, created O_EXCL, or renamed/unlinked (which act on
 * the link itself, never on its target).
 *
 * Paths given here are the normalised workspace-relative ones of WorkspacePaths.normalise.
 */
export class WorkspaceFs {
  constructor(readonly root: string) {
    if (!existsSync(PROC_FD)) {
      throw new Error(`the IDE server needs ${PROC_FD} (Linux) to open workspace files safely`);
    }
  }

  /**
   * Opens the parent folder of `rel` (creating missing folders when `create`), runs `fn` with it and
   * the entry's name, then closes it. `rel` = '' is refused (the root has no parent here).
   */
  async withParent<T>(rel: string, create: boolean, fn: (dir: DirAt, name: string) => Promise<T>): Promise<T> {
    const parts = rel.split('/').filter(Boolean);
    const name = parts.pop();
    if (!name) throw new HttpError(403, 'the workspace root itself cannot be changed');
    return this.withDir(parts, create, (dir) => fn(dir, name), rel);
  }

  /** Opens the folder `parts` (from the root), runs `fn` with it, closes it. */
  async withDir<T>(parts: string[], create: boolean, fn: (dir: DirAt) => Promise<T>, shown = parts.join('/')): Promise<T> {
    let handle = await open(this.root, O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
    try {
      for (const part of parts) {
        const next = await openChildDir(handle, part, create, shown);
        await handle.close();
        handle = next;
      }
      return await fn(pathAt(handle));
    } finally {
      await handle.close().catch(() => undefined);
    }
  }

  /**
   * Opens `name` in `dir` for reading, refusing a symlink and anything but a file or a folder; the
   * caller closes the handle. O_NONBLOCK: the open of a FIFO (a hostile folder can hold one under
   * any name) would otherwise wait for a writer for ever, holding one of the few threads every file
   * operation of the server runs on. Gives the handle with the stats of what it opened.
   */
  static async openFile(dir: DirAt, name: string, shown: string): Promise<{ handle: FileHandle; stats: Stats }> {
    let handle: FileHandle;
    try {
      handle = await open(dir.at(name), O_RDONLY | O_NOFOLLOW | O_NONBLOCK);
    } catch (e) {
      throw refusedLink(e, shown);
    }
    const stats = await handle.stat().catch(() => undefined);
    if (!stats || (!stats.isFile() && !stats.isDirectory())) {
      await handle.close().catch(() => undefined);
      throw new HttpError(400, `${shown} is not a regular file (a FIFO, socket or device): not opened`);
    }
    return { handle, stats };
  }

  /** The entry's lstat, or undefined when it does not exist. */
  static async entry(dir: DirAt, name: string): Promise<import('node:fs').Stats | undefined> {
    try {
      return await lstat(dir.at(name));
    } catch (e) {
      if ((e as NodeJS.ErrnoException).code === 'ENOENT') return undefined;
      throw e;
    }
  }

  /** Opens the sub-folder `name` of `dir` (O_NOFOLLOW), or undefined when it is not a real folder. */
  static async openSubdir(dir: DirAt, name: string): Promise<(DirAt & { close(): Promise<void> }) | undefined> {
    try {
      const h = await open(dir.at(name), O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
      return { ...pathAt(h), close: () => h.close() };
    } catch (e) {
      const code = (e as NodeJS.ErrnoException).code;
      if (code === 'ELOOP' || code === 'ENOTDIR' || code === 'ENOENT') return undefined;
      throw e;
    }
  }

  /** The names in an opened folder. */
  static list(dir: DirAt): Promise<import('node:fs').Dirent[]> {
    return readdir(dir.at(''), { withFileTypes: true });
  }

  /**
   * Removes `name` from `dir`, folders recursively, each sub-folder opened O_NOFOLLOW from its
   * parent (fs.rm would walk by path: a folder swapped for a symlink mid-way would be followed).
   */
  static async remove(dir: DirAt, name: string): Promise<void> {
    const st = await lstat(dir.at(name));
    if (!st.isDirectory()) return unlink(dir.at(name));
    const sub = await WorkspaceFs.openSubdir(dir, name);
    if (!sub) return unlink(dir.at(name)); // swapped for a link or a file since the lstat
    try {
      for (const child of await readdir(sub.at(''))) await WorkspaceFs.remove(sub, child);
    } finally {
      await sub.close();
    }
    await rmdir(dir.at(name));
  }
}

async function openChildDir(parent: FileHandle, part: string, create: boolean, shown: string): Promise<FileHandle> {
  const path = `${PROC_FD}/${parent.fd}/${part}`;
  for (let attempt = 0; ; attempt++) {
    try {
      return await open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
    } catch (e) {
      const code = (e as NodeJS.ErrnoException).code;
      if (code === 'ENOENT' && create && attempt < 3) {
        // mkdir never follows a symlink at its last component (EEXIST): a link planted here is refused next turn
        await mkdir(path).catch((m: NodeJS.ErrnoException) => {
          if (m.code !== 'EEXIST') throw m;
        });
        continue;
      }
      if (code === 'ENOENT') throw new HttpError(404, `not found: ${shown}`);
      // O_DIRECTORY|O_NOFOLLOW on a symlink fails ENOTDIR (not ELOOP): tell the two apart
      if (code === 'ENOTDIR') {
        const now = await lstat(path).catch(() => undefined);
        if (now?.isSymbolicLink()) throw new HttpError(403, `symbolic links are not followed: ${shown}`);
        if ((!now || now.isDirectory()) && attempt < 3) continue; // changed meanwhile: look again
      }
      throw refusedLink(e, shown);
    }
  }
}

/** ELOOP (O_NOFOLLOW met a symlink) -> 403; ENOTDIR -> 400; anything else unchanged. */
function refusedLink(e: unknown, shown: string): unknown {
  const code = (e as NodeJS.ErrnoException).code;
  if (code === 'ELOOP') return new HttpError(403, `symbolic links are not followed: ${shown}`);
  if (code === 'ENOTDIR') return new HttpError(400, `not a folder on the path of ${shown}`);
  return e;
}
