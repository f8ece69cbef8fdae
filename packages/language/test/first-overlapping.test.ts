/**
 * model/first-overlapping.ts: the first earlier rule that RuleOverlap.apart does not keep apart,
 * through its index — the answer of asking `apart` of every earlier rule in order, on functions of
 * every kind of rule relation; and on a 1,000-rule endof chain subscribing one port, the subscribe
 * check asks `apart` a few times per subscribe, not of every earlier one.
 */
import { afterEach, describe, expect, it, vi } from 'vitest';
import { architecture, supervisor } from './architecture-fixture.js';
import { build } from './helpers.js';
import { isSupervisor, type Model, type Rule, type SupervisionFunction } from '../src/generated/ast.js';
import { rulesOf } from '../src/model/blocks.js';
import { FirstOverlapping } from '../src/model/first-overlapping.js';
import { RuleOverlap } from '../src/model/rule-activity.js';

/** A small deterministic generator (mulberry32), so that a failure is reproduced by its seed. */
function random(seed: number): (n: number) => number {
    let a = seed >>> 0;
    return (n) => {
        a = (a + 0x6d2b79f5) >>> 0;
        let t = a;
        t = Math.imul(t ^ (t >>> 15), t | 1);
        t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
        return Math.floor((((t ^ (t >>> 14)) >>> 0) / 4294967296) * n);
    };
}

/** Rules R0..R(n-1) whose preconditions chain, branch, take turns, recur or start on their own. */
function rulesText(seed: number, n: number): string {
    const pick = random(seed);
    return Array.from({ length: n }, (_, i) => {
        const other = () => `R${pick(n)}`;
        const earlier = () => `R${i === 0 ? 0 : pick(i)}`;
        const pre = [
            `elapsed=${1 + pick(5)}ms`, `endof(${earlier()})`, `endof(${earlier()})`, `endof(${earlier()})`, `endof(${earlier()})`,
            `endof(${earlier()})`, `endof(${earlier()})`, `endof(${other()})`, `elapsed=1ms or endof(${other()})`,
            `started(${other()})`, 'MAA:0', `endof(${earlier()}){1s}`,
        ][pick(12)];
        return `R${i}: [${i === 0 ? 'elapsed=1ms' : pre}] compute doit("x", 1.0) [duration(R${i})=1ms]`;
    }).join('\n');
}

async function functionsOf(rules: string, more = ''): Promise<SupervisionFunction[]> {
    const built = await build(architecture({ 'sup.contract': supervisor(rules, { more }) }));
    return (built.docs.get('sup.contract')!.parseResult.value as Model).elements.find(isSupervisor)!.functions;
}

/** The subscribe check's answer before the index: the first earlier rule `apart` does not keep apart. */
function firstByScan(list: ReadonlyArray<Rule | undefined>, k: number, overlapOf: (r: Rule) => RuleOverlap | undefined): number | undefined {
    const rule = list[k];
    const overlap = rule && overlapOf(rule);
    const at = list.slice(0, k).findIndex((b) => !(rule && b && overlap?.apart(rule, b)));
    return at < 0 ? undefined : at;
}

afterEach(() => vi.restoreAllMocks());

describe('FirstOverlapping', () => {
    it('answers as asking apart of every earlier rule, on 30 random functions (rules repeated, of another function, missing)', async () => {
        let compared = 0;
        let found = 0;
        let none = 0;
        for (let seed = 1; seed <= 30; seed++) {
            const n = 15 + (seed % 20);
            const [fn, other] = await functionsOf(rulesText(seed, n), `other() { rules { ${rulesText(seed + 1000, 4).replace(/\bR(\d+)/g, 'O$1')} } }`);
            const overlaps = new Map([fn!, other!].map((f) => [f, new RuleOverlap(f)]));
            const overlapOf = (r: Rule) => overlaps.get(r.$container.$container);
            // the function's rules in written order (as its subscribes come), now and then one again, one of the other function's, or none
            const extra: Array<Rule | undefined> = [...rulesOf(fn!), ...rulesOf(other!).slice(0, 1), undefined];
            const pick = random(seed * 7919);
            const list = rulesOf(fn!).flatMap((r) => (pick(4) === 0 ? [r, extra[pick(extra.length)]] : [r]));
            const index = new FirstOverlapping(list, overlapOf);
            for (let k = 0; k < list.length; k++) {
                const expected = firstByScan(list, k, overlapOf);
                expect(index.firstBefore(k), `seed ${seed}, position ${k}`).toBe(expected);
                compared++;
                if (expected !== undefined && expected > 0) found++;
                if (expected === undefined && k > 0) none++;
            }
        }
        expect(compared).toBeGreaterThan(600);
        // answers past the first rule and "none" (all earlier ones apart), not only "the first"
        expect(found).toBeGreaterThan(100);
        expect(none).toBeGreaterThan(10);
    }, 60_000);

    it('contract check of a 1,000-rule endof chain subscribing one port: apart asked a few times per subscribe (it was asked of every earlier one: 499,500 times)', async () => {
        const n = 1000;
        const rules = Array.from({ length: n }, (_, i) =>
            `R${i}: [${i === 0 ? 'elapsed=1ms' : `endof(R${i - 1})`}] subscribe MAA:2 =* :2 [MAA:2<connection_status == "done">]`).join('\n');
        const apart = vi.spyOn(RuleOverlap.prototype, 'apart');
        const built = await build(architecture({ 'sup.contract': supervisor(rules) }));
        expect(built.diagnostics.filter((d) => d.code === 'supervisor-subscribe-conflict')).toEqual([]);
        expect(apart.mock.calls.length).toBeLessThan(20 * n);
    }, 60_000);
});
