/**
 * Changes of producer on input data ports, as `contract trace` tells them: a consumer writes
 * `producer_changed` when a value comes from another producer than its last
 * (runtime/src/dataflow.c). A schema switch between two schemas that feed the port from different
 * modules is a fact (`was CTL: a new producer (a schema switch)`): the story tells the first change
 * of each port between two producers as a plain line, the later ones counted at the end. Two
 * producers feeding the port at once (`was CTL: interleaved: ...`: a producer delivered a single
 * value between two of the other's, twice within 1 s) is a wiring fault: each port's first is told as a warning. Bounded: at most
 * PORTS_FOLLOWED ports and pairs.
 */
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

const PORTS_FOLLOWED = 4096;

/** The words the runtime writes in an interleave's detail. */
const INTERLEAVED = /^was [^:]*: interleaved: /;
/** The producer before, from a detail `was CTL: ...`. */
const WAS = /^was ([^:]*):/;

/** Whether a `producer_changed` record says two producers feed its port at once. */
export function isInterleave(k: Pick<KnownRecord, 'kind' | 'detail'>): boolean {
    return k.kind === 'producer_changed' && INTERLEAVED.test(k.detail);
}

interface PortChanges {
    changes: number;
    interleaves: number;
    producers: Set<string>;
}

export class ProducerChanges {
    private readonly ports = new Map<string, PortChanges>();
    private readonly pairsTold = new Set<string>();

    /**
     * Follows one record; the story's line for a port's first change between two producers
     * (`input MOT:0 now fed by SRC (was CTL): a schema switch; later changes are counted at the end`)
     * and for a port's first interleave (`warning: input MOT:0 is fed by CTL and SRC at once
     * (their values interleave): an input data port has one producer; ...`).
     */
    see(k: KnownRecord): string | undefined {
        if (k.kind !== 'producer_changed') return undefined;
        const port = `${k.module}:${k.port ?? '?'}`;
        const was = WAS.exec(k.detail)?.[1] ?? '?';
        let p = this.ports.get(port);
        if (!p) {
            if (this.ports.size >= PORTS_FOLLOWED) return undefined;
            p = { changes: 0, interleaves: 0, producers: new Set() };
            this.ports.set(ownString(port), p);
        }
        p.changes++;
        for (const m of [was, k.peer]) if (p.producers.size < 8) p.producers.add(ownString(m));
        if (isInterleave(k)) {
            p.interleaves++;
            if (p.interleaves > 1) return undefined;
            return `warning: input ${port} is fed by ${was} and ${k.peer} at once (their values interleave): an input data port has one producer; later changes are counted at the end`;
        }
        const pair = `${port} ${[was, k.peer].sort().join(' ')}`;
        if (this.pairsTold.has(pair) || this.pairsTold.size >= PORTS_FOLLOWED) return undefined;
        this.pairsTold.add(ownString(pair));
        return `input ${port} now fed by ${k.peer} (was ${was}): a schema switch; later changes are counted at the end`;
    }

    /** Interleaves of all ports (the line of counts). */
    get interleaves(): number {
        return [...this.ports.values()].reduce((n, p) => n + p.interleaves, 0);
    }

    /**
     * One line per port whose producer changed, in port order, told at the story's end: `input
     * MOT:0 changed producer 4 times (CTL, SRC)`, `..., 6 of them interleaved (two producers at once)`.
     */
    lines(): string[] {
        return [...this.ports].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([port, p]) =>
            `input ${port} changed producer ${p.changes} ${p.changes === 1 ? 'time' : 'times'} (${[...p.producers].sort().join(', ')})` +
            (p.interleaves ? `, ${p.interleaves} of them interleaved (two producers at once: a wiring fault)` : ''));
    }
}
