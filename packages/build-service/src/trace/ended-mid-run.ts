/**
 * A module whose records stopped mid-run (killed by SIGKILL, crashed before its handler could
 * write, its code called exit()) while the others went on: its log has no exit record, and the
 * story would otherwise say so only at its end. The first sign another module gives that it is
 * gone — a request to it that found it `not running` (its mailbox stale), `not sent, it has ended`
 * or to an `unknown module`, or ORD's `stuck: ... it is no longer running` — is the evidence; the
 * story tells it at the module's own last record (its time and name: when its records stopped),
 * when that was before the run's stop (the launcher's KILL): a module the launcher stopped first is
 * not one that ended mid-run. The story is told as the records are read, so the line comes where
 * the sign is read, after the lines of the records in between. The launcher's own end line of a
 * module, from the logs folder's `contract-launch.log` (launcher-lines-file.ts), is such a sign too,
 * told at the line's time: it comes as the module is reaped, whether or not another module sends it
 * a request; it is taken only when its pid is that module's, as its `module_started` record says.
 */
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';
import { receiverGone, stuckSaysGone } from './receiver-gone.js';
import { endedOnItsOwn } from './launcher-end-line.js';
import type { LauncherFileLine } from './launcher-lines-file.js';

/** The end of a runtime error record written while the launcher stopped the run. */
export const RUN_STOPPING = '; the run is stopping)';

/** Modules followed, at most (a forged log's names past them are not followed), as the story's STORY_FOLLOWED. */
const FOLLOWED = 4096;


export class EndedMidRun {
    /** Each module's last record's time (monotonic ns), while it wrote no exit or crash record. */
    private readonly last = new Map<string, bigint>();
    private readonly ended = new Set<string>();
    private readonly told = new Set<string>();
    /** Each module's pid, as its last `module_started` record gives it. */
    private readonly pids = new Map<string, number>();
    /** The first launcher's KILL read: the run's stop began. */
    private stopAt: bigint | undefined;

    see(k: KnownRecord): void {
        const at = BigInt(k.monoNs);
        if (k.kind === 'request_received' && k.peer === 'contract-launch' && k.detail.startsWith('KILL') && (this.stopAt === undefined || at < this.stopAt)) this.stopAt = at;
        if (k.kind === 'module_exit' || k.kind === 'module_crashed') {
            if (this.ended.size < FOLLOWED) this.ended.add(ownString(k.module));
            return;
        }
        if (k.kind === 'module_started') {
            const pid = /(?:^| )pid=(\d{1,10})(?: |$)/.exec(k.detail);
            if (pid && (this.pids.has(k.module) || this.pids.size < FOLLOWED)) this.pids.set(ownString(k.module), Number(pid[1]));
        }
        if (this.last.has(k.module)) this.last.set(k.module, at);
        else if (this.last.size < FOLLOWED) this.last.set(ownString(k.module), at);
    }

    /**
     * For a record (after see()) that is the first sign a module is gone (`told`: the story's words
     * for that record): the story's line for it, at the gone module's last record — `+0.700000s ORD
     * its records stop here (its last record), before the run's stop, with no exit record: it had
     * ended mid-run (...); the first sign, at +5.000000s: BSE while the run stopped: STOP request to
     * ORD: not sent, it has ended (...)` —, once per module; undefined when it ended at the stop,
     * wrote its exit record, or was told.
     */
    lineFor(k: KnownRecord, told: string, offsetText: (ns: bigint) => string): string | undefined {
        const receiver = goneModule(k);
        if (receiver === undefined || receiver === k.module || this.ended.has(receiver) || this.told.has(receiver)) return undefined;
        const last = this.last.get(receiver);
        if (last === undefined || last >= BigInt(k.monoNs)) return undefined;
        // at the stop (the runtime's `; the run is stopping)`): only with the launcher's KILL read, and before it
        const stopping = k.kind === 'error' && k.detail.endsWith(RUN_STOPPING);
        if (stopping ? this.stopAt === undefined || last >= this.stopAt : this.stopAt !== undefined && last >= this.stopAt) return undefined;
        if (this.told.size < FOLLOWED) this.told.add(ownString(receiver));
        const when = stopping ? 'before the run\'s stop' : 'while the others went on';
        return `${offsetText(last)} ${receiver.padEnd(4)} its records stop here (its last record), ${when}, with no exit record: it had ended mid-run ` +
            `(killed, crashed, or its code called exit(); the launcher's output says which); the first sign, at ${offsetText(BigInt(k.monoNs)).trim()}: ${k.module} ${told}`;
    }

    /**
     * One of the launcher's own end lines (`end`, from the logs folder's contract-launch.log, read
     * before the first record after its time): when it says the module ended on its own (a signal
     * the launcher did not send, an exit with a status) and names that module's pid, as its
     * `module_started` record gave it, the story's line for it at the module's last record — `+1.02s
     * MAB  its records stop here (its last record), with no exit record: it ended mid-run, while the
     * others went on; the launcher's line, at +1.03s: contract-launch: module MAB (pid 41) died by
     * signal 9 (Killed)` —, once per module; undefined when it wrote its exit or crash record, was
     * told, has no record, or the line names another pid (not the launcher's word on this module).
     */
    launcherLine(end: LauncherFileLine, offsetText: (ns: bigint) => string): LauncherToldEnd | undefined {
        if (!endedOnItsOwn(end.how) || this.pids.get(end.module) !== end.pid) return undefined;
        if (this.ended.has(end.module) || this.told.has(end.module)) return undefined;
        const last = this.last.get(end.module);
        if (last === undefined || last > end.monoNs) return undefined;
        if (this.told.size < FOLLOWED) this.told.add(ownString(end.module));
        const when = end.how.endsWith(' while the run stopped') ? 'while the run stopped' : 'while the others went on';
        return {
            module: end.module,
            text: `${offsetText(last)} ${end.module.padEnd(4)} its records stop here (its last record), with no exit record: it ended mid-run, ${when}; ` +
                `the launcher's line, at ${offsetText(end.monoNs).trim()}: contract-launch: ${end.line}`,
        };
    }
}

/** A module the launcher's line told ended, and the story's line for it. */
export interface LauncherToldEnd {
    module: string;
    text: string;
}

/** The module record `k` says is gone: a request's receiver it found gone (any way), ORD's stuck module no longer running. */
function goneModule(k: KnownRecord): string | undefined {
    if (k.kind === 'error') return receiverGone(k.detail)?.module;
    if (k.kind === 'scheduler' && k.fields['what'] === 'stuck' && stuckSaysGone(k.detail) && typeof k.fields['module'] === 'string') return k.fields['module'];
    return undefined;
}
