/**
 * Rules of one supervision function that take turns (rule-activity.ts RuleOverlap): `A: [elapsed=1ms
 * or endof(B)]`, `B: [endof(A)]`, each starting on the end of another, the usual alternation.
 *
 * A turn is a set of rules linked by their precondition clauses whose one event without
 * persistence (clause-trigger.ts) is the `endof` of another rule of the set. Count its tokens: the
 * rules of the set that are active, and the `endof` of a rule of the set that are queued and not
 * yet processed (docs/semantics.md "Supervisors: event order", "actions and their undo"). A rule
 * of the set becoming inactive queues its endof (the count stays); a function end deactivates its
 * rules without endof (it drops). Processing an endof(S) consumes one; when S's endof starts one
 * rule of the set at most (S has one successor in the set), the count does not grow. Every other
 * activation of a rule of the set is on an entry: a clause of the set that does not wait for such
 * an endof. With one entry whose event occurs once at most in a run (`elapsed=t`, or the
 * started/endof/duration of a rule active once at most), and every other clause never true, the
 * count is at most 1: two rules of the turn are never active at once. With no entry at all, none
 * of them ever becomes active. Otherwise the turn does not tell, and `mayOverlap` says why.
 */
import { isEndofEvent, type Clause, type Event, type Rule } from '../generated/ast.js';
import { clauseTrigger } from './clause-trigger.js';

interface Turn {
    /** Why two rules of this turn are never active at once, or undefined when they may be. */
    never?: string;
    /** When they may be: what breaks the turn. */
    breaks?: string;
}

const text = (clause: Clause) => (clause.$cstNode?.text ?? '?').replace(/\s+/g, ' ');

export class RuleTurns {
    private readonly turnOf = new Map<Rule, Turn>();

    /** `occursOnce`: whether an event without persistence occurs once at most in a run of the function. */
    constructor(rules: readonly Rule[], occursOnce: (event: Event) => boolean) {
        const inFunction = new Set(rules);
        /** The rule S whose transient endof is the clause's one event without persistence. */
        const passedBy = (clause: Clause): Rule | undefined => {
            const trigger = clauseTrigger(clause);
            const event = trigger === 'never' ? undefined : trigger?.event;
            const other = event && isEndofEvent(event) ? event.rule?.ref : undefined;
            return other && inFunction.has(other) ? other : undefined;
        };
        // the turns: rules joined by such clauses (union-find)
        const up = new Map<Rule, Rule>();
        const find = (r: Rule): Rule => {
            let root = r;
            while (up.get(root) !== root) root = up.get(root)!;
            for (let x = r; x !== root;) { const next = up.get(x)!; up.set(x, root); x = next; }
            return root;
        };
        const linked = new Set<Rule>();
        for (const rule of rules) up.set(rule, rule);
        for (const rule of rules) {
            for (const clause of rule.precondition?.clauses ?? []) {
                const s = passedBy(clause);
                if (!s) continue;
                linked.add(s).add(rule);
                up.set(find(s), find(rule));
            }
        }
        const members = new Map<Rule, Rule[]>();
        for (const rule of rules) {
            if (!linked.has(rule)) continue;
            const root = find(rule);
            const list = members.get(root) ?? [];
            list.push(rule);
            members.set(root, list);
        }
        for (const group of members.values()) {
            const turn = judge(group, passedBy, occursOnce);
            for (const rule of group) this.turnOf.set(rule, turn);
        }
    }

    /** The turn of `rule` when it keeps its rules apart (the same object for each of them), else undefined. */
    turnKey(rule: Rule): object | undefined {
        const turn = this.turnOf.get(rule);
        return turn?.never ? turn : undefined;
    }

    /** Why `a` and `b` (two rules of the function) are never active at once as a turn, if they are. */
    neverTogether(a: Rule, b: Rule): string | undefined {
        const turn = this.turnOf.get(a);
        return turn && turn === this.turnOf.get(b) && turn.never ? `${a.name} and ${b.name} ${turn.never}` : undefined;
    }

    /** When `a` and `b` take turns that do not keep them apart: what breaks the turn. */
    mayOverlap(a: Rule, b: Rule): string | undefined {
        const turn = this.turnOf.get(a);
        return turn && turn === this.turnOf.get(b) && turn.breaks ? `${a.name} and ${b.name} take turns on the endof of another rule, but ${turn.breaks}` : undefined;
    }
}

function judge(group: Rule[], passedBy: (c: Clause) => Rule | undefined, occursOnce: (e: Event) => boolean): Turn {
    const inGroup = new Set(group);
    const successors = new Map<Rule, Rule[]>();
    const entries: Array<{ rule: Rule; clause?: Clause }> = []; // clause absent: a rule without precondition
    for (const rule of group) {
        for (const clause of rule.precondition?.clauses ?? []) {
            const s = passedBy(clause);
            if (s && inGroup.has(s)) {
                const list = successors.get(s) ?? [];
                if (!list.includes(rule)) list.push(rule);
                successors.set(s, list);
            } else if (clauseTrigger(clause) !== 'never') {
                entries.push({ rule, clause });
            }
        }
        if ((rule.precondition?.clauses ?? []).length === 0) entries.push({ rule });
    }
    for (const [s, next] of successors) {
        if (next.length > 1) return { breaks: `endof(${s.name}) starts ${next.length} of them (${next.map((r) => r.name).join(', ')})` };
    }
    if (entries.length > 1) {
        const shown = entries.slice(0, 3).map((e) => `${e.rule.name} on ${e.clause ? text(e.clause) : 'its start'}`).join(', ');
        return { breaks: `${entries.length} of their clauses start one otherwise, so one may start while another is active: ${shown}` };
    }
    if (entries.length === 0) return { never: 'take turns, each starting only on the endof of another, and none of their turn starts otherwise: none becomes active' };
    const entry = entries[0]!;
    const trigger = entry.clause ? clauseTrigger(entry.clause) : undefined;
    const event = trigger === 'never' ? undefined : trigger?.event;
    if (!event || !occursOnce(event)) {
        return { breaks: `${entry.rule.name} also starts on ${entry.clause ? text(entry.clause) : 'its start'}, which may come again while another of their turn is active` };
    }
    return { never: `take turns, each starting only on the endof of another, and only ${entry.rule.name} starts otherwise, once at most (on ${text(entry.clause!)})` };
}
