/**
 * Property: the simulator is deterministic. Random event sequences on the tutorial (module events
 * with random values, ORD events, slow and crashing modules, modules whose code ends their run, starts and stops), replayed twice,
 * give identical decisions — every rule change with its cause, every action, every state.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { loadScenario, runLoadedScenario } from '../src/index.js';
import { prepared, TUTORIAL } from './support.js';

const word = fc.constantFrom('"connected"', '"disconnected"', '""', '"dis"');
const event = fc.oneof(
    word.map((w) => `MAA:2 ${w}`),
    fc.tuple(fc.integer({ min: -5, max: 5 }), fc.double({ min: -10, max: 10, noNaN: true })).map(([n, x]) => `MAA:0 {"m", ${n}, {${x.toFixed(3)}, 1.0, 2.0}}`),
    fc.integer({ min: -50, max: 50 }).map((n) => `MSC:1 {"failure", ${n}}`),
    fc.constantFrom('ORD:0 "schemaCommande1"', 'ORD:1 "schemaCommande2"'),
    fc.integer({ min: 0, max: 2500 }).map((ms) => `exec MSC ${ms}ms once`),
    fc.constantFrom('crash MSD', 'finish MAA', 'finish MAB', 'finish MAB after 3ms', 'finish MAA after 0 once', 'stop SUP.action', 'start SUP.action(consigne = {1.0, 2.0, 3.0})', 'stop GLB.mission', 'start GLB.mission()'),
);
const steps = fc.array(fc.tuple(fc.integer({ min: 0, max: 700 }), event), { minLength: 1, maxLength: 40 });

function scenarioText(list: Array<[number, string]>): string {
    let t = 0;
    const lines = ['until 8s', 'start GLB.mission(consigne = {1.0, 2.0, 3.0})'];
    for (const [dt, e] of list) {
        t += dt;
        lines.push(`t=${t}ms ${e}`);
    }
    return lines.join('\n');
}

describe('determinism', () => {
    it('the same random event sequence replayed twice gives identical decisions', async () => {
        const project = await prepared(TUTORIAL);
        await fc.assert(fc.asyncProperty(steps, async (list) => {
            const text = scenarioText(list);
            const s = loadScenario('random.scenario', 'random.scenario', text, project.index);
            expect(s.diagnostics).toEqual([]);
            const a = await runLoadedScenario(project, s);
            const b = await runLoadedScenario(project, s);
            expect(a.error).toBeUndefined();
            const decisions = (r: typeof a) => r.steps.map((x) => ({ line: x.line, ok: x.ok, rules: x.record.rules, actions: x.record.actions, schemas: x.record.schemas, locals: x.record.locals, log: x.record.log }));
            expect(decisions(b)).toEqual(decisions(a));
            expect(b.eventsProcessed).toBe(a.eventsProcessed);
        }), { numRuns: 40 });
    });
});
