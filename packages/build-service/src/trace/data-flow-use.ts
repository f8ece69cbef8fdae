/**
 * Data flows that ORD connected and that delivered nothing, or far less than their reader reads,
 * as `contract trace` tells them at the end: a producer whose exec region never calls PostData
 * (or calls it on another port) leaves its consumer reading nothing, silently — no drop, no error,
 * the schema's cycles complete. From ORD's `connect A:p -> B:i * k` and `disconnect` lines (the
 * activation that follows names the schema), A's `data_posted` and B's `data_received` records,
 * and ORD's releases of B, while the flow is connected:
 * - `data flow EST:1 -> CTL:0 connected for 7.07 s (schema altHold): 0 values delivered (EST posted
 *   none on its output :1); CTL read nothing in its 700 releases`;
 * - `... : 12 values delivered (1.7 a second), read 12 times in CTL's 700 releases (99 a second):
 *   1 value for 58 releases` when A posted (every k-th value for `* k`) fewer than a tenth of B's
 *   releases.
 * Only flows connected SILENT_FLOW_MIN_NS in all are told: a flow connected for a moment (a
 * schema activated and deactivated at once) may rightly have delivered nothing. Bounded: at most
 * FLOWS_FOLLOWED flows, a few numbers each. The event flows a supervisor connects (an event
 * schema's `A:p =* B:i`) are told by the same rules, with who connected them (supervisor-flow-use.ts).
 *
 * A simulation's trace (its `sim_start`: simulated()) tells none of them: a simulation runs no
 * module code, so its virtual modules read no data (no `data_received`) and post no event (no
 * `event_posted`; the events a scenario brings are no module's post), and every flow would look
 * silent. One line says so instead, with the flows that would have been told (SIMULATED_FLOWS_WHY).
 *
 * A record's time is read (a BigInt) only where it is needed: at a connect or a disconnect, and at
 * the end for a flow still connected. Every other record only moves the run's end so far, kept as
 * its digits (compared as text: a live Monitor feeds every line here, and a BigInt per line cost
 * it 0.1 µs a record).
 */
import { durationText } from './duration-text.js';
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';
import { SupervisorFlowUse, type SupervisorFlow } from './supervisor-flow-use.js';

/** A data flow is told only when connected this long in all (its connections summed): 1 s. */
export const SILENT_FLOW_MIN_NS = 1_000_000_000;
/** A flow that delivered fewer than one value for this many of its reader's releases (its `* k` taken into account) is told as sparse. */
export const SPARSE_FLOW_RATIO = 10;
/** Flows followed at most (a forged log naming a million flows does not grow the story's memory). */
const FLOWS_FOLLOWED = 4096;
/** What a simulation's trace says instead of its flows' findings (simulated()). */
export const SIMULATED_FLOWS_WHY = 'a simulation runs no module code: data values are not simulated, nor the events its modules post';
/** Schemas named for one flow at most. */
const SCHEMAS_NAMED = 4;

interface FlowUse {
    producer: string;
    port: string;
    consumer: string;
    toPort: string;
    periodicity: number;
    schemas: string[];
    /** Connected since (the connect record's time), undefined while disconnected. */
    since?: bigint;
    connectedNs: number;
    posted: number;
    received: number;
    consumerReleases: number;
}

/** `1 value`, `2 values`. */
function plural(n: number, one: string, many = `${one}s`): string {
    return `${n} ${n === 1 ? one : many}`;
}

/** `1.7 a second` for n in ns. */
function rate(n: number, ns: number): string {
    return `${+(n / (ns / 1e9)).toPrecision(2)} a second`;
}

export class DataFlowUse {
    /** `A:p -> B:i` -> its use. */
    private readonly flows = new Map<string, FlowUse>();
    /** `A -> B:i` (what a data_received record names: its producer, not the producer's port) -> the flow. */
    private readonly byReading = new Map<string, FlowUse>();
    /** Consumer -> the flows into it (ORD's releases of it are counted for each while connected). */
    private readonly byConsumer = new Map<string, FlowUse[]>();
    /** Flows connected since ORD's last activation: that activation names their schema. */
    private pending: FlowUse[] = [];
    /** The latest record's time, its digits (laterTime): a flow still connected at the end counts up to it. */
    private lastMono: string | undefined;
    /** The event flows supervisors connected. */
    private readonly bySupervisors = new SupervisorFlowUse();
    /** The records are a simulation's (its `sim_start`): no flow's use is told (module code never ran). */
    private simulation = false;

    /** The records are a simulation's: what its flows delivered is not told as a finding (lines, counts). */
    simulated(): void {
        this.simulation = true;
    }

    /** Follows one record (any kind: its time is the run's end so far). */
    see(k: KnownRecord): void {
        this.seeTime(k.monoNs);
        this.seeFlow(k);
    }

    /** A record's time, its mono_ns digits: the run's end so far when later than any before. */
    seeTime(mono: string): void {
        if (this.lastMono === undefined || laterTime(mono, this.lastMono)) this.lastMono = mono;
    }

    /** What one record does to the flows, its time left to seeTime (read here only at a connect or a disconnect). */
    seeFlow(k: KnownRecord): void {
        if (k.kind === 'scheduler' && k.module === 'ORD') this.scheduler(k);
        else if (k.kind === 'supervisor' && k.module !== 'ORD') this.bySupervisors.supervisorLine(k);
        else if (k.kind === 'event_posted') this.bySupervisors.posted(k);
        else if (k.kind === 'event_received') this.bySupervisors.received(k);
        else if (k.kind === 'data_posted') {
            const f = this.flows.get(`${k.module}:${k.port ?? '?'} -> ${k.peer}:${String(k.fields['to_port'] ?? '?')}`);
            if (f?.since !== undefined) f.posted++;
        } else if (k.kind === 'data_received') {
            const f = this.byReading.get(`${k.peer} -> ${k.module}:${k.port ?? '?'}`);
            if (f?.since !== undefined) f.received++;
        } else if (k.kind === 'ord_release') {
            for (const f of this.byConsumer.get(k.peer) ?? []) if (f.since !== undefined) f.consumerReleases++;
        }
    }

    private scheduler(k: KnownRecord): void {
        const what = k.fields['what'];
        if (what === 'activate') {
            const schema = String(k.fields['schema'] ?? '');
            for (const f of this.pending) if (schema && !f.schemas.includes(schema) && f.schemas.length < SCHEMAS_NAMED) f.schemas.push(ownString(schema));
            this.pending = [];
            return;
        }
        if (what !== 'connect' && what !== 'disconnect') return;
        const producer = String(k.fields['module'] ?? ''), port = String(k.fields['port'] ?? ''), consumer = String(k.fields['to_module'] ?? ''), toPort = String(k.fields['to_port'] ?? '');
        const name = `${producer}:${port} -> ${consumer}:${toPort}`;
        let f = this.flows.get(name);
        if (what === 'disconnect') {
            if (f?.since !== undefined) {
                f.connectedNs += Number(BigInt(k.monoNs) - f.since);
                f.since = undefined;
            }
            return;
        }
        if (!f) {
            if (this.flows.size >= FLOWS_FOLLOWED) return;
            f = { producer: ownString(producer), port: ownString(port), consumer: ownString(consumer), toPort: ownString(toPort), periodicity: 1, schemas: [], connectedNs: 0, posted: 0, received: 0, consumerReleases: 0 };
            this.flows.set(ownString(name), f);
            this.byReading.set(ownString(`${producer} -> ${consumer}:${toPort}`), f);
            const into = this.byConsumer.get(consumer);
            if (into) into.push(f);
            else this.byConsumer.set(f.consumer, [f]);
        }
        const k0 = k.fields['periodicity'];
        f.periodicity = typeof k0 === 'number' && Number.isSafeInteger(k0) && k0 > 0 ? k0 : 1;
        f.since ??= BigInt(k.monoNs);
        if (this.pending.length < FLOWS_FOLLOWED) this.pending.push(f);
    }

    /** How long the flow was connected in all, up to the run's last record for a flow still connected. */
    private connectedNs(f: FlowUse | SupervisorFlow): number {
        return f.connectedNs + (f.since !== undefined && this.lastMono !== undefined ? Number(BigInt(this.lastMono) - f.since) : 0);
    }

    /** Whether an event flow a supervisor connected, connected long enough, delivered nothing or had nothing taken. */
    private silentEvents(f: SupervisorFlow): boolean {
        return this.connectedNs(f) >= SILENT_FLOW_MIN_NS && (f.posted === 0 || f.received === 0);
    }

    /** Whether the flow, connected long enough, delivered nothing or had nothing read. */
    private silent(f: FlowUse): boolean {
        return this.connectedNs(f) >= SILENT_FLOW_MIN_NS && (f.posted === 0 || f.received === 0);
    }

    /** Whether the flow, connected long enough, delivered fewer than one value for SPARSE_FLOW_RATIO of its reader's releases. */
    private sparse(f: FlowUse): boolean {
        return this.connectedNs(f) >= SILENT_FLOW_MIN_NS && !this.silent(f) && f.consumerReleases >= SPARSE_FLOW_RATIO &&
            f.posted * f.periodicity * SPARSE_FLOW_RATIO <= f.consumerReleases;
    }

    /** Flows that delivered nothing, and flows far sparser than their reader: the line of counts. */
    get counts(): { silent: number; sparse: number; silentEvents: number } {
        if (this.simulation) return { silent: 0, sparse: 0, silentEvents: 0 };
        return this.foundCounts();
    }

    /** The flows the findings would tell, a simulation's too. */
    private foundCounts(): { silent: number; sparse: number; silentEvents: number } {
        let silent = 0, sparse = 0, silentEvents = 0;
        for (const f of this.flows.values()) {
            if (this.silent(f)) silent++;
            else if (this.sparse(f)) sparse++;
        }
        for (const f of this.bySupervisors.flows.values()) if (this.silentEvents(f)) silentEvents++;
        return { silent, sparse, silentEvents };
    }

    /** One line per data flow told (silent, then sparse), in flow order, at the story's end. */
    lines(): string[] {
        if (this.simulation) return this.simulatedLines();
        const out: string[] = [];
        for (const [name, f] of [...this.flows].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0))) {
            const ns = this.connectedNs(f);
            const head = `data flow ${name} connected for ${durationText(ns)}${f.schemas.length ? ` (schema ${f.schemas.join(', ')})` : ''}: `;
            const releases = plural(f.consumerReleases, 'release');
            if (this.silent(f) && f.posted === 0) {
                out.push(`${head}0 values delivered (${f.producer} posted none on its output :${f.port}); ${f.consumer} read nothing` +
                    `${f.consumerReleases ? ` in its ${releases}` : ''}`);
            } else if (this.silent(f)) {
                out.push(`${head}${plural(f.posted, 'value')} posted, none read (${f.consumer} never read its input :${f.toPort}: GetData or GetLatestData` +
                    `${f.consumerReleases ? `, in its ${releases}` : ''})`);
            } else if (this.sparse(f)) {
                out.push(`${head}${plural(f.posted, 'value')} delivered (${rate(f.posted, ns)}${f.periodicity > 1 ? `, every ${f.periodicity}th value` : ''}), ` +
                    `read ${plural(f.received, 'time')} in ${f.consumer}'s ${releases} (${rate(f.consumerReleases, ns)}): ` +
                    `1 value for ${Math.round(f.consumerReleases / Math.max(f.posted, 1))} releases`);
            }
        }
        return [...out, ...this.eventLines()];
    }

    /**
     * A simulation's: no finding, but, when there would be some, one line saying why none is made:
     * `a simulation runs no module code: data values are not simulated, nor the events its modules
     * post: what 2 data flows and 1 event flow connected over 1 s delivered is not told`.
     */
    private simulatedLines(): string[] {
        const { silent, sparse, silentEvents } = this.foundCounts();
        const data = silent + sparse;
        if (!data && !silentEvents) return [];
        const flows = [...(data ? [plural(data, 'data flow')] : []), ...(silentEvents ? [plural(silentEvents, 'event flow')] : [])].join(' and ');
        return [`${SIMULATED_FLOWS_WHY}: what ${flows} connected over ${durationText(SILENT_FLOW_MIN_NS)} delivered is not told`];
    }

    /** One line per event flow a supervisor connected that delivered nothing, in flow order. */
    private eventLines(): string[] {
        const out: string[] = [];
        for (const f of [...this.bySupervisors.flows.values()].filter((g) => this.silentEvents(g))) {
            const name = `${f.producer}:${f.port} ${f.arrow} ${f.consumer}:${f.toPort}`;
            const who = [...(f.schemas.length ? [`schema ${f.schemas.join(', ')}`] : []), `connected by ${f.connectedBy.join(', ')}`].join(', ');
            const head = `event flow ${name} connected for ${durationText(this.connectedNs(f))} (${who}): `;
            out.push(f.posted === 0
                ? `${head}0 events delivered (${f.producer} posted none on its output :${f.port}); ${f.consumer} received nothing`
                : `${head}${plural(f.posted, 'event')} posted, none taken (${f.consumer} never took one from its input :${f.toPort}: GetEventId)`);
        }
        return out.sort();
    }
}

/** Whether mono_ns digits `a` are a later time than `b`: more digits, or as many and greater (read as numbers when one has leading zeros, which a forged line may). */
function laterTime(a: string, b: string): boolean {
    if (a.charCodeAt(0) === 48 || b.charCodeAt(0) === 48) return BigInt(a) > BigInt(b);
    return a.length > b.length || (a.length === b.length && a > b);
}
