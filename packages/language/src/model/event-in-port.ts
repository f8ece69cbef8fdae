/**
 * The supervisor input port a module event of a rule waits on (docs/language-reference.md §6,
 * "Conditions"). `subscribe CTL:0 =* :2` delivers CTL's events into input port :2, and the engine
 * tells each delivery by the port it came in on. When a function subscribes one module port to
 * several input ports (`subscribe CTL:0 =* :2` in one rule, `subscribe CTL:0 =* :3` in another),
 * the input-port variables an event reads say which delivery it is: `CTL:0<status2 == "landed">`
 * waits for the one into status2's port. Validation warns from this, and code generation binds
 * the event's table (`.in_port`) with it, so that the check, the run and the simulator agree.
 */
import { AstUtils, type AstNode, type Reference } from 'langium';
import { isPort, isSubscribe, isSupervisionFunction, isSupervisor, isVariableRef, type ModuleEvent, type Port, type Subscribe, type SupervisionFunction, type VariableRef } from '../generated/ast.js';
import { rulesOf } from './blocks.js';

/** The supervisor input port a variable reference reads, if it reads one. */
export function inputPortRead(ref: VariableRef): Port | undefined {
    const variable = ref.variable?.ref;
    return isPort(variable) && variable.direction === 'in' && isSupervisor(variable.$container?.$container) ? variable : undefined;
}

/**
 * The function's subscribes by the text of the producer they name (`MAA:2`: the source's name and
 * the port's index as written), each list in written order, with what the last look-up found of
 * them; made once per function, in one pass over its rules (each module event scanned every rule
 * of the function: a 1,000-rule supervisor scanned a million actions). Kept per function: the
 * texts hold as long as its syntax tree does, while what they resolve to may change with other
 * files (a module file edited: the function is linked again, its tree kept), so a look-up reuses
 * what was found only for the same resolved source and port (`subscribesOf`).
 */
interface ProducerSubscribes {
    /** The function's subscribes naming the producer, as written. */
    named: Subscribe[];
    /** Those of them resolved to `source`:`port`, and the input ports they deliver into, each once. */
    found?: { source: AstNode; port: Port; subscribes: readonly Subscribe[]; delivered: readonly Port[] };
}

const subscribesByFunction = new WeakMap<SupervisionFunction, Map<string, ProducerSubscribes>>();

/** A producer's key: the two reference texts (a name and an index are resolved by their exact text). */
const producerText = (source: Reference | undefined, port: Reference | undefined): string => `${source?.$refText ?? ''}:${port?.$refText ?? ''}`;

function subscribesByProducer(fn: SupervisionFunction): Map<string, ProducerSubscribes> {
    let index = subscribesByFunction.get(fn);
    if (index) return index;
    index = new Map();
    for (const rule of rulesOf(fn)) {
        for (const a of rule.actions) {
            if (!isSubscribe(a)) continue;
            const key = producerText(a.source, a.sourcePort);
            const entry = index.get(key);
            if (entry) entry.named.push(a);
            else index.set(key, { named: [a] });
        }
    }
    subscribesByFunction.set(fn, index);
    return index;
}

const NOTHING_FOUND = { subscribes: [], delivered: [] } as const;

/** The subscribes of the event's function to its source port and the input ports they deliver into. */
function found(event: ModuleEvent): { subscribes: readonly Subscribe[]; delivered: readonly Port[] } {
    const source = event.source?.ref;
    const port = event.port?.ref;
    const fn = AstUtils.getContainerOfType(event, isSupervisionFunction);
    if (event.ord || !source || !port || !fn) return NOTHING_FOUND;
    const entry = subscribesByProducer(fn).get(producerText(event.source, event.port));
    if (!entry) return NOTHING_FOUND;
    if (entry.found?.source !== source || entry.found.port !== port) {
        const subscribes = entry.named.filter((a) => a.source?.ref === source && a.sourcePort?.ref === port);
        const delivered: Port[] = [];
        for (const a of subscribes) {
            const target = a.targetPort?.ref;
            if (target && !delivered.includes(target)) delivered.push(target);
        }
        entry.found = { source, port, subscribes, delivered };
    }
    return entry.found;
}

/**
 * The subscribes of the event's function to the event's source port, in written order (none for an
 * ORD event or an unresolved one): `supervisor-event-not-subscribed` when there is none.
 */
export function subscribesOf(event: ModuleEvent): readonly Subscribe[] {
    return found(event).subscribes;
}

/**
 * The supervisor input ports that the function's subscribes connect this event's source port to,
 * each once, in written order (none for an ORD event or an unresolved one).
 */
export function deliveredPorts(event: ModuleEvent): Port[] {
    return [...found(event).delivered];
}

/** The input ports whose variables the event's tests and its own extractions read, each once, in written order. */
function portsReadBy(event: ModuleEvent): Port[] {
    const ports: Port[] = [];
    const nodes = [...event.tests, ...event.extractions.flatMap((x) => (x.value ? [x.value] : []))];
    for (const root of nodes) {
        for (const node of [root, ...AstUtils.streamAllContents(root)]) {
            const port = isVariableRef(node) ? inputPortRead(node) : undefined;
            if (port && !ports.includes(port)) ports.push(port);
        }
    }
    return ports;
}

export interface EventInPort {
    /** The input ports the function's subscribes deliver the event's source port into. */
    delivered: Port[];
    /** Those of them whose variables the event's tests and extractions read. */
    read: Port[];
    /**
     * The one input port whose deliveries the event waits for: the only one delivered, or else the
     * only one of them it reads. Undefined: a delivery into any of them (it reads none of them, or
     * several: `ambiguous`), or none is delivered.
     */
    port: Port | undefined;
    /** It reads the variables of several ports it is delivered to: an occurrence writes one of them only. */
    ambiguous: boolean;
}

export function eventInPort(event: ModuleEvent): EventInPort {
    const delivered = deliveredPorts(event);
    const read = portsReadBy(event).filter((p) => delivered.includes(p));
    const port = delivered.length === 1 ? delivered[0] : read.length === 1 ? read[0] : undefined;
    return { delivered, read, port, ambiguous: delivered.length > 1 && read.length > 1 };
}
