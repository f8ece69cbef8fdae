/**
 * What went wrong in a `contract run`, as told to the user: the modules the launcher saw crash, and
 * the run's problems with ORD's `*stateindex` advice left out for a module that crashed.
 */
import { crashMeaningText, crashSiteOfLine, failureWords, LauncherCrashes } from '@contract-studio/build-service';
import { STUCK_ADVICE } from '@contract-studio/conventions';
import type { JobOutcome } from '../job-runner.js';

export interface ModuleFailure {
    module: string;
    /** How it ended, as the launcher said it (`died by signal 11 (Segmentation fault)`). */
    how: string;
    /**
     * Not a crash of its code: a SIGKILL the launcher did not send. `memory-limit`: while the memory
     * limit was hit (the kernel's OOM killer); `sigkill`: otherwise (the real-time mode's hard CPU
     * bound, or another process).
     */
    killedBy?: 'memory-limit' | 'sigkill';
    /** Its init region returned 0: it said so and ended with a status (not a crash). */
    initRefused?: boolean;
    /** Where it crashed, as the build service found it from the module's crash report: ` at FILE:LINE in its protected region ID (function)`. */
    site?: string;
    /** With killedBy, what `contract run` says of it instead of `module CTL crashed (...)`: `CTL was killed by the memory limit (...)`. */
    message?: string;
}

/**
 * `CTL crashed (died by signal 11 (Segmentation fault)) at FILE:LINE ...: a bad pointer: NULL, ...` (what the signal means last), `MAB did not start: its init region
 * returned 0 (exited with status 255)`, `CTL failed (exited with status 3)`, `CTL was killed by the
 * memory limit (...)`: the line `contract run` prints after `module `.
 */
export function failureText(f: ModuleFailure): string {
    return f.message ?? `${f.module} ${whatHappened(f)}${f.site ?? ''}${crashMeaningText(asLauncherFailure(f))}`;
}

const asLauncherFailure = (f: ModuleFailure) => ({ module: f.module, how: f.how, killed: false, initRefused: f.initRefused === true });

/** A failure not killed, in the build service's words (launcher-crashes.ts). */
const whatHappened = (f: ModuleFailure): string => failureWords(asLauncherFailure(f));

/** Why the kernel's OOM killer chose it, as `contract run` says it. */
const OOM_KILL = "signal 9: the kernel's OOM killer, which kills the process using the most memory";
/**
 * Who sends a SIGKILL the launcher did not: in a real-time run (`--realtime`), the kernel at the
 * real-time mode's hard CPU bound (RLIMIT_RTTIME); in any run, another process, or the kernel's OOM
 * killer at a memory limit (the run's own, when hit, is said apart: OOM_KILL). The launcher's own
 * `FAILED: module M was killed (...)` line says the same from its RLIMIT_RTTIME.
 */
function otherKill(realtime: boolean): string {
    return realtime
        ? "a SIGKILL the launcher did not send: the kernel's at the real-time mode's CPU bound, or another process's"
        : "a SIGKILL the launcher did not send: the kernel's at a memory limit, or another process's";
}

/**
 * Module failures reported by the launcher (`FAILED: module X crashed` or `... was killed (...)`,
 * with the preceding exit/signal line), read by the build service's reader of them (the failed
 * run's message names the same). A module killed (a SIGKILL the launcher did not send) in a run the
 * memory limit stopped (`limitHit`) was killed by that limit (the kernel's OOM killer): said so
 * (`killedBy`, `message`), `how` as the launcher said; another one by whom, as the run's mode
 * allows (`realtime`: the real-time mode's CPU bound). A crashed module's `site`: the service's
 * line that tells where it crashed (its crash report mapped to the code).
 */
export function moduleFailures(lines: JobOutcome['runLines'], limitHit?: { name: string } | null, realtime = false): ModuleFailure[] {
    const crashes = new LauncherCrashes();
    const sites = new Map<string, string>();
    for (const { source, line } of lines) {
        if (source === 'launcher') crashes.line(line);
        else if (source !== 'service' && source !== 'run') crashes.moduleLine(source, line);
        const site = source === 'service' ? crashSiteOfLine(line) : undefined;
        if (site) sites.set(site.module, site.said);
    }
    return crashes.failures().map(({ module, how = 'crashed', killed, initRefused }) => {
        const site = sites.get(module);
        if (initRefused) return { module, how, initRefused };
        if (!killed) return site ? { module, how, site } : { module, how };
        const stopped = how.endsWith(' while the run stopped') ? ' while the run stopped' : '';
        return limitHit?.name === 'memory'
            ? { module, how, killedBy: 'memory-limit' as const, message: `${module} was killed by the memory limit${stopped} (${OOM_KILL})` }
            : { module, how, killedBy: 'sigkill' as const, message: `${module} was killed${stopped} (${otherKill(realtime)})` };
    });
}


/**
 * The run's problems as told: a module ORD declared stuck because it crashed is told as crashed,
 * without the advice to set `*stateindex = -1` (its code ended by a crash, not a loop); one killed,
 * by whom as the run's mode allows (`realtime`, as moduleFailures).
 */
export function problemLines(issues: readonly { kind: string; module?: string; message: string }[], failures: readonly ModuleFailure[], realtime = false): string[] {
    const crashed = new Map(failures.map((f) => [f.module, f]));
    return issues.map((i) => {
        const f = i.kind === 'module-stuck' && i.module !== undefined ? crashed.get(i.module) : undefined;
        if (f === undefined) return i.message;
        const why = f.killedBy === 'memory-limit' ? `it was killed by the memory limit (${OOM_KILL})`
            : f.killedBy === 'sigkill' ? `it was killed (${otherKill(realtime)})` : `it ${whatHappened(f)}`;
        return `${i.message.replace(STUCK_ADVICE, '')}: ${why}`;
    });
}
