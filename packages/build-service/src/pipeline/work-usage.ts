/**
 * Which files filled a job's work dir, for the message of a disk limit hit (docs/sandbox.md,
 * "The disk limit"): a run that fills /work is told which module's files took the space
 * (`logs/MOT_….csv 180 MiB`), not only that the disk is full.
 * GNU find walks with descriptor-relative calls and never follows links (-P, -xdev), so any tree
 * the sandbox made can be measured; its output is parsed as a stream, bounded in entries and
 * time, and only the biggest few are kept.
 */
import { spawn } from 'node:child_process';
import type { Readable } from 'node:stream';
import { visibleText } from '@contract-studio/conventions';
import { formatBytes } from '../limits.js';

export interface WorkFileSize {
  /** Path relative to the work dir. */
  path: string;
  bytes: number;
}

export interface WorkUsage {
  /** The biggest regular files, biggest first. */
  biggest: WorkFileSize[];
  /** Bytes of the regular files seen. */
  totalBytes: number;
  files: number;
  /** The walk stopped at the entry or time bound (the figures are a lower bound). */
  partial: boolean;
}

/** Entries and time one measure may take: the tree is the sandbox's and may be huge. */
export const WORK_USAGE_BOUNDS: Readonly<{ entries: number; ms: number; keep: number }> = { entries: 200_000, ms: 5_000, keep: 5 };

/** find's arguments: `<size> <path>\0` for every regular file under `dir`. */
export function workUsageFindArgs(dir: string): string[] {
  return [dir, '-xdev', '-type', 'f', '-printf', '%s %P\\0'];
}

/** Reads find's NUL-separated `<size> <path>` records; never throws on malformed ones. */
export function readWorkUsage(stdout: Readable, stop: () => void, bounds = WORK_USAGE_BOUNDS): Promise<WorkUsage> {
  return new Promise((resolve) => {
    const usage: WorkUsage = { biggest: [], totalBytes: 0, files: 0, partial: false };
    let rest = '';
    let done = false;
    const finish = (): void => {
      if (done) return;
      done = true;
      clearTimeout(timer);
      resolve(usage);
    };
    const timer = setTimeout(() => {
      usage.partial = true;
      stop();
      finish();
    }, bounds.ms);
    const record = (text: string): void => {
      const space = text.indexOf(' ');
      const size = text.slice(0, space);
      const bytes = Number(size);
      if (space <= 0 || !/^\d{1,15}$/.test(size)) return;
      usage.files++;
      usage.totalBytes += bytes;
      const path = text.slice(space + 1, space + 1 + 512);
      if (usage.biggest.length < bounds.keep || bytes > usage.biggest[usage.biggest.length - 1]!.bytes) {
        usage.biggest.push({ path, bytes });
        usage.biggest.sort((a, b) => b.bytes - a.bytes || (a.path < b.path ? -1 : 1));
        usage.biggest.length = Math.min(usage.biggest.length, bounds.keep);
      }
    };
    stdout.on('data', (chunk: Buffer) => {
      if (done) return;
      const parts = (rest + chunk.toString('utf8')).split('\0');
      rest = parts.pop()!.slice(0, 4096); // a record longer than that is not a find record
      for (const p of parts) {
        record(p);
        if (usage.files >= bounds.entries) {
          usage.partial = true;
          stop();
          finish();
          return;
        }
      }
    });
    stdout.on('end', finish);
    stdout.on('close', finish);
    stdout.on('error', finish);
  });
}

/** The usage of a work dir on the host (bwrap, none); null when find cannot run. */
export function hostWorkUsage(workDir: string): Promise<WorkUsage | null> {
  const child = spawn('find', workUsageFindArgs(workDir), { stdio: ['ignore', 'pipe', 'ignore'] });
  const failed = new Promise<null>((resolve) => child.on('error', () => resolve(null)));
  return Promise.race([readWorkUsage(child.stdout, () => child.kill('SIGKILL')), failed]);
}

/**
 * "logs/MOT_x.csv 180 MiB, logs/ODO_x.csv 20 MiB (of 201 MiB in 14 files)". The paths are the
 * sandbox's to choose: written visibly (visibleText), so that a name with line breaks cannot add a
 * line to the message that reads as the service's (`ok: run finished`) nor act on a terminal.
 */
export function describeWorkUsage(u: WorkUsage): string {
  const top = u.biggest.map((f) => `${visibleText(f.path, { escapeTab: true })} ${formatBytes(f.bytes)}`).join(', ');
  return `${top || 'no regular file'} (of ${u.partial ? 'at least ' : ''}${formatBytes(u.totalBytes)} in ${u.files} file(s))`;
}
