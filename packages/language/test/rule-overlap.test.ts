/** model/rule-activity.ts RuleOverlap on long chains and turns of rules: answers, and the cost of deciding them. */
import { describe, expect, it } from 'vitest';
import { architecture, supervisor } from './architecture-fixture.js';
import { build } from './helpers.js';
import { isSupervisor, type Model, type SupervisionFunction } from '../src/generated/ast.js';
import { rulesOf } from '../src/model/blocks.js';
import { activationsBounded, activeAtMostOnce, RuleOverlap } from '../src/model/rule-activity.js';

async function functionOf(rules: string): Promise<SupervisionFunction> {
    const built = await build(architecture({ 'sup.contract': supervisor(rules) }));
    return (built.docs.get('sup.contract')!.parseResult.value as Model).elements.find(isSupervisor)!.functions[0]!;
}

/** R0 on `first`, then each R(i) on endof(R(i-1)). */
const chain = (n: number, first: string) =>
    Array.from({ length: n }, (_, i) => `R${i}: [${i === 0 ? first : `endof(R${i - 1})`}] compute doit("x", 1.0) [duration(R${i})=1ms]`).join('\n');

describe('RuleOverlap', () => {
    it('a 2,000-rule endof chain started once: every pair never active together, decided without a walk per pair or per rule', async () => {
        const n = 2000;
        const fn = await functionOf(chain(n, 'elapsed=1ms'));
        const rules = rulesOf(fn);
        const cpu0 = process.cpuUsage();
        const overlap = new RuleOverlap(fn);
        // each rule against its successor and the last rule, both ways (the subscribe check asks about many pairs)
        const unknown: string[] = [];
        for (let i = 0; i + 1 < n; i++) {
            for (const [a, b] of [[rules[i]!, rules[i + 1]!], [rules[i + 1]!, rules[i]!], [rules[i]!, rules[n - 1]!], [rules[n - 1]!, rules[i]!]]) {
                if (!overlap.neverActiveTogether(a, b)) unknown.push(`${a.name} ${b.name}`);
            }
        }
        expect(unknown).toEqual([]);
        expect(overlap.neverActiveTogether(rules[0]!, rules[n - 1]!)).toBe(`R0 becomes active once at most, and R${n - 1} only after it ended`);
        expect(overlap.neverActiveTogether(rules[n - 1]!, rules[n - 2]!)).toBe(`R${n - 2} becomes active once at most, and R${n - 1} only after it ended`);
        const cpu = process.cpuUsage(cpu0);
        // CPU time, not wall time: the suite runs beside others at low priority. The walk per rule
        // pair this replaces took seconds here (every answer walked its after-set).
        expect((cpu.user + cpu.system) / 1000).toBeLessThan(1500);
    });

    it('a 2,000-rule chain: its last rule is active once at most, and only elapsed ending it is no warning (no recursion through the chain)', async () => {
        const n = 2000;
        const rules = Array.from({ length: n }, (_, i) => `R${i}: [${i === 0 ? 'elapsed=1ms' : `endof(R${i - 1})`}] compute doit("x", 1.0) [elapsed=${i + 2}ms]`).join('\n');
        const built = await build(architecture({ 'sup.contract': supervisor(rules) }));
        const fn = (built.docs.get('sup.contract')!.parseResult.value as Model).elements.find(isSupervisor)!.functions[0]!;
        expect(activeAtMostOnce(rulesOf(fn)[n - 1]!)).toBe(true);
        expect(activationsBounded(rulesOf(fn)[n - 1]!)).toBe(true);
        expect(built.diagnostics.filter((d) => d.severity === 'error' || d.code === 'supervisor-elapsed-once')).toEqual([]);
    });

    it('a chain whose first rule recurs: no pair is known apart', async () => {
        const fn = await functionOf(chain(50, 'MAA:0'));
        const rules = rulesOf(fn);
        const overlap = new RuleOverlap(fn);
        expect(overlap.neverActiveTogether(rules[0]!, rules[49]!)).toBeUndefined();
        expect(overlap.neverActiveTogether(rules[10]!, rules[11]!)).toBeUndefined();
    });

    it('a turn of 1,000 rules (R0 on elapsed=1ms or endof(R999)): never two at once; a second entry breaks it', async () => {
        const ring = (second: string) => chain(1000, `elapsed=1ms or endof(R999)`).replace('R500: [endof(R499)]', `R500: [endof(R499)${second}]`);
        const rules = rulesOf(await functionOf(ring('')));
        const overlap = new RuleOverlap(rules[0]!.$container.$container as SupervisionFunction);
        expect(overlap.neverActiveTogether(rules[3]!, rules[700]!)).toBe('R3 and R700 take turns, each starting only on the endof of another, and only R0 starts otherwise, once at most (on elapsed=1ms)');
        const broken = rulesOf(await functionOf(ring(' or elapsed=3ms')));
        const brokenOverlap = new RuleOverlap(broken[0]!.$container.$container as SupervisionFunction);
        expect(brokenOverlap.neverActiveTogether(broken[3]!, broken[700]!)).toBeUndefined();
        expect(brokenOverlap.whyTurnsOverlap(broken[3]!, broken[700]!)).toContain('2 of their clauses start one otherwise');
    });
});
