/**
 * A process as the owner of what it leaves on the host (job cgroups, per-service work folders), in
 * a form written into names: `<pid>-<start time>-<pid namespace>` (ownerTag). Another process
 * judges a tag (judgeOwnerTag): `dead` when the owner was in its own pid namespace and that pid is
 * gone or started at another time (a reused pid), `alive` when it runs, `unknown` when it was in
 * another pid namespace (its pid means nothing here): only what a `dead` owner left is removed.
 */
import { readFileSync, readlinkSync } from 'node:fs';

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

/**
 * Field 22 (starttime) of /proc/<pid>/stat, or null when there is no such process or it has
 * ended and waits to be reaped (state Z/X: a zombie service owns nothing any more).
 */
export function processStartTime(pid: number): string | null {
  let stat: string;
  try {
    stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
  } catch {
    return null;
  }
  // field 2 (comm) is in parentheses and may hold spaces and ')': fields 3.. follow the last ')'
  const rest = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
  if (rest[0] === 'Z' || rest[0] === 'X') return null;
  const field22 = rest[22 - 3];
  return field22 && /^\d+$/.test(field22) ? field22 : null;
}

/**
 * The process that was `pid`, started at `startTime`: `alive`, `gone` (no such process, or a
 * zombie), or `reused` (the pid belongs to a newer process). The one liveness check of every owner:
 * a job cgroup's and a work folder's tag here, a Docker container's or volume's labels in
 * docker-owner.ts. `startTimeOf`: how a pid's start time is read (tests give their own).
 */
export function ownerProcessState(
  pid: number,
  startTime: string,
  startTimeOf: (pid: number) => string | null = processStartTime,
): 'alive' | 'gone' | 'reused' {
  const now = startTimeOf(pid);
  if (now === null) return 'gone';
  return now === startTime ? 'alive' : 'reused';
}

/** Is the process `pid` running, started at `startTime`? */
export function isProcessAlive(pid: number, startTime: string): boolean {
  return ownerProcessState(pid, startTime) === 'alive';
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
