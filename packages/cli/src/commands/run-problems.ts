/**
 * What went wrong in a `contract run`, as told to the user: the modules the launcher saw crash, and
 * the run's problems with ORD's `*stateindex` advice left out for a module that crashed.
 */
import { LauncherCrashes } from '@contract-studio/build-service';
import type { JobOutcome } from '../job-runner.js';

export interface ModuleFailure {
    module: string;
    how: string;
}

/**
 * Module crashes reported by the launcher (`FAILED: module X crashed`, with the preceding exit/signal
 * line), read by the build service's reader of them (the failed run's message names the same).
 */
export function moduleFailures(lines: JobOutcome['runLines']): ModuleFailure[] {
    const crashes = new LauncherCrashes();
    for (const { source, line } of lines) if (source === 'launcher') crashes.line(line);
    return crashes.failures().map(({ module, how }) => ({ module, how: how ?? 'crashed' }));
}

/** ORD's advice on a module that does not finish its release, which is wrong for one that crashed. */
const STUCK_ADVICE = /: does its exec region set \*stateindex = -1\?/;

/**
 * The run's problems as told: a module ORD declared stuck because it crashed is told as crashed,
 * without the advice to set `*stateindex = -1` (its code ended by a crash, not a loop).
 */
export function problemLines(issues: readonly { kind: string; module?: string; message: string }[], failures: readonly ModuleFailure[]): string[] {
    const crashed = new Map(failures.map((f) => [f.module, f.how]));
    return issues.map((i) => {
        const how = i.kind === 'module-stuck' && i.module !== undefined ? crashed.get(i.module) : undefined;
        return how === undefined ? i.message : `${i.message.replace(STUCK_ADVICE, '')}: it crashed (${how})`;
    });
}
