/**
 * Back-pressure on event flows, as `contract trace` tells it: a producer's `PostEvent` that waited
 * for room in its subscriber's full mailbox (the subscriber takes its events slower than they
 * come) writes `event_waited` records, one per streak of waits (runtime/src/eventflow.c). The story
 * tells a flow's first such record where it happens, and at the end each flow's waits with the
 * longest delivery latency its subscriber's `event_received` records give (the time an event
 * spent waiting in the full mailbox, and in the producer's wait before it). Bounded: at most
 * STORY_FOLLOWED flows, a few numbers each, whatever the run's length.
 */
import { durationText } from './duration-text.js';
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** Flows followed at most (a forged log naming a million flows does not grow the story's memory). */
const FLOWS_FOLLOWED = 4096;

/** An event flow's waits for room over all its streaks so far, and its deliveries' longest latency. */
export interface FlowWaitTotals {
    /** Posts that waited for room (every streak's `waits`). */
    waits: number;
    /** Their time waiting, in all (every streak's `wait_ns`). */
    waitNs: number;
    /** The longest one (the streaks' largest `max_wait_ns`). */
    maxWaitNs: number;
    /** The subscriber's `event_received` records' longest `latency_ns` (0: none known). */
    maxLatencyNs: number;
}

/** One event flow's waits for room and its deliveries' latency. */
interface FlowWaits extends FlowWaitTotals {
    producer: string;
    subscriber: string;
}

/** `waited for room 340 times (4.2 s in all, up to 25 ms)`: a flow's waits over all its streaks so far. */
export function waitTotalsText(w: FlowWaitTotals): string {
    return `waited for room ${times(w.waits)} (${durationText(w.waitNs)} in all, up to ${durationText(w.maxWaitNs)})`;
}

/**
 * The story's closing line for an event flow whose posts waited (`name`: `BAT:0 -> GCS:0`): `BAT's
 * events to GCS (BAT:0 -> GCS:0) waited for room 340 times (4.2 s in all, up to 25 ms): GCS takes
 * its events slower than BAT posts them; delivery latency up to 527 ms`.
 */
export function flowWaitsLine(name: string, producer: string, subscriber: string, w: FlowWaitTotals): string {
    return `${producer}'s events to ${subscriber} (${name}) ${waitTotalsText(w)}: ${subscriber} takes its events slower than ${producer} posts them` +
        `${w.maxLatencyNs ? `; delivery latency up to ${durationText(w.maxLatencyNs)}` : ''}`;
}

/** A whole, non-negative number of a record's fields, else 0 (a forged word is no count). */
function count(v: string | number | undefined): number {
    return typeof v === 'number' && Number.isSafeInteger(v) && v > 0 ? v : 0;
}

/** `1 time`, `2 times`. */
function times(n: number): string {
    return `${n} ${n === 1 ? 'time' : 'times'}`;
}

/** `BAT:0 -> GCS:0` for an `event_waited` record (producer's output port, subscriber's input port). */
function waitedFlow(k: KnownRecord): string {
    return `${k.module}:${k.port ?? '?'} -> ${k.peer}:${k.fields['to_port'] ?? '?'}`;
}

/** `BAT:0 -> GCS:0` for an `event_received` record (the producer's port is its from_port). */
function receivedFlow(k: KnownRecord): string {
    return `${k.peer}:${k.fields['from_port'] ?? '?'} -> ${k.module}:${k.port ?? '?'}`;
}

export class EventWaits {
    private readonly flows = new Map<string, FlowWaits>();
    /** Every post that waited for room, of all flows (the line of counts). */
    private allWaits = 0;

    /**
     * Follows one record; for a flow's first `event_waited` record, the story's line for it (after
     * the record's time and module): `events BAT:0 -> GCS:0 waited for room in GCS's full mailbox
     * 48 times in 1 s (940 ms in all, up to 21 ms each): GCS takes its events slower than BAT posts
     * them; later waits are counted at the end`. Undefined otherwise.
     */
    see(k: KnownRecord): string | undefined {
        if (k.kind === 'event_received') {
            const latency = count(k.fields['latency_ns']);
            const f = this.flows.get(receivedFlow(k));
            if (f && latency > f.maxLatencyNs) f.maxLatencyNs = latency;
            else if (!f && latency > 0) this.flowOf(receivedFlow(k), k.peer, k.module, latency);
            return undefined;
        }
        if (k.kind !== 'event_waited') return undefined;
        const waits = count(k.fields['waits']), waitNs = count(k.fields['wait_ns']), maxNs = count(k.fields['max_wait_ns']);
        this.allWaits += waits;
        const name = waitedFlow(k);
        const f = this.flowOf(name, k.module, k.peer, 0);
        if (!f) return undefined;
        const first = f.waits === 0;
        f.waits += waits;
        f.waitNs += waitNs;
        if (maxNs > f.maxWaitNs) f.maxWaitNs = maxNs;
        if (!first || waits === 0) return undefined;
        const streak = count(k.fields['streak_ns']);
        return `events ${name} waited for room in ${k.peer}'s full mailbox ${times(waits)}${streak ? ` in ${durationText(streak)}` : ''} ` +
            `(${durationText(waitNs)} in all, up to ${durationText(maxNs)} each): ${k.peer} takes its events slower than ${k.module} posts them; later waits are counted at the end`;
    }

    /** The flow's record, made when there is room (a flow seen first by its deliveries keeps their latency). */
    private flowOf(name: string, producer: string, subscriber: string, latencyNs: number): FlowWaits | undefined {
        let f = this.flows.get(name);
        if (!f && this.flows.size < FLOWS_FOLLOWED) {
            f = { producer: ownString(producer), subscriber: ownString(subscriber), waits: 0, waitNs: 0, maxWaitNs: 0, maxLatencyNs: latencyNs };
            this.flows.set(ownString(name), f);
        }
        return f;
    }

    /** Posts that waited for room, all flows together (the line of counts: `340 event posts waited for room`). */
    get waits(): number {
        return this.allWaits;
    }

    /**
     * One line per event flow whose posts waited, in flow order, told at the story's end: `BAT's
     * events to GCS (BAT:0 -> GCS:0) waited for room 340 times (4.2 s in all, up to 25 ms): GCS
     * takes its events slower than BAT posts them; delivery latency up to 527 ms`.
     */
    lines(): string[] {
        return [...this.flows].filter(([, f]) => f.waits > 0).sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([name, f]) => flowWaitsLine(name, f.producer, f.subscriber, f));
    }
}
