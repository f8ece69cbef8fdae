/**
 * Periodic schemas that share a module, and the rules of a supervision function that become
 * active together. ORD refuses to activate a periodic schema that shares a module with an active
 * one and emits `ORD:1` (docs/engines.md, "ORD"); these pure functions let validation warn when
 * that refusal is certain, and hover list a schema's conflicts.
 */
import {
    isDurationEvent, isElapsedEvent, isEndofEvent, isModuleEvent, isStartedEvent,
    type Clause, type Event, type Module, type Rule, type Schema, type SupervisionFunction
} from '../generated/ast.js';
import { moduleInstancesOf, rulesOf } from './blocks.js';
import { transientRuleEvent } from './rule-activity.js';
import { timeToNanoseconds } from './time.js';

/** The resolved modules of a schema, each once, in written order. */
function modulesOf(schema: Schema): Module[] {
    const modules: Module[] = [];
    for (const instance of moduleInstancesOf(schema)) {
        const m = instance.module?.ref;
        if (m && !modules.includes(m)) modules.push(m);
    }
    return modules;
}

/**
 * The modules two periodic schemas share (in `a`'s order); empty when either is an event schema:
 * event schemas are run by the supervisor engine, which shares modules between them
 * (docs/engines.md). A schema shares all its modules with itself: ORD refuses a second
 * activation of an active schema too.
 */
export function sharedModules(a: Schema, b: Schema): Module[] {
    if (a.kind !== 'periodic' || b.kind !== 'periodic') return [];
    const other = modulesOf(b);
    return modulesOf(a).filter((m) => other.includes(m));
}

/** Why two rules are active together: `A` starts on started(B), or both start on one event. */
export interface Together {
    rule: Rule;
    reason: string;
}

/**
 * A key for the event of a one-event clause: two preconditions with such a clause of the same key
 * become true on the same occurrence. Module events with tests only match the same written tests.
 */
function eventKey(event: Event): string | undefined {
    if (isStartedEvent(event)) return event.rule?.ref ? `started(${event.rule.ref.name})` : undefined;
    if (isEndofEvent(event)) return event.rule?.ref ? `endof(${event.rule.ref.name})` : undefined;
    if (isDurationEvent(event)) return event.rule?.ref && event.time ? `duration(${event.rule.ref.name})=${timeToNanoseconds(event.time.text)}ns` : undefined;
    if (isElapsedEvent(event)) return event.time ? `elapsed=${timeToNanoseconds(event.time.text)}ns` : undefined;
    if (isModuleEvent(event)) {
        const source = event.ord ? `ORD:${event.ordPort}` : event.source?.ref && event.port?.ref ? `${event.source.ref.name}:${event.port.ref.index}` : undefined;
        const tests = event.tests.map((t) => (t.$cstNode?.text ?? '?').replace(/\s+/g, '')).join('|');
        return source && (tests ? `${source}<${tests}>` : source);
    }
    return undefined;
}

/** The written form of an event key for messages (`elapsed=1000000ns` reads as the source text). */
function eventText(event: Event): string {
    return (event.$cstNode?.text ?? '?').replace(/\s+/g, ' ');
}

/** Events of a precondition that start the rule alone (one-event clauses), by key. */
function startingEvents(rule: Rule): Map<string, Event> {
    const found = new Map<string, Event>();
    for (const clause of rule.precondition?.clauses ?? []) {
        if (clause.events.length !== 1) continue;
        const key = eventKey(clause.events[0]!);
        if (key && !found.has(key)) found.set(key, clause.events[0]!);
    }
    return found;
}

/**
 * Rules whose `started` without persistence appears in a clause of `rule`'s precondition: when
 * that clause becomes true, they have just been activated and are active (docs/engines.md:
 * `started(L)` is queued after L's actions). `endof(L)` does not count: L's schemas are
 * deactivated before `endof(L)` is queued, so a rule started by it never overlaps L
 * (rule-activity.ts: transientRuleEvent, RuleOverlap).
 */
function startedBy(rule: Rule): Rule[] {
    const clauses: Clause[] = rule.precondition?.clauses ?? [];
    const rules: Rule[] = [];
    for (const event of clauses.flatMap((c) => c.events)) {
        const other = transientRuleEvent(event, 'started');
        if (other && other !== rule && !rules.includes(other)) rules.push(other);
    }
    return rules;
}

/**
 * For each rule of the function, rules that become active with it, and why: `started(L)` in one's
 * precondition, or a one-event precondition clause on the same event. Direct links only; callers
 * follow them to the rules active together through a chain. Rules that start on one event are
 * linked to the first of them (a star, not every pair): the same groups in linear time and memory
 * (3,000 rules on `[elapsed=1ms]` took 155 s and 1.4 GB when every pair was linked).
 */
export function activeTogether(fn: SupervisionFunction): Map<Rule, Together[]> {
    const rules = rulesOf(fn);
    const links = new Map<Rule, Together[]>(rules.map((r) => [r, []]));
    const linked = new Map<Rule, Set<Rule>>(rules.map((r) => [r, new Set()]));
    const link = (a: Rule, b: Rule, reason: string) => {
        if (a === b || linked.get(a)?.has(b)) return;
        linked.get(a)?.add(b);
        linked.get(b)?.add(a);
        links.get(a)?.push({ rule: b, reason });
        links.get(b)?.push({ rule: a, reason });
    };
    for (const rule of rules) {
        for (const other of startedBy(rule)) {
            if (links.has(other)) link(rule, other, `${rule.name} becomes active on started(${other.name})`);
        }
    }
    // per starting event, the first rule (in declaration order) that starts on it
    const firstOn = new Map<string, { rule: Rule; event: Event }>();
    for (const rule of rules) {
        for (const [key, event] of startingEvents(rule)) {
            const first = firstOn.get(key);
            if (!first) firstOn.set(key, { rule, event });
            else link(first.rule, rule, `${first.rule.name} and ${rule.name} both become active on ${eventText(first.event)}`);
        }
    }
    return links;
}

/**
 * The rules reachable from `start` through the links, each with the chain of reasons that joins
 * it to `start` (`start` itself has none), in breadth-first order.
 */
export function groupOf(start: Rule, links: Map<Rule, Together[]>): Map<Rule, string[]> {
    const reached = new Map<Rule, string[]>([[start, []]]);
    const queue: Rule[] = [start];
    while (queue.length > 0) {
        const current = queue.shift()!;
        for (const next of links.get(current) ?? []) {
            if (reached.has(next.rule)) continue;
            reached.set(next.rule, [...reached.get(current)!, next.reason]);
            queue.push(next.rule);
        }
    }
    return reached;
}
