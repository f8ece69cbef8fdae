/**
 * Differential test of the tutorial: a real run (`contract run --sandbox bwrap`, 5 s, real
 * processes, real MAA/MSC code) and the simulator fed with the same events must take the same
 * supervisor decisions: every `sup_rule` record of the run's CSV trace, in order, per supervisor,
 * equals the simulator's rule changes with their causes. The module runs that their own code ended
 * are replayed as `finish` steps (MAB's, at once, in every run; MAA's after it posts "disconnected"
 * in some: its script ends its run then, and SUP's STOP arrives 0.5 ms later or first, a race of
 * the two processes: 1 run of 8 here), and the story of both sides tells the same such runs, each
 * started by the same supervisor.
 *
 * The events are the run's (test/differential/replay-run.ts: what is replayed and how values are
 * found). Values the logs do not give: MAA:2 events that changed no rule were "connected" (the only
 * other status the tutorial's MAA script posts); a datatype's value that changed a rule is logged field
 * by field and replayed as logged; one that changed none (the tutorial's rules test none of them)
 * takes the type's default.
 *
 * And the records both sides write have the same fields (differential/record-shapes.ts): per kind
 * and writer, the simulation writes no field list a real run does not, and no field one does not
 * have (a supervisor's event_received with its taken_ns, rules and value, as sup_main.c writes it;
 * MAB's event_received and event_handled of the events MAA:0 =* MAB:0 brings it). And each
 * supervisor's event_received carries the same value and rule count as the run's, per source in
 * order (the values the replay cannot know, a datatype that changed no rule, left out).
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { renderStory, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import type { ScenarioResult } from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { TUTORIAL } from './support.js';
import { commonGroups, recordShapes, shapeDifferences } from './differential/record-shapes.js';
import { firstDifference, realDecisions, replayInSimulator, runForReal, simulatedDecisions, TUTORIAL_PLAN, type RealRun } from './differential/replay-run.js';

const SUPERVISORS = TUTORIAL_PLAN.supervisors;
let run: RealRun;

/** The story's `run #N ended by its own code (started by X)` lines, without their times. */
const ownRunEnds = (records: TraceRecord[]): string[] => renderStory(records).filter((l) => l.includes(' ended by its own code ')).map((l) => l.slice(11));

/** The run's records before the launcher's stop (what the simulation, which has no launcher, covers). */
function beforeLaunchersStop(records: TraceRecord[]): KnownRecord[] {
    const known = records.filter((r): r is KnownRecord => r.kind !== 'unknown');
    const stop = known.find((r) => r.kind === 'request_received' && r.peer === 'contract-launch' && /^(STOP|KILL)/.test(r.detail));
    return known.filter((r) => !stop || BigInt(r.monoNs) < BigInt(stop.monoNs));
}

beforeAll(() => {
    run = runForReal(TUTORIAL, '5s');
}, 300_000);
afterAll(() => run?.cleanUp());

describe('simulator vs a real bwrap run of the tutorial', () => {
    let sim: ScenarioResult;
    let real: RuleRecord[];
    let text: string;
    let finished: string[];
    let adjustments: string[];

    beforeAll(async () => {
        expect(run.code, run.output).toBe(0);
        let diagnostics: unknown[];
        ({ text, real, finished, adjustments, sim, diagnostics } = await replayInSimulator(TUTORIAL, run.records, TUTORIAL_PLAN));
        expect(diagnostics, text).toEqual([]);
    }, 120_000);

    it('the run took the report\'s decisions (FIRST, SECOND on "disconnected", the commutation)', () => {
        const told = [...SUPERVISORS].flatMap((sup) => realDecisions(real, sup));
        expect(told).toContain('SUP action.SECOND active <- MAA:2 value="disconnected"');
        expect(told.length).toBeGreaterThan(5);
    });

    it('every supervisor took the same decisions, in the same order, with the same causes', () => {
        expect(sim.error).toBeUndefined();
        const simulated = sim.steps.flatMap((s) => s.record.rules);
        for (const sup of SUPERVISORS) {
            const got = simulatedDecisions(simulated, sup);
            const want = realDecisions(real, sup);
            expect(got, firstDifference(sup, got, want, text, adjustments)).toEqual(want);
        }
    });

    it('the runs their own code ended (MAB at once; MAA when it won the race) end in the simulation too', () => {
        expect(finished).toContain('MAB');
        const want = ownRunEnds(beforeLaunchersStop(run.records));
        expect(want).toContain('MAB  run #1 ended by its own code (started by SUP)');
        expect(ownRunEnds(stepsToTrace(sim.steps.map(traceStepOf))), text).toEqual(want);
        expect(sim.failures.map((f) => f.message), text).toEqual([]);
    });

    it('the records of each kind both write carry the same fields in the same order (a supervisor\'s event_received: taken_ns, rules, value)', () => {
        const real = recordShapes(beforeLaunchersStop(run.records), SUPERVISORS);
        const simulated = recordShapes(stepsToTrace(sim.steps.map(traceStepOf)), SUPERVISORS);
        const compared = commonGroups(real, simulated);
        const shown = `compared: ${compared.join(', ')}\nreal: ${JSON.stringify([...real].map(([g, s]) => [g, [...s]]))}\nsimulated: ${JSON.stringify([...simulated].map(([g, s]) => [g, [...s]]))}`;
        expect(compared, shown).toEqual(expect.arrayContaining(['event_received by supervisor', 'event_received by module', 'event_handled by module', 'run_started by module', 'run_finished by module', 'ord_release by ORD', 'module_hold by supervisor', 'sup_rule by supervisor']));
        expect(shapeDifferences(real, simulated), shown).toEqual([]);
        expect([...simulated.get('event_received by supervisor')!]).toEqual(['from_port latency_ns taken_ns rules value port peer']);
        expect([...simulated.get('event_handled by module')!]).toEqual(['from_port handling_ns port peer']);
    });

    it("each supervisor's event_received says the same value and rule count in both (a datatype value that changed no rule is replayed as the type's default: its value is not compared)", () => {
        const simulatedRecords = stepsToTrace(sim.steps.map(traceStepOf)).filter((r): r is KnownRecord => r.kind !== 'unknown');
        const compared = (sup: string, records: KnownRecord[]): Map<string, string[]> => {
            const bySource = new Map<string, string[]>();
            for (const r of records) {
                if (r.kind !== 'event_received' || r.module !== sup || SUPERVISORS.has(r.peer)) continue;
                const rules = Number(r.fields['rules']);
                const value = String(r.fields['value']);
                const source = `${r.peer}:${r.fields['from_port']}`;
                (bySource.get(source) ?? bySource.set(source, []).get(source)!).push(`rules=${rules} value=${rules === 0 && value.startsWith('{') ? '(a datatype, not replayed)' : value}`);
            }
            return bySource;
        };
        let seen = 0;
        for (const sup of SUPERVISORS) {
            const got = compared(sup, simulatedRecords);
            const want = compared(sup, beforeLaunchersStop(run.records));
            for (const [source, list] of got) {
                // the simulation replays the events up to its end: the run's first ones of each source
                expect(list, `${sup} ${source}\n${text}`).toEqual(want.get(source)?.slice(0, list.length));
                seen += list.length;
            }
        }
        expect(seen).toBeGreaterThan(3);
    });
});
