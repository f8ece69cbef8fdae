/**
 * Runs a sandbox command as a host process tree (used by the bwrap and none sandboxes): joins the
 * job's cgroup before exec when there is one, watches the cgroup counters to name a memory or
 * process limit hit, and kills the whole tree on demand.
 */
import { spawn } from 'node:child_process';
import { readdirSync, readFileSync } from 'node:fs';
import type { LimitHit, Limits } from '../limits.js';
import { memoryBytes } from '../limits.js';
import type { LimitCgroup } from './cgroup.js';
import { isWorkDiskFull, workDiskState } from './work-disk.js';
import type { Mechanisms, SandboxExit, SandboxProcess, StopOnLimit } from './types.js';
import { stopThenKill } from './limit-stop.js';
import { terminateNamedOnHost } from './queue-term.js';
import type { StopReason } from '@contract-studio/conventions';
import { withForkingModule } from './forking-module.js';

export interface HostProcessOptions {
  argv: string[];
  cwd: string;
  env: Record<string, string>;
  limits: Limits;
  mechanisms: Mechanisms;
  cgroup: LimitCgroup | null;
  /** More cgroup.procs files to join before exec (the real-time budget's cpu cgroup, realtime.ts). */
  joinProcsFiles?: string[];
  /** rlimit mode: guess limit hits from the messages of refused forks/allocations. */
  guessLimitsFromOutput: boolean;
  /** Called once every process is gone (removes the cgroup). */
  cleanup?: () => Promise<void>;
  /** The work tmpfs to watch (work-disk.ts): filling it is the workDiskMiB limit hit. */
  workDisk?: { dir: string; bytes: number };
  /** A limit hit asks these processes to stop first (SandboxCommand.stopOnLimit). */
  stopOnLimit?: StopOnLimit;
}

const WATCH_INTERVAL_MS = 100;
/** statfs of the work tmpfs: a job refused a write (ENOSPC) is stopped within this time. */
const DISK_WATCH_INTERVAL_MS = 250;

/** Shell prologue: write our pid into each cgroup.procs given before "--", then exec the rest. */
const JOIN_CGROUP = 'for f; do [ "$f" = -- ] && break; echo $$ > "$f" || exit 125; shift; done; shift; exec "$@"';

export function startHostProcess(opts: HostProcessOptions): SandboxProcess {
  const join = [...(opts.cgroup?.procsFiles ?? []), ...(opts.joinProcsFiles ?? [])];
  const argv = join.length ? ['/bin/sh', '-c', JOIN_CGROUP, 'contract-join', ...join, '--', ...opts.argv] : opts.argv;
  const child = spawn(argv[0]!, argv.slice(1), {
    cwd: opts.cwd,
    env: opts.env,
    stdio: ['ignore', 'pipe', 'pipe'],
    detached: true, // own process group: kill(-pid) reaches what the cgroup/namespace may not
  });
  let limitHit: LimitHit | null = null;
  let killing: Promise<void> | null = null;
  let exited = false;
  let markExited!: () => void;
  const exitedPromise = new Promise<void>((r) => (markExited = r));

  /**
   * Kills the inner processes first and the direct child last, so that every process is reaped by
   * its own parent (killing the outer bwrap first would leave the namespace's init to PID 1).
   */
  const killTree = async (): Promise<void> => {
    const pid = child.pid;
    const inner = new Set<number>(pid === undefined ? [] : descendantsOf(pid));
    if (opts.cgroup) for (const p of await opts.cgroup.pids()) if (p !== pid) inner.add(p);
    for (const p of inner) {
      try {
        process.kill(p, 'SIGKILL');
      } catch {
        /* already gone */
      }
    }
    if (pid !== undefined && !exited) {
      await Promise.race([exitedPromise, new Promise((r) => setTimeout(r, 700))]);
      try {
        process.kill(-pid, 'SIGKILL');
      } catch {
        /* group gone */
      }
    }
    if (opts.cgroup) await opts.cgroup.killAll();
  };

  const terminateNamed = async (name: string, reason?: StopReason): Promise<boolean> => {
    const pid = child.pid;
    if (pid === undefined || exited || killing) return false;
    const pids = new Set<number>(descendantsOf(pid));
    if (opts.cgroup) for (const p of await opts.cgroup.pids()) if (p !== pid) pids.add(p);
    return (await terminateNamedOnHost([...pids], name, '/proc', reason)) === true;
  };

  const kill = (): Promise<void> => {
    killing ??= killTree();
    return killing.then(() => done.then(() => undefined));
  };

  const hit = (h: LimitHit): void => {
    if (limitHit) return;
    limitHit = h;
    void (opts.stopOnLimit ? stopThenKill(opts.stopOnLimit, h, { terminateNamed, exited: exitedPromise, kill }) : kill());
  };

  // an OOM kill the job's cgroup counted, with what of the memory the job's tmpfs files held (no kill frees them)
  const memoryHit = async (cg: LimitCgroup): Promise<LimitHit> => {
    const files = (await cg.memoryFiles?.().catch(() => null)) ?? null;
    return { name: 'memory', value: memoryBytes(opts.limits), unit: 'bytes', mechanism: cg.mechanism, ...(files !== null ? { memoryFilesBytes: files } : {}) };
  };

  const watcher = opts.cgroup
    ? setInterval(() => {
        void (async () => {
          const cg = opts.cgroup!;
          if ((await cg.oomKills()) > 0) {
            hit(await memoryHit(cg));
          } else if ((await cg.pidsLimitHits()) > 0) {
            // the module whose code forks, named while its processes are there
            const processes: LimitHit = { name: 'processes', value: opts.limits.processes, unit: 'count', mechanism: cg.mechanism };
            hit(withForkingModule(processes, await cg.pids().catch(() => []), HOST_PROCESSES));
          }
        })().catch(() => {});
      }, WATCH_INTERVAL_MS)
    : null;

  const diskHit = async (): Promise<LimitHit | null> => {
    if (!opts.workDisk) return null;
    const state = await workDiskState(opts.workDisk.dir);
    return state && isWorkDiskFull(state) ? { name: 'workDiskMiB', value: opts.workDisk.bytes, unit: 'bytes', mechanism: 'tmpfs-size' } : null;
  };
  const diskWatcher = opts.workDisk
    ? setInterval(() => {
        void diskHit().then((h) => h && hit(h), () => {});
      }, DISK_WATCH_INTERVAL_MS)
    : null;

  const done = new Promise<SandboxExit>((resolveDone) => {
    let exit: { code: number | null; signal: NodeJS.Signals | null } | null = null;
    let closed = false;
    const finish = async (): Promise<void> => {
      if (watcher) clearInterval(watcher);
      if (diskWatcher) clearInterval(diskWatcher);
      // final look at the counters: the kernel may have killed the process just before it exited
      if (opts.cgroup && !limitHit) {
        if ((await opts.cgroup.oomKills()) > 0) {
          limitHit = await memoryHit(opts.cgroup);
        } else if ((await opts.cgroup.pidsLimitHits()) > 0) {
          limitHit = { name: 'processes', value: opts.limits.processes, unit: 'count', mechanism: opts.cgroup.mechanism };
        }
      }
      // a job that was refused a write and gave up is reported too
      if (!limitHit) limitHit = await diskHit().catch(() => null);
      await killTree(); // nothing of the job outlives it
      await opts.cleanup?.().catch(() => {});
      resolveDone({ exitCode: exit?.code ?? null, signal: exit?.signal ?? null, limitHit });
    };
    child.on('error', (err) => {
      exit = { code: 127, signal: null };
      child.stderr?.emit('data', Buffer.from(`cannot start ${argv[0]}: ${err.message}\n`));
      if (!closed) {
        closed = true;
        void finish();
      }
    });
    child.on('exit', (code, signal) => {
      exited = true;
      markExited();
      exit = { code, signal };
      // a daemonised grandchild may keep the pipes open: stop it, then give the pipes a moment
      void killTree();
      setTimeout(() => {
        if (!closed) {
          child.stdout?.destroy();
          child.stderr?.destroy();
          closed = true;
          void finish();
        }
      }, 1000).unref();
    });
    child.on('close', () => {
      if (closed) return;
      closed = true;
      void finish();
    });
  });

  /**
   * "fork: ... EAGAIN" / "fork(): ... try again" in linear time: lines are the sandbox's, and
   * /fork(?:\(\))?: .*(?:EAGAIN|again)/ backtracks over the rest of the line at every "fork: "
   * of it (seconds on a 64 KiB line of them, with the service's event loop stalled meanwhile).
   */
  const forkAgain = (line: string): boolean => {
    const m = /fork(?:\(\))?: /i.exec(line);
    return m !== null && /EAGAIN|again/i.test(line.slice(m.index + m[0].length));
  };

  const noteLine = (line: string): void => {
    if (!opts.guessLimitsFromOutput || limitHit || exited) return;
    if (/Resource temporarily unavailable|cannot fork|fork failed/i.test(line) || forkAgain(line)) {
      hit({ name: 'processes', value: opts.limits.processes, unit: 'count', mechanism: 'rlimit-nproc' });
    } else if (/Cannot allocate memory|out of memory|std::bad_alloc|virtual memory exhausted/i.test(line)) {
      hit({ name: 'memory', value: memoryBytes(opts.limits), unit: 'bytes', mechanism: 'rlimit-as' });
    }
  };

  return {
    stdout: child.stdout!,
    stderr: child.stderr!,
    mechanisms: opts.mechanisms,
    done,
    kill,
    terminateNamed,
    noteLine,
  };
}

/** A process's name (/proc/<pid>/comm), '' when it is gone. */
export function processName(pid: number): string {
  try {
    return readFileSync(`/proc/${pid}/comm`, 'utf8').replace(/\n$/, '');
  } catch {
    return '';
  }
}

/** A process's parent pid (/proc/<pid>/stat), 0 when it is gone. */
export function processParent(pid: number): number {
  try {
    const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
    return Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]) || 0;
  } catch {
    return 0;
  }
}

/** The kernel's view of the job's processes, as forkingModule reads it. */
export const HOST_PROCESSES = { nameOf: processName, parentOf: processParent } as const;

/** pid -> parent pid of every process of the machine (from /proc/<pid>/stat). */
export function processParents(): Map<number, number> {
  const parent = new Map<number, number>();
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    try {
      const stat = readFileSync(`/proc/${name}/stat`, 'utf8');
      const ppid = Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]);
      parent.set(Number(name), ppid);
    } catch {
      /* exited meanwhile */
    }
  }
  return parent;
}

/** Every process below `root` (from /proc/<pid>/stat parent links), deepest last. */
export function descendantsOf(root: number): number[] {
  const parent = processParents();
  const out: number[] = [];
  const frontier = [root];
  while (frontier.length) {
    const p = frontier.shift()!;
    for (const [pid, pp] of parent) if (pp === p) {
      out.push(pid);
      frontier.push(pid);
    }
  }
  return out;
}
