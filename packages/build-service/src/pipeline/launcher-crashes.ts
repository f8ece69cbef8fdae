/**
 * The modules contract-launch saw fail (a crash: a signal, a non-zero exit; or a kill: a SIGKILL
 * it did not send, the kernel's OOM killer at the memory limit), read from its own lines, for the
 * failed run's message: `run failed: module MSC crashed (died by signal 11 (Segmentation fault))`
 * rather than make's exit status alone, which reads like a build failure. The launcher's words
 * (runtime/launcher/contract-launch.c reap, docs/runtime-api.md "contract-launch"): `module X (pid
 * N) died by signal ...` / `exited with status N ...`, then, at the end, `FAILED: module X died by
 * signal 11 (Segmentation fault)`, `FAILED: module X exited with status 3` or `FAILED: module X was
 * killed (...)` (a launcher before 2026-12-07 said `FAILED: module X crashed` for the first two).
 */
import { launcherEndLine } from '../trace/launcher-end-line.js';

import { crashSignalMeaning } from '@contract-studio/conventions';
/** The launcher's `died by signal 9 (Killed)`, `... while the run stopped`: a SIGKILL it did not send (it terminates with SIGTERM, and says `terminated`). */
const SIGKILLED = /^died by signal 9 \(Killed\)( while the run stopped)?$/;
/** `died by signal S (...)` or `exited with status N`; `was killed (a SIGKILL the launcher did not send: ...)`; `crashed` (an older launcher's, for both of the first). */
const FAILED_LINE = /^FAILED: module ([A-Za-z_]\w*) (crashed|died by signal \d{1,3} \([^()]{0,100}\)|exited with status \d{1,3}|was killed(?: \(.{1,300}\))?)$/;

/** A generated module's own line when its init region returned 0 (codegen's module-source.ts), its module tag removed. */
const INIT_REFUSED = /^([A-Za-z_]\w*): its init region returned 0 \(false\): the module does not start$/;
/** Failures named in one message at most (the others counted). */
const NAMED = 4;

/** One module the launcher saw fail. */
export interface LauncherFailure {
  module: string;
  /** How it ended, as the launcher said it (`died by signal 11 (Segmentation fault)`); undefined: no exit line read. */
  how: string | undefined;
  /** It was killed (a SIGKILL the launcher did not send), not crashed by its code. */
  killed: boolean;
  /** Its init region returned 0: it said so and ended with a status, before it ever started. */
  initRefused: boolean;
}

/** It ended by a signal of its own code's making (or no exit line was read), not with a status nor killed. */
export function crashedBySignal(f: LauncherFailure): boolean {
  return !f.killed && !f.initRefused && !f.how?.startsWith('exited with status');
}

/**
 * What happened to a module that failed, not killed, after its name: `crashed (died by signal 11
 * (Segmentation fault))`, `did not start: its init region returned 0 (exited with status 255)`,
 * `failed (exited with status 3)`: ending with a status is no crash.
 */
export function failureWords(f: LauncherFailure): string {
  const how = f.how ?? 'no exit line';
  if (f.initRefused) return `did not start: its init region returned 0 (${how})`;
  return crashedBySignal(f) ? `crashed (${how})` : `failed (${how})`;
}

/**
 * `: <what its signal means>` for a module that crashed by a crash signal (`died by signal 8
 * (Floating point exception)`: `: an integer division by zero, or INT_MIN / -1`, conventions'
 * crash-signals.ts), told after where it crashed; '' for any other failure.
 */
export function crashMeaningText(f: LauncherFailure): string {
  const m = crashedBySignal(f) && f.how ? /^died by signal (\d{1,2})\b/.exec(f.how) : null;
  const meaning = m ? crashSignalMeaning(Number(m[1])) : undefined;
  return meaning ? `: ${meaning}` : '';
}

export class LauncherCrashes {
  private readonly how = new Map<string, string>();
  private readonly failed: { module: string; killed: boolean }[] = [];
  private readonly initRefused = new Set<string>();

  /** A line of contract-launch (its `contract-launch: ` prefix removed). */
  line(text: string): void {
    const end = launcherEndLine(text);
    if (end) {
      if (!end.how.startsWith('terminated') && this.how.size < 1024) this.how.set(end.module, end.how);
      return;
    }
    const failed = FAILED_LINE.exec(text);
    if (failed && !this.failed.some((f) => f.module === failed[1]) && this.failed.length < 1024)
      this.failed.push({ module: failed[1]!, killed: failed[2]!.startsWith('was killed') });
  }

  /** A line of module `module`'s output (its `[NAME] ` tag removed): its init region's refusal to start is noted. */
  moduleLine(module: string, text: string): void {
    if (INIT_REFUSED.exec(text)?.[1] === module && this.initRefused.size < 1024) this.initRefused.add(module);
  }

  /** The modules that failed, in the order the launcher named them, each with how it ended. */
  failures(): LauncherFailure[] {
    return this.failed.map(({ module, killed }) => {
      const how = this.how.get(module);
      const sigkilled = killed || (how !== undefined && SIGKILLED.test(how));
      return { module, how, killed: sigkilled, initRefused: !sigkilled && this.initRefused.has(module) && !!how?.startsWith('exited with status') };
    });
  }

  /**
   * `module MSC crashed (died by signal 11 (...))`, `module HOG was killed by the memory limit
   * (died by signal 9 (Killed))`, `2 modules crashed: MSC (...), MAB (...)`; undefined when none
   * failed. `limitHit`: the limit that stopped the run; a module killed while the memory limit was
   * hit was killed by it (the kernel's OOM killer). `sites`: where each crashed module crashed
   * (` at FILE:LINE in its protected region ID (function)`), told after how it ended.
   */
  summary(limitHit?: { name: string } | null, sites?: ReadonlyMap<string, string>): string | undefined {
    const failures = this.failures();
    if (!failures.length) return undefined;
    const by = limitHit?.name === 'memory' ? ' by the memory limit' : '';
    // where it crashed (` at FILE:LINE ...`: crash-reports.ts), after how it ended
    const how = (f: LauncherFailure) => `${f.how ?? 'no exit line'}${f.killed ? '' : `${sites?.get(f.module) ?? ''}${crashMeaningText(f)}`}`;
    if (failures.length === 1) {
      const f = failures[0]!;
      return `module ${f.module} ${f.killed ? `was killed${by} (${f.how ?? 'no exit line'})` : `${failureWords(f)}${sites?.get(f.module) ?? ''}${crashMeaningText(f)}`}`;
    }
    // one ended with a status (its init refused to start, its code's exit): each said as it was
    if (failures.some((f) => !f.killed && !crashedBySignal(f))) {
      const named = failures.slice(0, NAMED).map((f) => `${f.module} ${f.killed ? `was killed${by} (${f.how ?? 'no exit line'})` : `${failureWords(f)}${crashedBySignal(f) ? `${sites?.get(f.module) ?? ''}${crashMeaningText(f)}` : ''}`}`).join(', ');
      return `${failures.length} modules failed: ${named}${failures.length > NAMED ? ` and ${failures.length - NAMED} more` : ''}`;
    }
    const killed = failures.filter((f) => f.killed).length;
    const verb = killed === 0 ? 'crashed' : killed === failures.length ? `were killed${by}` : `crashed or were killed${by}`;
    const mixed = killed > 0 && killed < failures.length;
    const named = failures.slice(0, NAMED).map((f) => `${f.module} (${mixed && f.killed ? 'killed: ' : ''}${how(f)})`).join(', ');
    const more = failures.length > NAMED ? ` and ${failures.length - NAMED} more` : '';
    return `${failures.length} modules ${verb}: ${named}${more}`;
  }
}
