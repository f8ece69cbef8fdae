/**
 * What went wrong in a `contract run`, as told to the user: the modules the launcher saw crash, and
 * the run's problems with ORD's `*stateindex` advice left out for a module that crashed.
 */
import type { JobOutcome } from '../job-runner.js';

export interface ModuleFailure {
    module: string;
    how: string;
}

/** Module crashes reported by the launcher (`FAILED: module X crashed`, with the preceding exit/signal line). */
export function moduleFailures(lines: JobOutcome['runLines']): ModuleFailure[] {
    const how = new Map<string, string>();
    const failed: ModuleFailure[] = [];
    for (const { source, line } of lines) {
        if (source !== 'launcher') continue;
        const exit = /^module (\S+) \(pid \d+\) (exited with status \d+(?: while the run stopped)?|died by signal .*)$/.exec(line);
        if (exit) how.set(exit[1]!, exit[2]!);
        const crash = /^FAILED: module (\S+) crashed/.exec(line);
        if (crash) failed.push({ module: crash[1]!, how: how.get(crash[1]!) ?? 'crashed' });
    }
    return failed;
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
