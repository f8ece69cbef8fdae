/**
 * When rules of a supervision function are active, as far as the rules alone tell
 * (docs/semantics.md "Supervisors: event order"). A rule's undo runs when it becomes inactive,
 * before its `endof(L)` is queued: `started(L)` without persistence finds L active (its actions have
 * just run), `endof(L)` without persistence finds it inactive (its schemas deactivated, its
 * subscriptions cancelled). The warnings about things two rules do at the same time use these:
 * supervisor-schema-conflict (rules certainly active together: schema-conflicts.ts) and
 * supervisor-subscribe-conflict (rules that may be: all but those never active together).
 */
import { AstUtils } from 'langium';
import { isDurationEvent, isElapsedEvent, isEndofEvent, isStartedEvent, isSupervisionFunction, type Event, type Rule, type SupervisionFunction } from '../generated/ast.js';
import { rulesOf } from './blocks.js';
import { RulesAfterEnd } from './rule-after-end.js';
import { RuleTurns } from './rule-turns.js';

/**
 * The rule L of a `started(L)` (kind 'started') or `endof(L)` ('endof') without persistence: the
 * event is present only while it is processed, right after L became active (started) or inactive
 * (endof).
 */
export function transientRuleEvent(event: Event, kind: 'started' | 'endof'): Rule | undefined {
    const matches = kind === 'started' ? isStartedEvent(event) : isEndofEvent(event);
    return matches ? transientRuleOf(event) : undefined;
}

/** The rule of a transient started/endof/duration event: it occurs once per activation of that rule. */
function transientRuleOf(e: Event): Rule | undefined {
    return !e.persistence && (isEndofEvent(e) || isStartedEvent(e) || isDurationEvent(e)) ? e.rule?.ref : undefined;
}

/**
 * Whether `rule` can become active a bounded number of times only in a run of its function (with
 * `single`: once at most): each precondition clause (with `single`: its one clause) needs a
 * transient event that occurs a bounded number of times (once at most): an `elapsed=t`, or an
 * endof/started/duration of such a rule. A module event, a persistence, or a cycle of rules (R1 on
 * endof(R6), ..., R6 on endof(R5)) makes it recur. Decided for every rule of the function at once
 * (limitedRules) and kept per function: a rule's events name rules of its own function only, so
 * the answers hold as long as its syntax tree does.
 */
function limitedActivations(rule: Rule, single: boolean): boolean {
    const fn = AstUtils.getContainerOfType(rule, isSupervisionFunction);
    if (!fn) return limitedRules([rule], single).has(rule);
    let known = limitedByFunction.get(fn);
    if (!known) limitedByFunction.set(fn, known = {});
    const set = single ? (known.once ??= limitedRules(rulesOf(fn), true)) : (known.bounded ??= limitedRules(rulesOf(fn), false));
    return set.has(rule);
}

const limitedByFunction = new WeakMap<SupervisionFunction, { once?: Set<Rule>; bounded?: Set<Rule> }>();

/** `rule` becomes active a bounded number of times in a run of its function (`[elapsed=1ms or elapsed=5s]`: twice at most). */
export function activationsBounded(rule: Rule): boolean {
    return limitedActivations(rule, false);
}

/** `rule` becomes active once at most in a run of its function. */
export function activeAtMostOnce(rule: Rule): boolean {
    return limitedActivations(rule, true);
}

/**
 * The rules of `rules` that become active a bounded number of times (with `single`: once at most)
 * in a run of their function, for all of them in one pass: the
 * least set closed under its rule (a rule joins once each of its clauses, with `single` its one
 * clause, has an event that occurs a bounded number of times), grown from the `elapsed=t` clauses
 * through the rules whose clauses wait for the events of rules that joined.
 */
function limitedRules(rules: readonly Rule[], single: boolean): Set<Rule> {
    const limited = new Set<Rule>();
    const left = new Map<Rule, number>(); // rule -> its clauses not yet shown to occur a bounded number of times
    const firstClause = new Map<Rule, number>(); // rule -> the number of its first clause among all
    const shown = new Set<number>();
    const waiters = new Map<Rule, Array<{ rule: Rule; clause: number }>>(); // X -> clauses with a transient event of X
    const queue: Rule[] = [];
    const show = (rule: Rule, clause: number) => {
        const id = firstClause.get(rule)! + clause;
        if (shown.has(id)) return;
        shown.add(id);
        const remaining = left.get(rule)! - 1;
        left.set(rule, remaining);
        if (remaining === 0) {
            limited.add(rule);
            queue.push(rule);
        }
    };
    let count = 0;
    for (const rule of rules) {
        const clauses = rule.precondition?.clauses ?? [];
        firstClause.set(rule, count);
        count += clauses.length;
        if (clauses.length === 0 || (single && clauses.length !== 1)) continue;
        left.set(rule, clauses.length);
        clauses.forEach((c, clause) => {
            for (const e of c.events) {
                const other = transientRuleOf(e);
                if (!other || other === rule) continue;
                const list = waiters.get(other) ?? [];
                list.push({ rule, clause });
                waiters.set(other, list);
            }
        });
    }
    for (const rule of left.keys()) {
        (rule.precondition?.clauses ?? []).forEach((c, clause) => {
            if (c.events.some((e) => isElapsedEvent(e) && !e.persistence)) show(rule, clause);
        });
    }
    while (queue.length > 0) {
        for (const w of waiters.get(queue.pop()!) ?? []) if (left.has(w.rule)) show(w.rule, w.clause);
    }
    return limited;
}

/**
 * Which rules of one supervision function are never active at the same time (`neverActiveTogether`),
 * decided for the whole function at once (the checks ask it about many pairs: each answer then
 * takes a few steps, not a walk through the rules). Rules of different functions, which may run at
 * once, are never said to be.
 */
export class RuleOverlap {
    /** Per rule of the function: what the pair questions read, in one record (one lookup per rule). */
    private readonly info = new Map<Rule, RuleFacts>();
    private readonly turns: RuleTurns;

    constructor(fn: SupervisionFunction) {
        const rules = rulesOf(fn);
        const once = new Set(rules.filter(activeAtMostOnce));
        const afterEnd = new RulesAfterEnd(rules);
        const intervals = afterEnd.intervals();
        const occursOnce = (e: Event): boolean => {
            if (e.persistence) return false;
            if (isElapsedEvent(e)) return true;
            const other = transientRuleOf(e);
            return other !== undefined && once.has(other);
        };
        this.turns = new RuleTurns(rules, occursOnce);
        for (const rule of rules) {
            const own = intervals.get(rule)!;
            const head = afterEnd.headOf(rule);
            const ended = head ? intervals.get(head)! : undefined;
            this.info.set(rule, { once: once.has(rule), enter: own.enter, leave: own.leave, endedEnter: ended?.enter ?? -1, endedLeave: ended?.leave ?? -1, turn: this.turns.turnKey(rule) });
        }
    }

    /** Whether `a` and `b` are never active at the same time (neverActiveTogether, without its reason). */
    apart(a: Rule, b: Rule): boolean {
        const x = this.info.get(a);
        const y = this.info.get(b);
        if (!x || !y || a === b) return false;
        return (x.once && endsBefore(x, y)) || (y.once && endsBefore(y, x)) || (x.turn !== undefined && x.turn === y.turn);
    }

    /**
     * Why `a` and `b` are never active at the same time, or undefined when the rules do not tell:
     * one becomes active once at most, and the other only after its end (on its transient endof, or
     * through a chain of rules that start so: `LAND: [endof(HOLD)]`, `TAXI: [endof(LAND)]` after
     * `HOLD: [elapsed=2ms]`: rule-after-end.ts); or they take turns that only one event, occurring
     * once at most, starts (`A: [elapsed=1ms or endof(B)]`, `B: [endof(A)]`: rule-turns.ts).
     */
    neverActiveTogether(a: Rule, b: Rule): string | undefined {
        if (!this.apart(a, b)) return undefined;
        const x = this.info.get(a)!;
        const y = this.info.get(b)!;
        if (x.once && endsBefore(x, y)) return `${a.name} becomes active once at most, and ${b.name} only after it ended`;
        if (y.once && endsBefore(y, x)) return `${b.name} becomes active once at most, and ${a.name} only after it ended`;
        return this.turns.neverTogether(a, b);
    }

    /** What the pair questions read of `rule` (undefined for a rule of another function): for indexes over many rules (first-overlapping.ts). */
    factsOf(rule: Rule): Readonly<RuleFacts> | undefined {
        return this.info.get(rule);
    }

    /** For two rules that may be active together but take turns: what lets them overlap (rule-turns.ts). */
    whyTurnsOverlap(a: Rule, b: Rule): string | undefined {
        if (a === b || !this.info.has(a) || !this.info.has(b)) return undefined;
        return this.turns.mayOverlap(a, b);
    }
}

/** What `apart` reads of one rule: `a` and `b` are apart when one is `once` and ends before the other (endsBefore), or they share a `turn`. */
export interface RuleFacts {
    once: boolean;
    /** The rule's interval in the walk of the ended-tree (rule-after-end.ts). */
    enter: number;
    leave: number;
    /** The interval of the first rule of ended(rule); -1: none ends before its activations. */
    endedEnter: number;
    endedLeave: number;
    /** Its turn when the turn keeps its rules apart (rule-turns.ts). */
    turn: object | undefined;
}

/** Whether `earlier`'s end precedes every activation of `later`: earlier is the first rule of ended(later) or one of its ancestors. */
function endsBefore(earlier: RuleFacts, later: RuleFacts): boolean {
    return later.endedEnter >= 0 && earlier.enter <= later.endedEnter && later.endedLeave <= earlier.leave;
}
