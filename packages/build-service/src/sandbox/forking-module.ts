/**
 * Which module's code forked past the process limit. The launcher (contract-launch) starts each
 * module as its own child, named after it (modules run as `modules/<M>_mod/<M>`: the kernel's
 * `comm` is M). So at the hit, each of the job's processes is counted for the module it descends
 * from: the ancestor whose parent is the launcher. That holds when the code forks and then execs
 * another program (`sh`, `sleep`: a name that is no module's). A process whose line of parents is
 * broken (its parent exited: the kernel gave it to the sandbox's first process) counts for the
 * name it bears, which a fork keeps until it execs. The sandbox's own programs are not modules;
 * a module with fewer than 3 processes (itself and one child) is named for no one.
 */
import { LAUNCHER_PROCESS_NAME } from '@contract-studio/conventions';
import type { LimitHit } from '../limits.js';

/** Programs of the sandbox and the build, never a module's code. */
const NOT_MODULES: ReadonlySet<string> = new Set(['bwrap', 'make', 'sh', 'bash', 'dash', LAUNCHER_PROCESS_NAME, 'setpriv', 'prlimit', 'docker-init', 'tini', 'cc', 'gcc', 'cc1', 'as', 'ld', 'collect2', 'sleep', 'true']);
/** A module's name as the kernel keeps it (15 characters at most). */
const MODULE_NAME = /^[A-Za-z_][A-Za-z0-9_]{0,14}$/;
/** Processes at the hit that read no more names (a limit of thousands of processes). */
const MAX_READ = 4096;
/** How the job's processes are read (/proc/<pid>/comm and stat): '' and 0 for a process gone. */
export interface ProcessTable {
  nameOf(pid: number): string;
  parentOf(pid: number): number;
}

export interface ForkingModule {
  module: string;
  /** The job's processes at the hit that descend from that module (itself included). */
  processes: number;
}

const isModuleName = (name: string): boolean => MODULE_NAME.test(name) && !NOT_MODULES.has(name);

/** A process's module, and whether its line of parents reached the launcher. */
interface Descent {
  module: string | null;
  reached: boolean;
}

/**
 * The module each of `pids` descends from. Walks up the parents within `pids`, each process once:
 * the child of the launcher names the module of all below it; below a broken line (a parent
 * outside the job, gone, or a loop of reused pids), a process counts for the nearest module name
 * among itself and the ancestors walked.
 */
function modulesOf(pids: readonly number[], table: ProcessTable): Map<number, Descent> {
  const job = new Set(pids);
  const known = new Map<number, Descent>();
  for (const pid of pids) {
    const path: number[] = [];
    const onPath = new Set<number>();
    let top: Descent = { module: null, reached: false };
    for (let cur = pid; ; ) {
      const seen = known.get(cur);
      if (seen) {
        top = seen;
        break;
      }
      if (onPath.has(cur)) break; // a loop of reused pids
      const parent = table.parentOf(cur);
      if (job.has(parent) && table.nameOf(parent) === LAUNCHER_PROCESS_NAME) {
        const name = table.nameOf(cur);
        top = { module: isModuleName(name) ? name : null, reached: true };
        known.set(cur, top);
        break;
      }
      path.push(cur);
      onPath.add(cur);
      if (!job.has(parent)) break;
      cur = parent;
    }
    let below = top;
    for (let i = path.length - 1; i >= 0; i--) {
      const p = path[i]!;
      if (!below.reached) {
        const own = table.nameOf(p);
        if (isModuleName(own)) below = { module: own, reached: false };
      }
      known.set(p, below);
    }
  }
  return known;
}

/** The module most of `pids` descend from, or null (none, a tie, fewer than 3). */
export function forkingModule(pids: readonly number[], table: ProcessTable): ForkingModule | null {
  // each process read once, however many descend from it
  const names = new Map<number, string>();
  const parents = new Map<number, number>();
  const read: ProcessTable = {
    nameOf: (pid) => names.get(pid) ?? (names.set(pid, table.nameOf(pid)), names.get(pid)!),
    parentOf: (pid) => parents.get(pid) ?? (parents.set(pid, table.parentOf(pid)), parents.get(pid)!),
  };
  const counted = pids.slice(0, MAX_READ);
  const modules = modulesOf(counted, read);
  const counts = new Map<string, number>();
  for (const pid of counted) {
    const module = modules.get(pid)?.module;
    if (module) counts.set(module, (counts.get(module) ?? 0) + 1);
  }
  let best: ForkingModule | null = null;
  let tie = false;
  for (const [module, processes] of counts) {
    if (!best || processes > best.processes) [best, tie] = [{ module, processes }, false];
    else if (processes === best.processes) tie = true;
  }
  return best && !tie && best.processes >= 3 ? best : null;
}

/** A process limit hit, with the module whose code forks (limitHit.module) when `pids` name one. */
export function withForkingModule(hit: LimitHit, pids: readonly number[], table: ProcessTable): LimitHit {
  const who = forkingModule(pids, table);
  return who ? { ...hit, module: who.module, moduleProcesses: who.processes } : hit;
}
