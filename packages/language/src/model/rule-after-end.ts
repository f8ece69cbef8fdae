/**
 * Which rules of one supervision function become active only after another has become inactive
 * (rule-activity.ts RuleOverlap): `LAND: [endof(HOLD)]`, and `TAXI: [endof(LAND)]` after it, start
 * only after HOLD's end. Computed once per function in one pass over its rules, kept as a tree.
 *
 * For a rule R, ended(R) is the set of rules each of whose ends precedes every activation of R:
 * each precondition clause of R that can be true (clause-trigger.ts) is true only while its one
 * event without persistence is processed; `endof(S)` gives {S} and ended(S) (S has just become
 * inactive, after every end ended(S) holds), `started(S)` and `duration(S)=t` give ended(S) (they
 * occur while S is active); any other event gives nothing. ended(R) is the intersection over the
 * clauses. Each of these sets is a path to the root of one tree (ended(R) is S followed by
 * ended(S), or a common tail of such paths), so ended(R) is kept as its first rule, R's parent in
 * the tree, and the intersection of two paths is their lowest common ancestor. Rules are placed
 * after the rules their clauses name; a rule met again while it is being placed (a cycle of rules)
 * gives nothing, which only ever leaves rules out: a cycle proves nothing.
 */
import { isDurationEvent, isEndofEvent, isStartedEvent, type Rule } from '../generated/ast.js';
import { clauseTrigger } from './clause-trigger.js';

export class RulesAfterEnd {
    /** R -> the first rule of ended(R) (its parent in the tree); absent: ended(R) is empty. */
    private readonly parent = new Map<Rule, Rule>();
    private readonly depth = new Map<Rule, number>();
    /** R -> its ancestors 1, 2, 4, 8... steps up (binary lifting: an ancestor query in log steps). */
    private readonly jumps = new Map<Rule, Rule[]>();
    /** The rules in the order they were placed (each after its parent). */
    private readonly order: Rule[] = [];

    constructor(rules: readonly Rule[]) {
        const placed = new Set<Rule>();
        const placing = new Set<Rule>();
        const inFunction = new Set(rules);
        for (const root of rules) {
            // depth-first, without recursion: a 10,000-rule chain is as deep
            const stack: Array<{ rule: Rule; next: number; needs: Rule[] }> = [];
            const open = (rule: Rule) => {
                placing.add(rule);
                stack.push({ rule, next: 0, needs: needed(rule).filter((r) => inFunction.has(r)) });
            };
            if (!placed.has(root)) open(root);
            while (stack.length > 0) {
                const top = stack[stack.length - 1]!;
                const need = top.needs[top.next++];
                if (need) {
                    if (!placed.has(need) && !placing.has(need)) open(need);
                    continue;
                }
                stack.pop();
                placing.delete(top.rule);
                this.place(top.rule, placed);
                placed.add(top.rule);
                this.order.push(top.rule);
            }
        }
    }

    /**
     * Each rule's interval in a depth-first walk of the tree (entered, left): `a` is an ancestor of
     * `b`, or `b` itself, when its interval holds b's. An ancestor query is then two comparisons.
     */
    intervals(): Map<Rule, { enter: number; leave: number }> {
        const children = new Map<Rule, Rule[]>();
        const roots: Rule[] = [];
        for (const rule of this.order) {
            const parent = this.parent.get(rule);
            if (!parent) roots.push(rule);
            else {
                const list = children.get(parent) ?? [];
                list.push(rule);
                children.set(parent, list);
            }
        }
        const result = new Map<Rule, { enter: number; leave: number }>();
        let clock = 0;
        for (const root of roots) {
            const stack: Array<{ rule: Rule; next: number }> = [{ rule: root, next: 0 }];
            result.set(root, { enter: clock++, leave: 0 });
            while (stack.length > 0) {
                const top = stack[stack.length - 1]!;
                const child = children.get(top.rule)?.[top.next++];
                if (child) {
                    result.set(child, { enter: clock++, leave: 0 });
                    stack.push({ rule: child, next: 0 });
                } else {
                    result.get(top.rule)!.leave = clock++;
                    stack.pop();
                }
            }
        }
        return result;
    }

    /** The first rule of ended(rule) (the latest end that precedes its activations), if any. */
    headOf(rule: Rule): Rule | undefined {
        return this.parent.get(rule);
    }

    private place(rule: Rule, placed: Set<Rule>): void {
        let head: Rule | undefined;
        let first = true;
        for (const clause of rule.precondition?.clauses ?? []) {
            const trigger = clauseTrigger(clause);
            if (trigger === 'never') continue; // never true: it starts nothing
            let clauseHead: Rule | undefined;
            const event = trigger?.event;
            const other = event && (isEndofEvent(event) || isStartedEvent(event) || isDurationEvent(event)) ? event.rule?.ref : undefined;
            if (other && other !== rule && placed.has(other)) {
                clauseHead = isEndofEvent(event) ? other : this.parent.get(other);
            }
            if (!clauseHead) return; // this clause may be true before any end: ended(rule) is empty
            head = first ? clauseHead : this.commonAncestor(head, clauseHead);
            first = false;
            if (!head) return;
        }
        if (!head) return;
        this.parent.set(rule, head);
        this.depth.set(rule, (this.depth.get(head) ?? 0) + 1);
        const jumps: Rule[] = [head];
        for (let k = 0; jumps[k] && this.jumps.get(jumps[k]!)?.[k]; k++) jumps.push(this.jumps.get(jumps[k]!)![k]!);
        this.jumps.set(rule, jumps);
    }

    private ancestor(rule: Rule, steps: number): Rule | undefined {
        let current: Rule | undefined = rule;
        for (let k = 0; current && steps > 0; k++, steps >>= 1) {
            if (steps & 1) current = this.jumps.get(current)?.[k];
        }
        return current;
    }

    private commonAncestor(a: Rule | undefined, b: Rule): Rule | undefined {
        if (!a) return undefined;
        const da = this.depth.get(a) ?? 0;
        const db = this.depth.get(b) ?? 0;
        let x: Rule | undefined = da > db ? this.ancestor(a, da - db) : a;
        let y: Rule | undefined = db > da ? this.ancestor(b, db - da) : b;
        if (x === y) return x;
        for (let k = Math.floor(Math.log2(Math.max(da, db) + 1)); k >= 0; k--) {
            const jx = x && this.jumps.get(x)?.[k];
            const jy = y && this.jumps.get(y)?.[k];
            if (jx !== jy) { x = jx; y = jy; }
        }
        x = x && this.parent.get(x);
        y = y && this.parent.get(y);
        return x === y ? x : undefined;
    }
}

/** The rules whose started/endof/duration events trigger a clause of `rule`. */
function needed(rule: Rule): Rule[] {
    const rules: Rule[] = [];
    for (const clause of rule.precondition?.clauses ?? []) {
        const trigger = clauseTrigger(clause);
        const event = trigger === 'never' ? undefined : trigger?.event;
        const other = event && (isEndofEvent(event) || isStartedEvent(event) || isDurationEvent(event)) ? event.rule?.ref : undefined;
        if (other && other !== rule) rules.push(other);
    }
    return rules;
}
