/**
 * The event flows a supervisor connected (an event schema's `A:p =* B:i`, DataFlowUse's share of
 * them): from the supervisor's action lines `connect A:p =* B:i` (`=>` one shot) and `undo:
 * disconnect A:p =* B:i`, the `rule F.R active|inactive` line its actions follow (who connected it)
 * and its `activate schema S() (event schema)` line (the schema), A's `event_posted` and B's
 * `event_received` records while the flow is connected. A flow is one subscription at A whichever
 * supervisors connect it (docs/engines.md): it is connected from the first supervisor's connect to
 * the undo of the last one that holds it. Told with the rules of ORD's data flows (connected
 * SILENT_FLOW_MIN_NS in all, counted over the time connected), silent only (an asynchronous module
 * has no releases to compare a rate with):
 * - `event flow PRD:0 =* CNS:0 connected for 2.5 s (schema relay, connected by MIS's rule
 *   mission.RELAY): 0 events delivered (PRD posted none on its output :0); CNS received nothing`;
 * - `... : 3 events posted, none taken (CNS never took one from its input :0: GetEventId)`.
 * Bounded like DataFlowUse: at most FLOWS_FOLLOWED flows, a few names each.
 */
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** Flows followed at most (a forged log naming a million flows does not grow the story's memory). */
const FLOWS_FOLLOWED = 4096;
/** Connectors (`SUP's rule F.R`) and schemas named for one flow at most. */
const NAMED = 4;

/** A supervisor's context for its next actions: the rule whose change they follow, the event schema they activate. */
interface SupervisorContext {
    rule?: string;
    schema?: string;
}

export interface SupervisorFlow {
    producer: string;
    port: string;
    consumer: string;
    toPort: string;
    /** `=*`, or `=>` for a one-shot flow (as the last connect wrote it). */
    arrow: string;
    /** `MIS's rule mission.RELAY`, in connection order. */
    connectedBy: string[];
    schemas: string[];
    /** The supervisors holding it now: connected while any does. */
    holders: Set<string>;
    /** Connected since (the first holder's connect record's time), undefined while disconnected. */
    since?: bigint;
    connectedNs: number;
    posted: number;
    received: number;
}

export class SupervisorFlowUse {
    /** `A:p>B:i` (whichever arrow) -> its use. */
    readonly flows = new Map<string, SupervisorFlow>();
    private readonly contexts = new Map<string, SupervisorContext>();

    /** A supervisor's record (its rule lines, event schema activations, connects and disconnects). */
    supervisorLine(k: KnownRecord): void {
        const what = k.fields['what'];
        if (what === 'rule' || what === 'function_stopped') {
            const c = this.context(k.module);
            if (!c) return;
            c.rule = what === 'rule' ? ownString(`${String(k.fields['function'])}.${String(k.fields['rule'])}`) : undefined;
            c.schema = undefined;
            return;
        }
        if (what !== 'action') return;
        const action = k.fields['action'];
        if (action === undefined && k.detail.startsWith('activate schema ') && k.detail.endsWith(' (event schema)')) {
            const c = this.context(k.module);
            if (c) c.schema = ownString(String(k.fields['schema'] ?? ''));
            return;
        }
        if (action !== 'connect' && action !== 'disconnect') return;
        const producer = String(k.fields['module'] ?? ''), port = String(k.fields['port'] ?? ''), consumer = String(k.fields['to_module'] ?? ''), toPort = String(k.fields['to_port'] ?? '');
        const key = `${producer}:${port}>${consumer}:${toPort}`;
        let f = this.flows.get(key);
        if (action === 'disconnect') {
            if (!f?.holders.delete(k.module) || f.holders.size > 0 || f.since === undefined) return;
            f.connectedNs += Number(BigInt(k.monoNs) - f.since);
            f.since = undefined;
            return;
        }
        if (!f) {
            if (this.flows.size >= FLOWS_FOLLOWED) return;
            f = { producer: ownString(producer), port: ownString(port), consumer: ownString(consumer), toPort: ownString(toPort), arrow: '=*', connectedBy: [], schemas: [], holders: new Set(), connectedNs: 0, posted: 0, received: 0 };
            this.flows.set(ownString(key), f);
        }
        f.arrow = k.detail.includes(' => ') ? '=>' : '=*';
        const c = this.contexts.get(k.module);
        const by = ownString(c?.rule ? `${k.module}'s rule ${c.rule}` : k.module);
        if (!f.connectedBy.includes(by) && f.connectedBy.length < NAMED) f.connectedBy.push(by);
        if (c?.schema && !f.schemas.includes(c.schema) && f.schemas.length < NAMED) f.schemas.push(c.schema);
        if (f.holders.size < NAMED * 64) f.holders.add(ownString(k.module));
        f.since ??= BigInt(k.monoNs);
    }

    /** A producer's `event_posted` record (one that failed delivered nothing). */
    posted(k: KnownRecord): void {
        if (k.peer === '' || k.detail.endsWith(' failed')) return;
        const f = this.flows.get(`${k.module}:${k.port ?? '?'}>${k.peer}:${String(k.fields['to_port'] ?? '?')}`);
        if (f?.since !== undefined) f.posted++;
    }

    /** A consumer's `event_received` record (peer = the producer, port = its input, from_port = the producer's port). */
    received(k: KnownRecord): void {
        if (this.flows.size === 0) return;
        const f = this.flows.get(`${k.peer}:${String(k.fields['from_port'] ?? '?')}>${k.module}:${k.port ?? '?'}`);
        if (f?.since !== undefined) f.received++;
    }

    private context(supervisor: string): SupervisorContext | undefined {
        let c = this.contexts.get(supervisor);
        if (!c && this.contexts.size < FLOWS_FOLLOWED) this.contexts.set(ownString(supervisor), (c = {}));
        return c;
    }
}
