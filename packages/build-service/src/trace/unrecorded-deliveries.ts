/**
 * Supervisors whose event deliveries a log does not record: a supervisor of an older version of
 * ContrACT Studio wrote no `event_received` record for the module events it took (today's writes
 * one each, once its rules have seen it: runtime-api.md). A supervisor with a rule change caused
 * by a module event (`cause=M:p value=V`) and no `event_received` record of its own in the whole
 * log is such one: the story's line of counts then says that the number of event deliveries is not
 * known, instead of counting none for it. Bounded: at most SUPERVISORS_FOLLOWED names each.
 */
import type { KnownRecord, RuleRecord } from './records.js';

/** Names followed at most (a forged log naming a million supervisors does not grow the story's memory). */
const SUPERVISORS_FOLLOWED = 4096;

export class UnrecordedDeliveries {
    /** Supervisors with a rule change caused by a module event. */
    private readonly ruledByEvents = new Set<string>();
    /** Modules (supervisors among them) that wrote an `event_received` record. */
    private readonly receivers = new Set<string>();

    seeRule(r: RuleRecord): void {
        if (r.causeEvent.kind === 'event' && this.ruledByEvents.size < SUPERVISORS_FOLLOWED) this.ruledByEvents.add(r.module);
    }

    seeRecord(k: Pick<KnownRecord, 'kind' | 'module'>): void {
        if (k.kind === 'event_received' && this.receivers.size < SUPERVISORS_FOLLOWED) this.receivers.add(k.module);
    }

    /** The supervisors (name order) whose rules changed on module events none of their records tell: logs of an older version. */
    supervisors(): string[] {
        return [...this.ruledByEvents].filter((s) => !this.receivers.has(s)).sort();
    }
}
