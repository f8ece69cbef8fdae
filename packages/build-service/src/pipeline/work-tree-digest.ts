/**
 * A digest of a work dir as a build left it (docs/sandbox.md, "Build products between jobs"):
 * every entry's type, mode, owner and path, and for files and links also size, mtime, ctime, inode
 * and link target. The ctime is set by the kernel on any change and cannot be set back by the job,
 * so a build product rewritten, re-dated or swapped between two jobs changes the digest without
 * its bytes being read. `logs/` and `run/` (what a run leaves, collected or emptied) are not part
 * of it, nor are folder times (creating logs/ changes its parent's).
 * GNU find walks with descriptor-relative calls and never follows links (-P), so any tree the
 * sandbox made can be digested; a walk that fails (a chmod 000 folder) gives no digest at all.
 */
import { spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import type { Readable } from 'node:stream';

/** find's arguments for the work dir seen at `dir` (host path, or /work inside a container). */
export function workTreeFindArgs(dir: string): string[] {
  return [
    dir, '-xdev',
    '(', '-path', `${dir}/logs`, '-o', '-path', `${dir}/run`, ')', '-prune',
    '-o', '-type', 'd', '-printf', 'd %m %U %G %P\\0',
    '-o', '-printf', '%y %m %U %G %s %T@ %C@ %i %P\\0%l\\0',
  ];
}

/** Hashes find's output; null unless find ended with exit 0. */
export async function digestFindOutput(stdout: Readable, exited: Promise<number | null>): Promise<string | null> {
  const hash = createHash('sha256');
  stdout.on('data', (c: Buffer) => hash.update(c));
  const ended = new Promise<void>((resolve) => {
    stdout.on('end', resolve);
    stdout.on('close', resolve);
    stdout.on('error', () => resolve());
  });
  const code = await exited;
  await ended;
  return code === 0 ? hash.digest('hex') : null;
}

/** The digest of a work dir on the host (bwrap, none); call only while no job process runs. */
export function hostWorkTreeDigest(workDir: string): Promise<string | null> {
  const child = spawn('find', workTreeFindArgs(workDir), { stdio: ['ignore', 'pipe', 'ignore'] });
  const exited = new Promise<number | null>((resolve) => {
    child.on('error', () => resolve(null));
    child.on('close', (code) => resolve(code));
  });
  return digestFindOutput(child.stdout, exited);
}
