/**
 * While a run pinned to CPUs (`cpus`, contract-launch --cpus) goes on, the service's own threads
 * keep off those CPUs: its work for that run (the live trace channel: reading the logs, ordering,
 * sending them to the monitor) then never takes a CPU from the modules (docs/watching-a-run.md
 * "Keep the run's CPUs to the run"). Every thread of the process is moved at once (`taskset -a -p`,
 * util-linux); threads made later inherit the mask of the thread that makes them. When no pinned
 * run is left, the mask the process had is given back. Runs pinned to every CPU the service may
 * use leave it where it is (it would have nowhere to go), and say so.
 */
import { execFile } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { isCpuList } from '@contract-studio/conventions';

/** `0-2,5` -> [0, 1, 2, 5]; null for anything else. */
export function parseCpuList(text: string): number[] | null {
  if (!isCpuList(text)) return null;
  const out = new Set<number>();
  for (const part of text.split(',')) {
    const [a, b] = part.split('-').map(Number) as [number, number | undefined];
    const end = b ?? a;
    if (end < a || end - a > 4096) return null;
    for (let c = a; c <= end; c++) out.add(c);
  }
  return [...out].sort((x, y) => x - y);
}

/** The CPUs this process may run on now (`Cpus_allowed_list` of /proc/self/status); null when unknown. */
export function ownCpus(): number[] | null {
  try {
    const m = /^Cpus_allowed_list:\s*(\S+)$/m.exec(readFileSync('/proc/self/status', 'utf8'));
    return m ? parseCpuList(m[1]!) : null;
  } catch {
    return null;
  }
}

/** Moves every thread of this process to `cpus`; resolves with an error text, or null when done. */
function moveProcess(cpus: number[]): Promise<string | null> {
  return new Promise((resolve) => {
    execFile('taskset', ['-a', '-p', '-c', cpus.join(','), String(process.pid)], { timeout: 5000 }, (err, _out, stderr) => {
      resolve(err ? (String(stderr).trim().split('\n')[0] || err.message) : null);
    });
  });
}

export class ServiceAffinity {
  private readonly runs = new Map<symbol, number[]>();
  /** The process's mask before the first pinned run. */
  private original: number[] | null = null;
  /** The mask set last (null: the original). */
  private current: number[] | null = null;
  private queue: Promise<unknown> = Promise.resolve();

  /**
   * A run pinned to `cpuList` starts: the service moves off those CPUs. Resolves with what to tell
   * the user (one line) and the release to call when the run has ended.
   */
  async keepOff(cpuList: string): Promise<{ said: string; release: () => Promise<void> }> {
    const cpus = parseCpuList(cpuList);
    const key = Symbol(cpuList);
    if (cpus) this.runs.set(key, cpus);
    const said = await this.apply();
    return { said, release: async () => void (this.runs.delete(key), await this.apply()) };
  }

  /** Sets the mask the runs now ask for (one change at a time); what it did, as one line. */
  private apply(): Promise<string> {
    const next = this.queue.then(async () => {
      if (this.runs.size === 0) {
        if (this.current && this.original) {
          const err = await moveProcess(this.original);
          this.current = null;
          return err ? `the build service could not take back its CPUs ${this.original.join(',')}: ${err}` : `the build service is back on its CPUs ${this.original.join(',')}`;
        }
        return '';
      }
      this.original ??= ownCpus();
      if (!this.original) return 'the build service does not know its CPUs (/proc/self/status): it stays where it is';
      const taken = new Set([...this.runs.values()].flat());
      const left = this.original.filter((c) => !taken.has(c));
      if (left.length === 0) return `the build service stays on CPUs ${this.original.join(',')}: the runs are pinned to all of them`;
      if (this.current && left.join(',') === this.current.join(',')) return `the build service keeps off CPUs ${[...taken].sort((a, b) => a - b).join(',')}: it runs on ${left.join(',')}`;
      const err = await moveProcess(left);
      if (err) return `the build service could not keep off the run's CPUs (taskset: ${err}): it stays where it is`;
      this.current = left;
      return `the build service keeps off CPUs ${[...taken].sort((a, b) => a - b).join(',')} while the run is pinned there: it runs on ${left.join(',')}`;
    });
    this.queue = next.catch(() => {});
    return next;
  }
}

/** One per process: the service's threads are the process's. */
export const SERVICE_AFFINITY = new ServiceAffinity();
