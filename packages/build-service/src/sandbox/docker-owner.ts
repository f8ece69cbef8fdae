/**
 * Who owns a Docker container or volume of the build service, and whether that owner still lives.
 *
 * Every container and volume the service creates carries:
 *   contract-studio.owner       = <hostname>:<pid>:<start time>  (start time: /proc/<pid>/stat field 22,
 *                                 clock ticks since boot, so a recycled pid is not taken for the owner)
 *   contract-studio.owner-boot  = /proc/sys/kernel/random/boot_id (a reboot kills every owner)
 *   contract-studio.owner-pidns = the owner's pid namespace (readlink /proc/self/ns/pid): pids of
 *                                 another namespace cannot be checked from here
 *   contract-studio.owner-instance = a random id per service instance (one process may hold
 *                                 several services, e.g. tests: each closes only its own)
 *   contract-studio.job         = the job id (for the log lines)
 * Whether the owner's process lives is process-owner.ts's answer, as for the cgroups and work folders.
 */
import { randomBytes } from 'node:crypto';
import { readFileSync, readlinkSync } from 'node:fs';
import { hostname } from 'node:os';
import { ownerProcessState, processStartTime } from './process-owner.js';

export const LABEL_KIND = 'contract-studio';
export const LABEL_OWNER = 'contract-studio.owner';
export const LABEL_OWNER_BOOT = 'contract-studio.owner-boot';
export const LABEL_OWNER_PIDNS = 'contract-studio.owner-pidns';
export const LABEL_OWNER_INSTANCE = 'contract-studio.owner-instance';
export const LABEL_JOB = 'contract-studio.job';

export interface ServiceOwner {
  host: string;
  pid: number;
  /** /proc/<pid>/stat field 22 (clock ticks after boot), as text. */
  startTime: string;
  boot: string;
  pidns: string;
  /** Random per service instance (not part of liveness). */
  instance: string;
}

function readOr(read: () => string, fallback: string): string {
  try {
    return read().trim();
  } catch {
    return fallback;
  }
}

/** This process as an owner (a new instance id per call: one per service). */
export function currentOwner(): ServiceOwner {
  return {
    host: hostname(),
    pid: process.pid,
    startTime: processStartTime(process.pid) ?? '0',
    boot: readOr(() => readFileSync('/proc/sys/kernel/random/boot_id', 'utf8'), 'unknown'),
    pidns: readOr(() => readlinkSync('/proc/self/ns/pid'), 'unknown'),
    instance: randomBytes(6).toString('hex'),
  };
}

export function ownerLabelValue(owner: ServiceOwner): string {
  return `${owner.host}:${owner.pid}:${owner.startTime}`;
}

/** The labels of a container (kind 'job') or volume (kind 'workspace') made for `jobId`. */
export function ownerLabels(owner: ServiceOwner, kind: 'job' | 'workspace', jobId: string): Record<string, string> {
  return {
    [LABEL_KIND]: kind,
    [LABEL_OWNER]: ownerLabelValue(owner),
    [LABEL_OWNER_BOOT]: owner.boot,
    [LABEL_OWNER_PIDNS]: owner.pidns,
    [LABEL_OWNER_INSTANCE]: owner.instance,
    [LABEL_JOB]: jobId,
  };
}

export type OwnerVerdict =
  /** the owning service runs: leave it alone */
  | { state: 'alive' }
  /** the owning service is gone: `why` ends the log line, e.g. "its service pid 4242 is gone" */
  | { state: 'dead'; why: string }
  /** owned by a service this process cannot check (another host or pid namespace, unreadable label) */
  | { state: 'elsewhere'; why: string }
  /** made before owner labels existed */
  | { state: 'unowned' };

/**
 * Judges the owner written in `labels` from the point of view of `self` (same host, boot and pid
 * namespace are needed to say "dead"); `startTimeOf` reads a pid's start time (null: no process).
 */
export function judgeOwner(
  labels: Record<string, string> | null | undefined,
  self: ServiceOwner,
  startTimeOf: (pid: number) => string | null = processStartTime,
): OwnerVerdict {
  const value = labels?.[LABEL_OWNER];
  if (value === undefined) return { state: 'unowned' };
  const m = /^(.+):(\d+):(\d+)$/.exec(value);
  if (!m) return { state: 'elsewhere', why: `its owner label "${value}" is not host:pid:start` };
  const [, host, pidText, startTime] = m as unknown as [string, string, string, string];
  const pid = Number(pidText);
  if (host !== self.host) return { state: 'elsewhere', why: `owned by a service on host ${host}` };
  const boot = labels?.[LABEL_OWNER_BOOT];
  if (boot !== undefined && boot !== self.boot) return { state: 'dead', why: `its service pid ${pid} ran before this machine rebooted` };
  const pidns = labels?.[LABEL_OWNER_PIDNS];
  if (pidns !== undefined && pidns !== self.pidns) return { state: 'elsewhere', why: `its service pid ${pid} is in another pid namespace (${pidns})` };
  const state = ownerProcessState(pid, startTime, startTimeOf);
  if (state === 'gone') return { state: 'dead', why: `its service pid ${pid} is gone` };
  if (state === 'reused') return { state: 'dead', why: `its service pid ${pid} is gone (the pid now belongs to a newer process)` };
  return { state: 'alive' };
}
