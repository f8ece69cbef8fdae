/**
 * How each asynchronous module handled the events its event flows brought it, as `contract trace`
 * tells it at the end of its story: from its `event_handled` records (libmodule writes one when the
 * module reads its mailbox again after an event's handler, `handling_ns` after its `event_received`,
 * docs/runtime-api.md; the simulator writes them too, `exec M TIME` its handler's time), per module
 * the events handled, the handling time's p99 and max, and the longest handling with its event and
 * when it was received: `MAB handled 12 events: handling p99 3.7 ms, max 3.7 ms; the longest, MAA:0
 * -> MAB:0 received at +1.502114s, 3.7 ms`. Bounded: at most STORY_FOLLOWED modules, a histogram
 * each, whatever the run's length.
 */
import { DurationQuantiles } from './duration-quantiles.js';
import { durationText } from './duration-text.js';
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** Modules followed at most (a forged log naming a million modules does not grow the story's memory). */
const MODULES_FOLLOWED = 4096;

/** One asynchronous module's handling of events over the run, as data (`contract run --format json`'s `eventHandling`). */
export interface EventHandlingFigures {
    module: string;
    /** Events whose handler ended (its `event_handled` records). */
    handled: number;
    p99HandlingNs: number;
    maxHandlingNs: number;
    /** The longest handling (the first of equal ones): its event's producer and ports, when it was received (mono ns), how long it took. */
    longest: { from: string; fromPort: number | null; port: number | null; receivedMonoNs: string; handlingNs: number };
}

interface Handling {
    times: DurationQuantiles;
    longest: EventHandlingFigures['longest'];
}

/** A whole, non-negative number of a record's fields, else undefined (a forged word is no time). */
function nanoseconds(v: string | number | undefined): number | undefined {
    return typeof v === 'number' && Number.isSafeInteger(v) && v >= 0 ? v : undefined;
}

export class EventHandling {
    private readonly modules = new Map<string, Handling>();

    /** Follows one record: an `event_handled` counts in its module's figures. */
    see(k: KnownRecord): void {
        if (k.kind !== 'event_handled') return;
        const ns = nanoseconds(k.fields['handling_ns']);
        if (ns === undefined) return;
        let m = this.modules.get(k.module);
        const fromPort = typeof k.fields['from_port'] === 'number' ? k.fields['from_port'] : null;
        const longest = { from: ownString(k.peer), fromPort, port: k.port, receivedMonoNs: String(BigInt(k.monoNs) - BigInt(ns)), handlingNs: ns };
        if (!m) {
            if (this.modules.size >= MODULES_FOLLOWED) return;
            this.modules.set(ownString(k.module), (m = { times: new DurationQuantiles(), longest }));
        } else if (ns > m.longest.handlingNs) m.longest = longest;
        m.times.add(ns);
    }

    /** Per module that handled events, in name order. */
    figures(): EventHandlingFigures[] {
        return [...this.modules].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([module, m]) => ({
            module, handled: m.times.count, p99HandlingNs: m.times.quantileNs(0.99), maxHandlingNs: m.times.maxNs, longest: m.longest,
        }));
    }

    /**
     * One line per module that handled events, in name order (`at`: a mono time as the story's
     * offset): `MAB handled 12 events: handling p99 3.7 ms, max 3.7 ms; the longest, MAA:0 -> MAB:0
     * received at +1.502114s, 3.7 ms`.
     */
    lines(at: (monoNs: bigint) => string): string[] {
        return this.figures().map((f) => {
            const l = f.longest;
            return `${f.module} handled ${f.handled} ${f.handled === 1 ? 'event' : 'events'}: handling p99 ${durationText(f.p99HandlingNs)}, max ${durationText(f.maxHandlingNs)}; ` +
                `the longest, ${l.from}:${l.fromPort ?? '?'} -> ${f.module}:${l.port ?? '?'} received at ${at(BigInt(l.receivedMonoNs))}, ${durationText(l.handlingNs)}`;
        });
    }
}
