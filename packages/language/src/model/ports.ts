/**
 * Ports by index. Cactal refers to ports by number in the context of their owner and kind:
 * `MSC:1 -> MSD:2` names MSC's output data port 1 and MSD's input data port 2; `subscribe MAA:2 =* :2`
 * names MAA's output event port 2 and the supervisor's own input event port 2; `(v :0)` names
 * parameter port 0. The scope provider and code generation both use these helpers.
 */
import { isDataFlowsBlock, type Module, type Parameter, type Port, type Supervisor } from '../generated/ast.js';
import { dataPortsOf, eventPortsOf, parametersOf } from './blocks.js';

export type PortKind = 'data' | 'event';
export type PortDirection = 'in' | 'out';

/** A port with its kind (from its block) and direction. */
export interface PortInfo {
    port: Port;
    kind: PortKind;
    direction: PortDirection;
    index: number;
}

/** The kind of a port: `data` in a `data flows` block, `event` in an `event flows` block. */
export function portKind(port: Port): PortKind {
    return isDataFlowsBlock(port.$container) ? 'data' : 'event';
}

/** Every port of a module or supervisor, in declaration order. */
export function portsOf(owner: Module | Supervisor): PortInfo[] {
    const ports = owner.$type === 'Module' ? [...dataPortsOf(owner), ...eventPortsOf(owner)] : eventPortsOf(owner);
    return ports.map((port) => ({ port, kind: portKind(port), direction: port.direction, index: port.index }));
}

/** The ports of an owner with the given kind and direction. */
export function portsOfKind(owner: Module | Supervisor, kind: PortKind, direction: PortDirection): Port[] {
    return portsOf(owner).filter((p) => p.kind === kind && p.direction === direction).map((p) => p.port);
}

/** The port `index` of the given kind and direction (the first one if the index is duplicated). */
export function resolvePort(owner: Module | Supervisor, index: number, kind: PortKind, direction: PortDirection): Port | undefined {
    return portsOfKind(owner, kind, direction).find((p) => p.index === index);
}

/** The parameter port `index` of a module. */
export function resolveParameter(module: Module, index: number): Parameter | undefined {
    return parametersOf(module).find((p) => p.index === index);
}
