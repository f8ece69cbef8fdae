/**
 * A module whose records stopped mid-run (killed by SIGKILL, crashed before its handler could
 * write, its code called exit()) while the others went on: its log has no exit record, and the
 * story would otherwise say so only at its end. The first sign another module gives that it is
 * gone — a request to it `not sent, it has ended` or to an `unknown module` — is where the story
 * says when its records stopped, when that was before the run's stop (the launcher's KILL): a
 * module the launcher stopped first is not one that ended mid-run.
 */
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';
import { receiverGone } from './receiver-gone.js';

/** The end of a runtime error record written while the launcher stopped the run. */
export const RUN_STOPPING = '; the run is stopping)';

/** Modules followed, at most (a forged log's names past them are not followed), as the story's STORY_FOLLOWED. */
const FOLLOWED = 4096;


export class EndedMidRun {
    /** Each module's last record's time (monotonic ns), while it wrote no exit or crash record. */
    private readonly last = new Map<string, bigint>();
    private readonly ended = new Set<string>();
    private readonly told = new Set<string>();
    /** The first launcher's KILL read: the run's stop began. */
    private stopAt: bigint | undefined;

    see(k: KnownRecord): void {
        const at = BigInt(k.monoNs);
        if (k.kind === 'request_received' && k.peer === 'contract-launch' && k.detail.startsWith('KILL') && (this.stopAt === undefined || at < this.stopAt)) this.stopAt = at;
        if (k.kind === 'module_exit' || k.kind === 'module_crashed') {
            if (this.ended.size < FOLLOWED) this.ended.add(ownString(k.module));
            return;
        }
        if (this.last.has(k.module)) this.last.set(k.module, at);
        else if (this.last.size < FOLLOWED) this.last.set(ownString(k.module), at);
    }

    /**
     * For an `error` record (after see()) that finds a module gone: `ORD's records stopped at
     * +2.694981s (its last record), before the run's stop, with no exit record: it had ended mid-run
     * (...)`, once per module; undefined when it ended at the stop, wrote its exit record, or was told.
     */
    textFor(k: KnownRecord, offsetText: (ns: bigint) => string): string | undefined {
        if (k.kind !== 'error') return undefined;
        // `STOP request to ORD: not sent, it has ended (...)`, `UNSUBSCRIBE request to SRT: unknown module (...)`
        const gone = receiverGone(k.detail);
        const receiver = gone && gone.way !== 'not running' ? gone.module : undefined;
        if (receiver === undefined || receiver === k.module || this.ended.has(receiver) || this.told.has(receiver)) return undefined;
        const last = this.last.get(receiver);
        if (last === undefined || last >= BigInt(k.monoNs)) return undefined;
        // at the stop (the runtime's `; the run is stopping)`): only with the launcher's KILL read, and before it
        const stopping = k.detail.endsWith(RUN_STOPPING);
        if (stopping ? this.stopAt === undefined || last >= this.stopAt : this.stopAt !== undefined && last >= this.stopAt) return undefined;
        if (this.told.size < FOLLOWED) this.told.add(ownString(receiver));
        const when = stopping ? 'before the run\'s stop' : 'while the others went on';
        return `${receiver}'s records stopped at ${offsetText(last).trim()} (its last record), ${when}, with no exit record: it had ended mid-run ` +
            '(killed, crashed, or its code called exit(); the launcher\'s output says which)';
    }
}
