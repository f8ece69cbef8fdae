import { realpathSync, lstatSync } from 'node:fs';
import { isAbsolute, join, relative, sep, dirname, basename } from 'node:path';
import { HttpError } from './http-error.js';
import { WorkspaceFs } from './workspace-fs.js';

/**
 * Resolves user-supplied workspace-relative paths to absolute paths, refusing anything that
 * would leave the workspace: absolute paths, `..` segments, NUL bytes, and symlinks (anywhere on
 * the path) whose target lies outside the workspace. Checks use realpath on the longest existing
 * prefix, so a path to a file that does not exist yet is accepted only if its existing parent
 * folders are inside the workspace. These checks are check-then-use (a folder swapped for a
 * symlink afterwards is not seen): they give clear errors, and the file API then opens every path
 * through `fs` (workspace-fs.ts), which does not follow symlinks at all.
 */
export class WorkspacePaths {
  readonly root: string;
  /** The no-follow, fd-anchored file operations every file API request goes through. */
  readonly fs: WorkspaceFs;

  constructor(root: string) {
    try {
      this.root = realpathSync(root);
    } catch {
      throw new Error(`workspace folder not found: ${root}`);
    }
    if (!lstatSync(this.root).isDirectory()) throw new Error(`workspace is not a folder: ${root}`);
    this.fs = new WorkspaceFs(this.root);
  }

  /** Normalised relative path ('' = the workspace root), or an HttpError(400/403). */
  normalise(userPath: unknown): string {
    if (typeof userPath !== 'string') throw new HttpError(400, 'missing path');
    if (userPath.includes('\0')) throw new HttpError(400, 'path contains a NUL byte');
    if (isAbsolute(userPath) || /^[a-zA-Z]:[\\/]/.test(userPath) || userPath.startsWith('\\')) {
      throw new HttpError(403, `absolute paths are refused: ${userPath}`);
    }
    const parts = userPath.split(/[\\/]+/).filter((p) => p !== '' && p !== '.');
    if (parts.includes('..')) throw new HttpError(403, `paths with '..' are refused: ${userPath}`);
    return parts.join('/');
  }

  /** Absolute path inside the workspace for a user path; the target need not exist. */
  resolve(userPath: unknown): string {
    const rel = this.normalise(userPath);
    const abs = rel === '' ? this.root : join(this.root, ...rel.split('/'));
    this.assertInside(abs, userPath as string);
    return abs;
  }

  /** Same as resolve, but refuses the workspace root itself (for write/rename/delete). */
  resolveEntry(userPath: unknown): string {
    const abs = this.resolve(userPath);
    if (abs === this.root) throw new HttpError(403, 'the workspace root itself cannot be changed');
    return abs;
  }

  /**
   * The normalised relative path of an entry (not the root) after the checks of resolveEntry, for
   * WorkspaceFs: those checks only give clear errors; the access itself never follows a symlink.
   */
  entry(userPath: unknown): string {
    return this.toRelative(this.resolveEntry(userPath));
  }

  /** Workspace-relative path (with '/') of an absolute path known to be inside. */
  toRelative(abs: string): string {
    return relative(this.root, abs).split(sep).join('/');
  }

  private assertInside(abs: string, shown: string): void {
    // Walk up to the longest existing prefix; its realpath decides (symlinks resolved).
    let probe = abs;
    const missing: string[] = [];
    for (;;) {
      let real: string | undefined;
      try {
        real = realpathSync(probe);
      } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        if (code !== 'ENOENT' && code !== 'ENOTDIR') throw new HttpError(403, `cannot resolve ${shown}: ${code}`);
        // A dangling symlink also lands here: refuse it if it is a link.
        try {
          if (lstatSync(probe).isSymbolicLink()) throw new HttpError(403, `dangling symlink refused: ${shown}`);
        } catch (inner) {
          if (inner instanceof HttpError) throw inner;
        }
      }
      if (real !== undefined) {
        if (!this.contains(real)) throw new HttpError(403, `path leaves the workspace: ${shown}`);
        return;
      }
      missing.push(basename(probe));
      const parent = dirname(probe);
      if (parent === probe) throw new HttpError(403, `path leaves the workspace: ${shown}`);
      probe = parent;
    }
  }

  private contains(real: string): boolean {
    return real === this.root || real.startsWith(this.root + sep);
  }
}
