/**
 * supervisor-schema-conflict: periodic schemas sharing a module activated by one rule, or by rules
 * that become active together, are certain to be refused by ORD (ORD:1, docs/engines.md); and
 * schema hover lists the schemas a schema conflicts with.
 */
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import type { MarkupContent } from 'vscode-languageserver-protocol';
import { loadWorkspace } from '../src/node/load-workspace.js';
import { architecture, supervisor } from './architecture-fixture.js';
import { build, type Built } from './helpers.js';
import { isSupervisor, type Model } from '../src/generated/ast.js';
import { rulesOf } from '../src/model/blocks.js';
import { activeTogether, groupOf } from '../src/model/schema-conflicts.js';
import { offsetOf, positionParams } from './lsp-workspace.js';

/** sc2 shares MSC and MSD with sc1; sc3 (in ev2.contract, a file of the schemas' import tier) shares nothing (MSB alone). */
const SCHEMAS = {
    'sc2.contract': `periodic schema sc2(TypeA consigne) {
        realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }
        modules { MSC (consigne:0); MSD (); }
        scheduling graph { MSC -> MSD; }
    }`,
    'ev2.contract': 'periodic schema sc3() { realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } modules { MSB (); } }',
    'sched.contract': 'scheduler configuration { modules { MSA; MSB; MSC; MSD; } schemas { sc1; sc2; sc3; } }'
};
const withRules = (rules: string) => architecture({ ...SCHEMAS, 'sup.contract': supervisor(rules) });
const A = 'activate schema sc1(consigne = temp_consigne)';
const B = 'activate schema sc2(consigne = temp_consigne)';

async function conflicts(rules: string): Promise<Array<{ line: string; data: unknown }>> {
    const built = await build(withRules(rules));
    const other = built.diagnostics.filter((d) => d.severity === 'error' || (d.severity === 'warning' && d.code !== 'supervisor-schema-conflict'));
    expect(other, built.lines.join('\n')).toEqual([]);
    return built.diagnostics.filter((d) => d.code === 'supervisor-schema-conflict').map((d) => ({ line: `${d.severity} ${d.message}`, data: d.data }));
}

describe('supervisor-schema-conflict', () => {
    it('one rule activating two periodic schemas that share modules: warns on the second, naming the modules', async () => {
        const found = await conflicts(`R: [elapsed=1ms] ${A}; ${B} [elapsed=2ms]`);
        expect(found).toEqual([{
            line: 'warning Rule R activates periodic schemas sc1 and sc2, which share modules MSC, MSD: ORD refuses an activation while a schema sharing a module is active and emits ORD:1 (docs/engines.md), so sc2 is always refused. Activate them in rules that are never active together (e.g. start the second rule on endof of the first).',
            data: expect.objectContaining({ code: 'supervisor-schema-conflict', conflictsWith: 'sc1', modules: ['MSC', 'MSD'] })
        }]);
    });

    it('no warning for schemas that share no module, or for event schemas (run by the supervisor engine)', async () => {
        expect(await conflicts(`R: [elapsed=1ms] ${A}; activate schema sc3() [elapsed=2ms]`)).toEqual([]);
        expect(await conflicts('R: [elapsed=1ms] activate schema ev(); activate schema ev() [elapsed=2ms]')).toEqual([]);
    });

    it('the same periodic schema twice in one rule', async () => {
        const found = await conflicts(`R: [elapsed=1ms] ${A}; ${A} [elapsed=2ms]`);
        expect(found.map((f) => f.line)).toEqual([expect.stringContaining('Rule R activates periodic schema sc1 twice')]);
    });

    it('a rule started on started(other) without persistence is active with it', async () => {
        const found = await conflicts(`P: [elapsed=1ms] ${A} [elapsed=1s]\nQ: [started(P)] ${B} [elapsed=2s]`);
        expect(found.map((f) => f.line)).toEqual([expect.stringContaining(
            'In rule Q, periodic schema sc2 shares modules MSC, MSD with sc1, activated by rule P, and the two rules are active together (Q becomes active on started(P))')]);
    });

    it('rules started on the same event are active together; different events are not', async () => {
        const same = await conflicts(`P: [elapsed=1ms] ${A} [elapsed=1s]\nQ: [elapsed=1000us] ${B} [elapsed=2s]`);
        expect(same.map((f) => f.line)).toEqual([expect.stringContaining('(P and Q both become active on elapsed=1ms)')]);
        expect(await conflicts(`P: [elapsed=1ms] ${A} [elapsed=1s]\nQ: [elapsed=2ms] ${B} [elapsed=2s]`)).toEqual([]);
    });

    it('many rules on one event: each later activation is warned once, its reason the direct one, with links linear in the rules (not every pair)', async () => {
        const n = 300;
        const rules = Array.from({ length: n }, (_, i) => `R${i}: [elapsed=1ms] ${i % 2 ? B : A} [elapsed=2ms]`).join('\n');
        const found = await conflicts(rules);
        expect(found).toHaveLength(n - 1);
        expect(found[0]!.line).toContain('In rule R1, periodic schema sc2 shares modules MSC, MSD with sc1, activated by rule R0, and the two rules are active together (R0 and R1 both become active on elapsed=1ms)');
        expect(found[n - 2]!.line).toContain(`(R0 and R${n - 1} both become active on elapsed=1ms)`);
        const built = await build(withRules(rules));
        const fn = (built.docs.get('sup.contract')!.parseResult.value as Model).elements.find(isSupervisor)!.functions[0]!;
        const links = activeTogether(fn);
        expect([...links.values()].reduce((total, l) => total + l.length, 0)).toBe(2 * (n - 1));
        expect(groupOf(rulesOf(fn)[n - 1]!, links).size).toBe(n);
    });

    it('through a chain of rules: P, then Q on started(P), then S on started(Q)', async () => {
        const found = await conflicts(`P: [elapsed=1ms] ${A} [elapsed=1s]\nQ: [started(P)] compute doit("x", 1.0) [elapsed=2s]\nS: [started(Q)] ${B} [elapsed=3s]`);
        expect(found.map((f) => f.line)).toEqual([expect.stringContaining('(Q becomes active on started(P), then S becomes active on started(Q))')]);
    });

    it('no warning for endof(other) (its schemas are deactivated first), started with persistence, or another function', async () => {
        expect(await conflicts(`P: [elapsed=1ms] ${A} [elapsed=1s]\nQ: [endof(P)] ${B} [elapsed=2s]`)).toEqual([]);
        expect(await conflicts(`P: [elapsed=1ms] ${A} [elapsed=1s]\nQ: [(elapsed=5ms and started(P){1s})] ${B} [elapsed=2s]`)).toEqual([]);
        const otherFunction = architecture({ ...SCHEMAS, 'sup.contract': supervisor(`P: [elapsed=1ms] ${A} [elapsed=1s]`, { more: `other() { rules { Q: [elapsed=1ms] activate schema sc2() [elapsed=2s] } }` }) });
        expect((await build(otherFunction)).diagnostics.filter((d) => d.code === 'supervisor-schema-conflict')).toEqual([]);
    });
});

describe('no false positive on the examples', () => {
    for (const example of ['tutorial', 'mobile-robot']) {
        it(`examples/${example}`, async () => {
            const ws = await loadWorkspace(fileURLToPath(new URL(`../../../examples/${example}`, import.meta.url)));
            expect(ws.diagnostics.filter((d) => d.code === 'supervisor-schema-conflict')).toEqual([]);
        });
    }
});

describe('schema hover lists the schemas it conflicts with', () => {
    async function hover(ws: Built, file: string, needle: string, delta = 0): Promise<string> {
        const doc = ws.docs.get(file)!;
        const result = await ws.services.lsp.HoverProvider!.getHoverContent(doc, positionParams(doc, offsetOf(doc, needle, delta)));
        return (result?.contents as MarkupContent | undefined)?.value ?? '';
    }

    it('on the declaration and on a reference, with the shared modules; not for a schema without conflict', async () => {
        const ws = await build(withRules(`R: [elapsed=1ms] ${A} [elapsed=2ms]`));
        const line = 'conflicts with (shared modules: ORD refuses one while the other is active, ORD:1): `sc2` (MSC, MSD)';
        expect(await hover(ws, 'sc1.contract', 'sc1(', 0)).toContain(line);
        expect(await hover(ws, 'sup.contract', 'schema sc1', 7)).toContain(line);
        expect(await hover(ws, 'sc2.contract', 'sc2(', 0)).toContain('conflicts with (shared modules: ORD refuses one while the other is active, ORD:1): `sc1` (MSC, MSD)');
        const sc3 = await hover(ws, 'ev2.contract', 'sc3(', 0);
        expect(sc3).toContain('periodic schema sc3');
        expect(sc3).not.toContain('conflicts with');
    });
});
