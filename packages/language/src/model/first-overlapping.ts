/**
 * For a list of rules (the rules of the subscribes to one input port, in written order): for each
 * one, the first earlier one it may be active with — the first that RuleOverlap.apart does not keep
 * apart from it (rule-activity.ts). Asking `apart` of every earlier one took n²/2 questions on a
 * chain of n rules each ending before the next (`R1: [endof(R0)]`, …), all of them apart.
 *
 * A segment tree over the list keeps, for each run of rules, what `apart` reads of them summed up
 * (their function, whether all are active once, the bounds of their intervals and of their
 * ended-rules' intervals, their common turn): a run all of whose rules are apart from the rule asked
 * about, for one and the same reason, is passed over whole; any other run is looked into, down to
 * single rules, which `apart` itself decides. So the answer is `apart`'s, found in a few steps when
 * the earlier rules are apart for a shared reason (the chain: all end before the rule asked about).
 */
import type { Rule } from '../generated/ast.js';
import type { RuleFacts, RuleOverlap } from './rule-activity.js';

/** What `apart` reads of a run of rules, summed up. */
interface Run {
    /** Rules in the run (0: padding). */
    count: number;
    /** The RuleOverlap of all of them (one function), or null: mixed, or a rule missing. */
    overlap: RuleOverlap | null;
    allOnce: boolean;
    maxEnter: number;
    minLeave: number;
    minEndedEnter: number;
    maxEndedLeave: number;
    /** The turn all of them share (undefined: none of them has one), or null: mixed. */
    turn: object | undefined | null;
}

const EMPTY: Run = { count: 0, overlap: null, allOnce: true, maxEnter: -Infinity, minLeave: Infinity, minEndedEnter: Infinity, maxEndedLeave: -Infinity, turn: null };

function join(a: Run, b: Run): Run {
    if (a.count === 0) return b;
    if (b.count === 0) return a;
    return {
        count: a.count + b.count,
        overlap: a.overlap === b.overlap ? a.overlap : null,
        allOnce: a.allOnce && b.allOnce,
        maxEnter: Math.max(a.maxEnter, b.maxEnter),
        minLeave: Math.min(a.minLeave, b.minLeave),
        minEndedEnter: Math.min(a.minEndedEnter, b.minEndedEnter),
        maxEndedLeave: Math.max(a.maxEndedLeave, b.maxEndedLeave),
        turn: a.turn === b.turn ? a.turn : null,
    };
}

/**
 * Whether every rule of `run` is apart from the rule of facts `x` (of `overlap`'s function), the
 * rule itself aside (a rule is never apart from itself: FirstOverlapping counts it apart):
 * all end before it (each active once, an ancestor of its ended-rule), or it is active once and
 * ends before all of them, or all share its turn (RuleOverlap.apart).
 */
function allApart(run: Run, overlap: RuleOverlap, x: Readonly<RuleFacts>): boolean {
    if (run.overlap !== overlap) return false;
    const allEndBefore = x.endedEnter >= 0 && run.allOnce && run.maxEnter <= x.endedEnter && x.endedLeave <= run.minLeave;
    const endsBeforeAll = x.once && run.minEndedEnter >= 0 && x.enter <= run.minEndedEnter && run.maxEndedLeave <= x.leave;
    const sameTurn = x.turn !== undefined && run.turn === x.turn;
    return allEndBefore || endsBeforeAll || sameTurn;
}

export class FirstOverlapping {
    private readonly leaves: number;
    private readonly tree: Run[];
    /** Per position: the first earlier position holding the same rule (never apart from itself). */
    private readonly sameRuleBefore: Array<number | undefined>;

    /**
     * @param rules the rules in order (undefined: an action outside any rule, apart from none)
     * @param overlapOf the RuleOverlap of a rule's function
     */
    constructor(private readonly rules: ReadonlyArray<Rule | undefined>, private readonly overlapOf: (rule: Rule) => RuleOverlap | undefined) {
        let leaves = 1;
        while (leaves < rules.length) leaves *= 2;
        this.leaves = leaves;
        this.tree = new Array<Run>(2 * leaves).fill(EMPTY);
        const firstOf = new Map<Rule, number>();
        this.sameRuleBefore = rules.map((rule, i) => {
            if (!rule) return undefined;
            const first = firstOf.get(rule);
            if (first === undefined) firstOf.set(rule, i);
            return first;
        });
        rules.forEach((rule, i) => { this.tree[leaves + i] = this.leaf(rule); });
        for (let node = leaves - 1; node >= 1; node--) this.tree[node] = join(this.tree[2 * node]!, this.tree[2 * node + 1]!);
    }

    /** The first position before `k` whose rule `apart` does not keep apart from the rule at `k`, or undefined. */
    firstBefore(k: number): number | undefined {
        if (k <= 0) return undefined;
        const rule = this.rules[k];
        const overlap = rule && this.overlapOf(rule);
        const x = overlap && rule ? overlap.factsOf(rule) : undefined;
        if (!rule || !overlap || !x) return 0; // apart from none
        const found = this.search(1, 0, this.leaves, k, rule, overlap, x);
        const same = this.sameRuleBefore[k];
        return same !== undefined && (found === undefined || same < found) ? same : found;
    }

    private leaf(rule: Rule | undefined): Run {
        const overlap = rule && this.overlapOf(rule);
        const f = overlap && rule ? overlap.factsOf(rule) : undefined;
        if (!overlap || !f) return { ...EMPTY, count: 1 };
        return { count: 1, overlap, allOnce: f.once, maxEnter: f.enter, minLeave: f.leave, minEndedEnter: f.endedEnter, maxEndedLeave: f.endedLeave, turn: f.turn };
    }

    /** The first position in [lo, hi) ∩ [0, k) of node `node` whose rule may be active with `rule`. */
    private search(node: number, lo: number, hi: number, k: number, rule: Rule, overlap: RuleOverlap, x: Readonly<RuleFacts>): number | undefined {
        if (lo >= k || this.tree[node]!.count === 0 || allApart(this.tree[node]!, overlap, x)) return undefined;
        if (hi - lo === 1) {
            const other = this.rules[lo];
            return other && overlap.apart(rule, other) ? undefined : lo;
        }
        const mid = (lo + hi) >> 1;
        return this.search(2 * node, lo, mid, k, rule, overlap, x) ?? this.search(2 * node + 1, mid, hi, k, rule, overlap, x);
    }
}
