/**
 * Events a producer posted that never reached their subscriber: `PostEvent` waits up to 2 s for
 * room in a subscriber's full mailbox, then that post fails and the event is lost; the producer's
 * log holds `event_posted SUB,port,...,to_port=N [oneshot] failed` (runtime/src/eventflow.c). A post
 * that failed because its subscriber had already ended while the launcher stopped the run is no
 * loss: the runtime logs its `error` record just before, ending `; the run is stopping)`
 * (runtime/src/mailbox.c rt_send_failed), and the run's end is expected to leave such posts.
 * One reader for `contract trace`'s story (its line of counts, a line per flow at the end) and the
 * build service's run issues (a lost event fails the run). Bounded: at most FLOWS_FOLLOWED flows.
 */

/** Flows followed at most (a forged log naming a million flows does not grow the memory). */
const FLOWS_FOLLOWED = 4096;
/** Modules whose last record is remembered at most (a run has at most 256). */
const MODULES_FOLLOWED = 4096;

/** The runtime's `error` record of a send to a peer that ended at the run's stop (mailbox.c rt_send_failed). */
const AT_STOP_ERROR = /; the run is stopping\)"?$/;
/** The runtime's `error` record of a failed event send: `EVENT request to SUB: <why> (<errno text>)`. */
const EVENT_SEND_ERROR = /^"?(EVENT request to [A-Za-z_]\w* ?: [^\n]{1,300}?)"?$/;

/** One flow's lost events. */
export interface LostFlow {
    /** `MAA:2 -> SUP:0`: the producer's output port, the subscriber's input port. */
    name: string;
    producer: string;
    subscriber: string;
    lost: number;
    /** The runtime's words for the last failure (its `error` record just before), when it wrote one. */
    why?: string;
}

/** What one record says, as either reader gives it: the producer (the log's module), its kind, peer, port and detail. */
export interface PostRecordFields {
    module: string;
    kind: string;
    peer: string;
    port: string | number | undefined;
    detail: string;
}

/** The `to_port` of an `event_posted` detail (`to_port=0 oneshot failed`). */
function toPort(detail: string): string {
    return /^to_port=(-?\d{1,9})\b/.exec(detail)?.[1] ?? '?';
}

export class LostEvents {
    private readonly flows = new Map<string, LostFlow>();
    /** Each module's last `error` record, when its last record was one (the cause of a failed send that follows). */
    private readonly lastError = new Map<string, string>();
    private allLost = 0;

    /** Follows one record of a module's log (in the log's order per module). */
    see(r: PostRecordFields): void {
        if (r.kind === 'error') {
            if (this.lastError.has(r.module) || this.lastError.size < MODULES_FOLLOWED) this.lastError.set(r.module, r.detail.slice(0, 400));
            return;
        }
        const before = this.lastError.get(r.module);
        if (before !== undefined) this.lastError.delete(r.module);
        if (r.kind !== 'event_posted' || !r.peer || !/ failed"?$/.test(r.detail)) return;
        if (before !== undefined && AT_STOP_ERROR.test(before)) return; // its subscriber had ended at the run's stop
        this.allLost++;
        const name = `${r.module}:${r.port ?? '?'} -> ${r.peer}:${toPort(r.detail)}`;
        let f = this.flows.get(name);
        if (!f && this.flows.size < FLOWS_FOLLOWED) this.flows.set(name, (f = { name, producer: r.module, subscriber: r.peer, lost: 0 }));
        if (!f) return;
        f.lost++;
        const why = before !== undefined ? EVENT_SEND_ERROR.exec(before)?.[1] : undefined;
        if (why) f.why = why;
    }

    /** Posts that failed during the run (not at its stop), all flows together. */
    get lost(): number {
        return this.allLost;
    }

    /** The flows that lost events, in name order. */
    lostFlows(): LostFlow[] {
        return [...this.flows.values()].sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
    }
}

/**
 * `3 events MAA posted to SUP were lost (MAA:2 -> SUP:0): their posts failed (PostEvent gives up
 * after waiting 2 s for room in SUP's full mailbox, ...); the last: EVENT request to SUP: ...`.
 */
export function lostFlowText(f: LostFlow): string {
    return `${f.lost} ${f.lost === 1 ? 'event' : 'events'} ${f.producer} posted to ${f.subscriber} ${f.lost === 1 ? 'was' : 'were'} lost (${f.name}): ` +
        `${f.lost === 1 ? 'its post' : 'their posts'} failed (PostEvent gives up after waiting 2 s for room in ${f.subscriber}'s full mailbox, at once when ${f.subscriber} is not running)` +
        `${f.why ? `; the last: ${f.why}` : ''}`;
}
