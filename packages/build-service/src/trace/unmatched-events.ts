/**
 * A supervisor's module events that changed no rule, as `contract trace` tells them: the
 * supervisor writes each module event it took as an `event_received` record once its rules have
 * seen it, with the rule changes it made and its value (`rules=0 value="lsot"`:
 * runtime/src/engines/sup_main.c). A rule waiting for `status == "lost"` while the camera sends
 * "lsot" gives no other sign. The story tells each flow's first event of each value that changed
 * no rule where it happens, and at the end each flow's count with its values. Bounded: at most
 * FLOWS_FOLLOWED flows and VALUES_FOLLOWED values each, whatever the run's length.
 */
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** Flows followed at most (a forged log naming a million flows does not grow the story's memory). */
const FLOWS_FOLLOWED = 4096;
/** Distinct values counted apart per flow; the others are counted together. */
export const VALUES_FOLLOWED = 8;

/** One flow's events that changed no rule: how many, per value (the first VALUES_FOLLOWED). */
interface Unmatched {
    supervisor: string;
    source: string;
    count: number;
    values: Map<string, number>;
    otherValues: number;
}

/** The value of a supervisor's `event_received` record, when it has one (logs of older versions and modules' records: none). */
export function receivedValue(k: Pick<KnownRecord, 'kind' | 'fields'>): string | undefined {
    if (k.kind !== 'event_received') return undefined;
    const v = k.fields['value'];
    return v === undefined ? undefined : String(v);
}

/** Whether a supervisor's `event_received` record says its event changed no rule (`rules=0`). */
export function changedNoRule(k: Pick<KnownRecord, 'kind' | 'fields'>): boolean {
    return k.kind === 'event_received' && k.fields['rules'] === 0 && k.fields['value'] !== undefined;
}

/** `CAM:0`: the producer's port of an `event_received` record (its from_port), as a rule's cause names it. */
export function receivedSource(k: Pick<KnownRecord, 'peer' | 'fields'>): string {
    return `${k.peer}:${k.fields['from_port'] ?? '?'}`;
}

/** `×12`. */
function times(n: number): string {
    return `×${n}`;
}

export class UnmatchedEvents {
    private readonly flows = new Map<string, Unmatched>();
    /** Every event that changed no rule, of all flows (the line of counts). */
    private all = 0;

    /**
     * Follows one record; for a flow's first event of a value that changed no rule, the story's
     * line for it (after the record's time and module): `received CAM:0 = "lsot": it changed no
     * rule (no rule waited for this value); later ones are counted at the end`. Undefined otherwise.
     */
    see(k: KnownRecord): string | undefined {
        if (!changedNoRule(k)) return undefined;
        this.all++;
        const value = receivedValue(k)!;
        const source = receivedSource(k);
        const name = `${k.module} ${source}`;
        let f = this.flows.get(name);
        if (!f) {
            if (this.flows.size >= FLOWS_FOLLOWED) return undefined;
            f = { supervisor: ownString(k.module), source: ownString(source), count: 0, values: new Map(), otherValues: 0 };
            this.flows.set(ownString(name), f);
        }
        f.count++;
        const seen = f.values.get(value);
        if (seen !== undefined) {
            f.values.set(value, seen + 1);
            return undefined;
        }
        if (f.values.size >= VALUES_FOLLOWED) {
            f.otherValues++;
            return undefined;
        }
        f.values.set(ownString(value), 1);
        return `received ${source} = ${value}: it changed no rule (no active rule waited for this value); later ones are counted at the end`;
    }

    /** Events that changed no rule, all flows together (the line of counts). */
    get count(): number {
        return this.all;
    }

    /**
     * One line per flow with events that changed no rule, in flow order, told at the story's end:
     * `LFR got CAM:0 ×12 that changed no rule: "lsot" ×12`.
     */
    lines(): string[] {
        return [...this.flows].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([, f]) =>
            `${f.supervisor} got ${f.source} ${times(f.count)} that changed no rule: ` +
            [...f.values].map(([v, n]) => `${v} ${times(n)}`).join(', ') +
            (f.otherValues ? `, ${f.otherValues} of other values` : ''));
    }
}
