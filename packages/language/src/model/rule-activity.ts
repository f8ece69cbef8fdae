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
 * endof(R6), ..., R6 on endof(R5)) makes it recur. `seen`: the rules being decided.
 */
function limitedActivations(rule: Rule, single: boolean, seen: Set<Rule>): boolean {
    if (seen.has(rule)) return false; // a cycle: each turn makes it active again
    seen.add(rule);
    const limited = (e: Event): boolean => {
        if (isElapsedEvent(e)) return !e.persistence;
        const other = transientRuleOf(e);
        return other !== undefined && limitedActivations(other, single, seen);
    };
    const clauses = rule.precondition?.clauses ?? [];
    const result = clauses.length > 0 && (!single || clauses.length === 1) && clauses.every((c) => c.events.some(limited));
    seen.delete(rule);
    return result;
}

/** `rule` becomes active a bounded number of times in a run of its function (`[elapsed=1ms or elapsed=5s]`: twice at most). */
export function activationsBounded(rule: Rule): boolean {
    return limitedActivations(rule, false, new Set());
}

/** `rule` becomes active once at most in a run of its function. */
export function activeAtMostOnce(rule: Rule): boolean {
    return limitedActivations(rule, true, new Set());
}

/**
 * Which rules of one supervision function are never active at the same time (`neverActiveTogether`),
 * its answers kept: the checks ask it about many pairs of one function. Rules of different
 * functions, which may run at once, are never said to be.
 */
export class RuleOverlap {
    private readonly once = new Map<Rule, boolean>();
    private readonly after = new Map<Rule, Set<Rule>>();
    /** For each rule X, the rules whose precondition has a transient started/endof/duration(X). */
    private readonly dependents = new Map<Rule, Rule[]>();

    constructor(private readonly fn: SupervisionFunction) {
        for (const rule of rulesOf(fn)) {
            for (const e of (rule.precondition?.clauses ?? []).flatMap((c) => c.events)) {
                const other = transientRuleOf(e);
                if (!other) continue;
                const list = this.dependents.get(other) ?? [];
                if (!list.includes(rule)) list.push(rule);
                this.dependents.set(other, list);
            }
        }
    }

    /**
     * Why `a` and `b` are never active at the same time, or undefined when the rules do not tell:
     * one becomes active once at most, and the other only after its end (on its transient endof, or
     * through a chain of rules that start so: `LAND: [endof(HOLD)]`, `TAXI: [endof(LAND)]` after
     * `HOLD: [elapsed=2ms]`).
     */
    neverActiveTogether(a: Rule, b: Rule): string | undefined {
        if (a === b || !this.owns(a) || !this.owns(b)) return undefined;
        for (const [earlier, later] of [[a, b], [b, a]] as const) {
            if (this.activeAtMostOnce(earlier) && this.startingAfterEndOf(earlier).has(later)) {
                return `${earlier.name} becomes active once at most, and ${later.name} only after it ended`;
            }
        }
        return undefined;
    }

    private owns(rule: Rule): boolean {
        return AstUtils.getContainerOfType(rule, isSupervisionFunction) === this.fn;
    }

    private activeAtMostOnce(rule: Rule): boolean {
        let known = this.once.get(rule);
        if (known === undefined) this.once.set(rule, known = activeAtMostOnce(rule));
        return known;
    }

    /**
     * The rules that become active only after `earlier` has become inactive: each of their
     * precondition clauses waits for a transient endof(earlier), or for a transient
     * started/endof/duration of a rule that itself starts so. The least such set (a cycle proves
     * nothing), grown from endof(earlier)'s rules through the dependents.
     */
    private startingAfterEndOf(earlier: Rule): Set<Rule> {
        const known = this.after.get(earlier);
        if (known) return known;
        const found = new Set<Rule>();
        const waits = (e: Event) => {
            if (transientRuleEvent(e, 'endof') === earlier) return true;
            const other = transientRuleOf(e); // started/duration(earlier) occur while it is active
            return other !== undefined && other !== earlier && found.has(other);
        };
        const queue = [...(this.dependents.get(earlier) ?? [])];
        while (queue.length > 0) {
            const rule = queue.pop()!;
            if (rule === earlier || found.has(rule)) continue;
            const clauses = rule.precondition?.clauses ?? [];
            if (clauses.length === 0 || !clauses.every((c) => c.events.some(waits))) continue;
            found.add(rule);
            queue.push(...(this.dependents.get(rule) ?? []));
        }
        this.after.set(earlier, found);
        return found;
    }
}
