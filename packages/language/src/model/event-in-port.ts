/**
 * The supervisor input port a module event of a rule waits on (docs/language-reference.md §6,
 * "Conditions"). `subscribe CTL:0 =* :2` delivers CTL's events into input port :2, and the engine
 * tells each delivery by the port it came in on. When a function subscribes one module port to
 * several input ports (`subscribe CTL:0 =* :2` in one rule, `subscribe CTL:0 =* :3` in another),
 * the input-port variables an event reads say which delivery it is: `CTL:0<status2 == "landed">`
 * waits for the one into status2's port. Validation warns from this, and code generation binds
 * the event's table (`.in_port`) with it, so that the check, the run and the simulator agree.
 */
import { AstUtils } from 'langium';
import { isPort, isSubscribe, isSupervisionFunction, isSupervisor, isVariableRef, type ModuleEvent, type Port, type VariableRef } from '../generated/ast.js';
import { rulesOf } from './blocks.js';

/** The supervisor input port a variable reference reads, if it reads one. */
export function inputPortRead(ref: VariableRef): Port | undefined {
    const variable = ref.variable?.ref;
    return isPort(variable) && variable.direction === 'in' && isSupervisor(variable.$container?.$container) ? variable : undefined;
}

/**
 * The supervisor input ports that the function's subscribes connect this event's source port to,
 * each once, in written order (none for an ORD event or an unresolved one).
 */
export function deliveredPorts(event: ModuleEvent): Port[] {
    const ports: Port[] = [];
    const source = event.source?.ref;
    const port = event.port?.ref;
    const fn = AstUtils.getContainerOfType(event, isSupervisionFunction);
    if (event.ord || !source || !port || !fn) return ports;
    for (const rule of rulesOf(fn)) {
        for (const a of rule.actions) {
            const target = isSubscribe(a) && a.source?.ref === source && a.sourcePort?.ref === port ? a.targetPort?.ref : undefined;
            if (target && !ports.includes(target)) ports.push(target);
        }
    }
    return ports;
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
