/**
 * Which module's code forked past the process limit: a forked process keeps its parent's name
 * (the kernel's `comm`) until it execs, so at the hit the name most of the job's processes share
 * is the module's (modules run as `modules/<M>_mod/<M>`: their name is M). The sandbox's own
 * programs are not modules; a name shared by fewer than 3 processes (a module and one child)
 * names no one.
 */
import type { LimitHit } from '../limits.js';

/** Programs of the sandbox and the build, never a module's code. */
const NOT_MODULES: ReadonlySet<string> = new Set(['bwrap', 'make', 'sh', 'bash', 'dash', 'contract-launch', 'setpriv', 'prlimit', 'docker-init', 'tini', 'cc', 'gcc', 'cc1', 'as', 'ld', 'collect2', 'sleep', 'true']);
/** A module's name as the kernel keeps it (15 characters at most). */
const MODULE_NAME = /^[A-Za-z_][A-Za-z0-9_]{0,14}$/;
/** Processes at the hit that read no more names (a limit of thousands of processes). */
const MAX_READ = 4096;

export interface ForkingModule {
  module: string;
  /** The job's processes of that name at the hit. */
  processes: number;
}

/** The module most of `pids` are named after (`nameOf`: /proc/<pid>/comm, '' when gone), or null. */
export function forkingModule(pids: readonly number[], nameOf: (pid: number) => string): ForkingModule | null {
  const counts = new Map<string, number>();
  for (const pid of pids.slice(0, MAX_READ)) {
    const name = nameOf(pid);
    if (!MODULE_NAME.test(name) || NOT_MODULES.has(name)) continue;
    counts.set(name, (counts.get(name) ?? 0) + 1);
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
export function withForkingModule(hit: LimitHit, pids: readonly number[], nameOf: (pid: number) => string): LimitHit {
  const who = forkingModule(pids, nameOf);
  return who ? { ...hit, module: who.module, moduleProcesses: who.processes } : hit;
}
