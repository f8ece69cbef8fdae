/**
 * The scenario editor services as functions, on the tutorial loaded from examples/ (the stdio
 * session is lsp-scenario-server.test.ts): completion and hover do not throw (tested without their
 * guards) and diagnostics stay inside the text, whatever
 * the text and the position (fast-check: scenario-like lines mutated at random); "did you mean"
 * picks the closest name and nothing far; a project is found from the scenario's folder upwards.
 */
import fc from 'fast-check';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { isModel, type Model } from '../src/index.js';
import { loadWorkspace } from '../src/node/index.js';
import { closestName } from '../src/scenario/did-you-mean.js';
import { completeUnguarded } from '../src/lsp/scenario/scenario-completion.js';
import { scenarioDiagnostics } from '../src/lsp/scenario/scenario-diagnostics.js';
import { hoverUnguarded } from '../src/lsp/scenario/scenario-hover.js';
import { scenarioNames } from '../src/lsp/scenario/scenario-names.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
const COMMUTATION = readFileSync(`${TUTORIAL}/scenarios/commutation.scenario`, 'utf8');

async function tutorialModels(): Promise<Model[]> {
    const ws = await loadWorkspace(TUTORIAL);
    return ws.documents.map((d) => d.model).filter(isModel);
}

describe('scenario editor services', () => {
    it('never throw and keep every range inside the text (fast-check)', async () => {
        const models = await tutorialModels();
        const names = scenarioNames(models);
        const lines = COMMUTATION.split('\n');
        const pieces = ['t=', '300ms', 'MAA:', '2', ' ', '"', '{', '}', ',', '.', '#', 'expect', 'rule', 'SUP.action.', 'local', '==', '(', ')', '=', 'ORD:0', '\t', 'é', '\u0000'];
        fc.assert(fc.property(
            fc.array(fc.tuple(fc.nat(lines.length - 1), fc.nat(200), fc.constantFrom(...pieces), fc.boolean()), { maxLength: 12 }),
            fc.nat(60), fc.nat(120),
            (edits, line, character) => {
                const text = lines.slice();
                for (const [l, at, piece, remove] of edits) {
                    const s = text[l]!;
                    const i = Math.min(at, s.length);
                    text[l] = remove ? s.slice(0, i) + s.slice(i + 1) : s.slice(0, i) + piece + s.slice(i);
                }
                const joined = text.join('\n');
                for (const d of scenarioDiagnostics(joined, { models })) {
                    expect(d.range.start.line).toBeLessThan(text.length);
                    expect(d.range.end.character).toBeGreaterThanOrEqual(d.range.start.character);
                    expect(d.range.end.character).toBeLessThanOrEqual(text[d.range.start.line]!.length + 1);
                }
                // Unguarded: a throw here fails the property (the services themselves also catch it).
                for (const item of completeUnguarded(joined, { line, character }, names)) expect(item.textEdit).toBeDefined();
                const h = hoverUnguarded(joined, { line, character }, names);
                if (h) expect(h.range!.start.line).toBe(line);
            }), { numRuns: 300, seed: 4207 });
    }, 60_000);

    it('suggests the closest name only when it is close', () => {
        expect(closestName('SECNOD', ['FIRST', 'SECOND', 'THIRD'])).toBe('SECOND');
        expect(closestName('MZA', ['MAA', 'MAB', 'MSC'])).toBe('MAA');
        expect(closestName('schemacommande1', ['schemaCommande1', 'schemaCommande2'])).toBe('schemaCommande1');
        expect(closestName('FIFTH', ['FIRST', 'SECOND', 'THIRD', 'FOURTH'])).toBeUndefined();
        expect(closestName('x'.repeat(10_000), ['x'])).toBeUndefined();
    });

    it('suggests a name or a word of the scenario with two letters swapped', async () => {
        const models = await tutorialModels();
        const text = 'start SUP.atcion(consigne = {1.0, 2.0, 3.0})\nexpect rule SUP.action.SECNOD active\nexepct module MAA running\nexpect module MAA runnign\n';
        expect(scenarioDiagnostics(text, { models }).map((d) => [d.range.start.line, d.message.replace(/^.*(Did you mean '[^']*'\?)$/, '$1')]).sort()).toEqual([
            [0, "Did you mean 'action'?"],
            [1, "Did you mean 'SECOND'?"],
            [2, "Did you mean 'expect'?"],
            [3, "Did you mean 'running'?"]
        ]);
    });

    it('warns that names are not checked when the scenario has no project', () => {
        const d = scenarioDiagnostics('start SUP.action()\n', { models: [] });
        expect(d.map((x) => [x.code, x.severity])).toEqual([['scenario-no-project', 2]]);
    });
});
