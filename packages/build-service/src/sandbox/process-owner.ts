/**
 * A process as the owner of what it leaves on the host (job cgroups, per-service work folders), in
 * a form written into names: `<pid>-<start time>-<pid namespace>` (ownerTag). Another process
 * judges a tag (judgeOwnerTag): `dead` when the owner was in its own pid namespace and that pid is
 * gone or started at another time (a reused pid), `alive` when it runs, `unknown` when it was in
 * another pid namespace (its pid means nothing here): only what a `dead` owner left is removed.
 */
import { readlinkSync } from 'node:fs';
import { processStartTime } from './docker-owner.js';

export interface ProcessOwner {
  pid: number;
  startTime: string;
  /** The inode of the owner's pid namespace (`pid:[N]`), '0' when unknown. */
  pidns: string;
}

export const OWNER_TAG = String.raw`(\d{1,10})-(\d{1,20})-(\d{1,20})`;

let own: ProcessOwner | undefined;

/** This process (read once). */
export function currentProcessOwner(): ProcessOwner {
  own ??= { pid: process.pid, startTime: processStartTime(process.pid) ?? '0', pidns: ownPidNamespace() };
  return own;
}

function ownPidNamespace(): string {
  try {
    return /^pid:\[(\d+)\]$/.exec(readlinkSync('/proc/self/ns/pid'))?.[1] ?? '0';
  } catch {
    return '0'; // no /proc: '0' never judges an owner
  }
}

export function ownerTag(owner: ProcessOwner = currentProcessOwner()): string {
  return `${owner.pid}-${owner.startTime}-${owner.pidns}`;
}

/** Is the process `pid` running, started at `startTime`? */
export function isProcessAlive(pid: number, startTime: string): boolean {
  return processStartTime(pid) === startTime;
}

/** The owner named by a tag's three parts, judged from `self`'s pid namespace. */
export function judgeOwnerTag(
  pid: string,
  startTime: string,
  pidns: string,
  self: ProcessOwner,
  alive: (pid: number, startTime: string) => boolean,
): 'dead' | 'alive' | 'unknown' {
  if (self.pidns === '0' || pidns !== self.pidns) return 'unknown';
  return alive(Number(pid), startTime) ? 'alive' : 'dead';
}
