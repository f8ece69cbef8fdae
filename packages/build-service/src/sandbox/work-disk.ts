/**
 * The disk bound of a job's /work in the host sandboxes (bwrap, none): the workspace's work dir is
 * a tmpfs of `workDiskMiB` (and a bounded inode count), mounted by the service when it runs as root
 * (docs/sandbox.md, "Limits"). The kernel refuses writes beyond it (ENOSPC), whatever the job does;
 * the service reads statfs to name the hit and to kill a job that keeps trying. Its pages are
 * charged to the memory cgroup of the process that wrote them, so they also count against
 * `memoryMiB` while the job runs. Removing a workspace unmounts it first: whatever tree the job
 * left there is then dropped by the kernel, not walked by the service.
 */
import { execFile } from 'node:child_process';
import { promises as fsp } from 'node:fs';
import { dirname } from 'node:path';
import { promisify } from 'node:util';
import type { Owner } from '../util/safe-fs.js';

const run = promisify(execFile);

const TMPFS_MAGIC = 0x01021994;

/** Inodes of a work tmpfs: enough for deep trees and big builds, bounded so kernel memory is too. */
export function workDiskInodes(bytes: number): number {
  return Math.max(4096, Math.floor(bytes / 4096));
}

export interface WorkDiskState {
  sizeBytes: number;
  freeBytes: number;
  freeInodes: number;
}

/** The tmpfs mounted at `dir` by mountWorkDisk, or null when `dir` is a plain folder. */
export async function workDiskState(dir: string): Promise<WorkDiskState | null> {
  try {
    const [here, parent] = await Promise.all([fsp.lstat(dir), fsp.lstat(dirname(dir))]);
    if (here.dev === parent.dev) return null;
    const s = await fsp.statfs(dir);
    if (s.type !== TMPFS_MAGIC) return null;
    return { sizeBytes: s.blocks * s.bsize, freeBytes: s.bavail * s.bsize, freeInodes: s.ffree };
  } catch {
    return null;
  }
}

/**
 * True when the job filled its work dir: (nearly) no byte or no inode left. A job that stops just
 * short of the bound is not reported (it was not refused anything).
 */
export function isWorkDiskFull(s: WorkDiskState): boolean {
  return s.freeInodes === 0 || s.freeBytes <= Math.max(64 * 1024, s.sizeBytes / 256);
}

/** Whether this service may mount (root). */
export function canMountWorkDisk(): boolean {
  return process.getuid?.() === 0;
}

function options(bytes: number, owner: Owner): string {
  return `size=${bytes},nr_inodes=${workDiskInodes(bytes)},mode=0755,uid=${owner.uid},gid=${owner.gid},nosuid,nodev`;
}

/** Mounts the work tmpfs on the (empty, service-made) folder `dir`. */
export async function mountWorkDisk(dir: string, bytes: number, owner: Owner): Promise<void> {
  await run('mount', ['-t', 'tmpfs', '-o', options(bytes, owner), 'contract-work', dir]);
}

/** Changes the size of a mounted work tmpfs (a job may lower workDiskMiB); false when refused. */
export async function resizeWorkDisk(dir: string, bytes: number, owner: Owner): Promise<boolean> {
  try {
    await run('mount', ['-o', `remount,${options(bytes, owner)}`, dir]);
    return true;
  } catch {
    return false;
  }
}

/** Unmounts the work tmpfs at `dir` if there is one (lazily if something still holds it). */
export async function unmountWorkDisk(dir: string): Promise<void> {
  if (!(await workDiskState(dir))) return;
  try {
    await run('umount', [dir]);
  } catch {
    await run('umount', ['-l', dir]);
  }
}
