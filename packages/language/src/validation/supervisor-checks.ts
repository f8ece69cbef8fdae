/**
 * docs/language-reference.md §6, structure of supervisors: unique function, parameter, local and label names; one
 * producer per input event port across the supervisor's subscribes; no cycle of
 * `activate supervisor` between supervisors. Conditions are checked in supervisor-rule-checks.ts,
 * actions in supervisor-action-checks.ts.
 */
import { AstUtils, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isActivateSupervisor, isRule, isSubscribe, isSupervisor,
    type ActivateSupervisor, type CactalAstType, type Port, type Rule, type Subscribe, type SupervisionFunction, type Supervisor
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { eventPortsOf, localsOf, rulesOf } from '../model/blocks.js';
import { FirstOverlapping } from '../model/first-overlapping.js';
import { RuleOverlap } from '../model/rule-activity.js';
import { SupervisorCodes } from './codes/supervisors.js';
import { report } from './report.js';
import { NAME_CHARS_MAX } from './schema-checks.js';

export function supervisorChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    return {
        Supervisor: [checkFunctionNames, checkSubscribeConflicts],
        SupervisionFunction: [checkParameterNames, checkLocalNames, checkLabels],
        ActivateSupervisor: checkActivationCycle
    };
}

function checkFunctionNames(sup: Supervisor, accept: ValidationAcceptor): void {
    const seen = new Set<string>();
    for (const fn of sup.functions) {
        if (!fn.name) continue;
        if (fn.name.length > NAME_CHARS_MAX) {
            report(accept, SupervisorCodes['supervisor-function-name-too-long'],
                `Function name '${fn.name.slice(0, 20)}…' has ${fn.name.length} characters: at most ${NAME_CHARS_MAX} (a start request carries the name in 64 bytes).`,
                { node: fn, property: 'name' });
        }
        if (seen.has(fn.name)) {
            report(accept, SupervisorCodes['supervisor-function-duplicate'],
                `Supervisor ${sup.name} already has a function '${fn.name}': function names are unique within a supervisor.`,
                { node: fn, property: 'name' });
        }
        seen.add(fn.name);
    }
}

function checkParameterNames(fn: SupervisionFunction, accept: ValidationAcceptor): void {
    const seen = new Set<string>();
    for (const p of fn.parameters) {
        if (!p.name) continue;
        if (seen.has(p.name)) {
            report(accept, SupervisorCodes['supervisor-parameter-duplicate'],
                `Function ${fn.name} already has a parameter '${p.name}': parameters are set by name, each needs its own.`,
                { node: p, property: 'name' });
        }
        seen.add(p.name);
    }
}

function checkLocalNames(fn: SupervisionFunction, accept: ValidationAcceptor): void {
    const params = new Set(fn.parameters.map((p) => p.name));
    const sup = fn.$container;
    const ports = new Map<string, Port>();
    if (isSupervisor(sup)) for (const port of eventPortsOf(sup)) if (port.name) ports.set(port.name, port);
    const locals = new Set<string>();
    for (const local of localsOf(fn)) {
        const name = local.name;
        if (!name) continue;
        let clash: string | undefined;
        if (locals.has(name)) clash = `another local of ${fn.name}`;
        else if (params.has(name)) clash = `a parameter of ${fn.name}`;
        else if (ports.has(name)) clash = `the variable of ${ports.get(name)!.direction === 'in' ? 'input' : 'output'} event port :${ports.get(name)!.index} of ${isSupervisor(sup) ? sup.name : 'the supervisor'}`;
        if (clash) {
            report(accept, SupervisorCodes['supervisor-local-name-conflict'],
                `Local '${name}' has the name of ${clash}: a local's name differs from the other locals, the function's parameters and the supervisor's event-port variables.`,
                { node: local, property: 'name' });
        }
        locals.add(name);
    }
}

function checkLabels(fn: SupervisionFunction, accept: ValidationAcceptor): void {
    const seen = new Set<string>();
    for (const rule of rulesOf(fn)) {
        if (!rule.name) continue;
        if (seen.has(rule.name)) {
            report(accept, SupervisorCodes['supervisor-label-duplicate'],
                `Function ${fn.name} already has a rule labelled '${rule.name}': labels are unique within a function (started/endof/duration name them).`,
                { node: rule, property: 'name' });
        }
        seen.add(rule.name);
    }
}

/** Every subscribe action of a supervisor, in all its functions. */
function subscribesOf(sup: Supervisor): Subscribe[] {
    return sup.functions.flatMap((fn) => rulesOf(fn).flatMap((r) => r.actions.filter(isSubscribe)));
}

function producerKey(s: Subscribe): string | undefined {
    const source = s.source?.ref;
    const port = s.sourcePort?.ref;
    return source && port ? `${source.name}:${port.index}` : undefined;
}

/**
 * Two subscribes of the supervisor to one input port, in rules that may be active at once (any two
 * but those the rules show never are: rule-activity.ts RuleOverlap); each subscribe is
 * reported once, against the first earlier one its rule may be active with (found through an index
 * of each port's subscribes, first-overlapping.ts: asking of every earlier one was quadratic).
 */
function checkSubscribeConflicts(sup: Supervisor, accept: ValidationAcceptor): void {
    const overlaps = new Map<SupervisionFunction, RuleOverlap>(sup.functions.map((fn) => [fn, new RuleOverlap(fn)]));
    const overlap = (rule: Rule) => overlaps.get(rule.$container.$container);
    interface Entry { s: Subscribe; target: Port; key: string; rule: Rule | undefined; position: number }
    const entries: Entry[] = [];
    const onPort = new Map<Port, Entry[]>();
    for (const s of subscribesOf(sup)) {
        const target = s.targetPort?.ref;
        const key = producerKey(s);
        if (!target || !key) continue;
        const before = onPort.get(target) ?? [];
        const entry = { s, target, key, rule: AstUtils.getContainerOfType(s, isRule), position: before.length };
        before.push(entry);
        onPort.set(target, before);
        entries.push(entry);
    }
    const indexes = new Map([...onPort].map(([port, list]) => [port, new FirstOverlapping(list.map((e) => e.rule), overlap)]));
    for (const { s, target, key, rule, position } of entries) {
        const at = indexes.get(target)!.firstBefore(position);
        if (at === undefined) continue;
        const first = onPort.get(target)![at]!;
        const turns = rule && first.rule ? overlap(rule)?.whyTurnsOverlap(rule, first.rule) : undefined;
        const when = turns ? ` They may be active at once: ${turns}.` : '';
        // the same producer twice is refused at run time too (`port :i already subscribed`): one subscription at a time
        report(accept, SupervisorCodes['supervisor-subscribe-conflict'], first.key === key
            ? `Input event port :${target.index} (${target.name}) is also subscribed to ${key} by rule ${first.rule?.name ?? '?'}: an input port takes one subscribe at a time, the same producer's too (the second is refused while the first holds it: \`port :${target.index} already subscribed\`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.${when}`
            : `Input event port :${target.index} (${target.name}) is also subscribed to ${first.key} (rule ${first.rule?.name ?? '?'}): an input port has at most one producer at a time. Make sure these rules are never active at once, or use another input port for ${key}.${when}`,
            { node: s, property: 'targetPort' });
    }
}

/** Supervisors activated by `sup` (any function), in written order. */
function activatedBy(sup: Supervisor): Supervisor[] {
    const result: Supervisor[] = [];
    for (const node of AstUtils.streamAllContents(sup)) {
        if (isActivateSupervisor(node)) {
            const target = node.supervisor?.ref;
            if (target && !result.includes(target)) result.push(target);
        }
    }
    return result;
}

function checkActivationCycle(action: ActivateSupervisor, accept: ValidationAcceptor): void {
    const target = action.supervisor?.ref;
    const self = AstUtils.getContainerOfType(action, isSupervisor);
    if (!target || !self) return;
    // a path target -> ... -> self closes a cycle through this action
    const path: Supervisor[] = [];
    const visited = new Set<Supervisor>();
    const reach = (current: Supervisor): boolean => {
        path.push(current);
        if (current === self) return true;
        if (!visited.has(current)) {
            visited.add(current);
            for (const next of activatedBy(current)) if (reach(next)) return true;
        }
        path.pop();
        return false;
    };
    if (!reach(target)) return;
    const cycle = [self, ...path].map((s) => s.name).join(' -> ');
    report(accept, SupervisorCodes['supervisor-activation-cycle'],
        `Supervisors activate each other: ${cycle}. The supervisor hierarchy must be a tree or a DAG (a supervisor activates only supervisors below it).`,
        { node: action, property: 'supervisor' });
}
