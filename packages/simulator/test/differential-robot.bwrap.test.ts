/**
 * Differential test of examples/mobile-robot: a real run (`contract run --sandbox bwrap`, 7 s:
 * teleoperation, the operator's "auto", the obstacle from 3.0 s to 4.5 s of OBS's clock) and the
 * simulator fed with the same events take the same decisions: per supervisor (MIS, DRV), every
 * `sup_rule` record of the run's CSV trace, in order, equals the simulator's rule changes with
 * their causes.
 *
 * What depends on timing, and how the comparison stays exact:
 * - the 100 Hz velocity loop misses deadlines on a loaded machine (no real-time priority under
 *   bwrap here): each miss is an `ORD:0 "velocityLoop"` that ends AUTO. Which cycles miss is timing,
 *   not semantics, so the real ORD's misses are replayed as events at their times (the simulated
 *   ORD's virtual modules are never late and make none of their own); what is compared is what the
 *   supervisors decide on them, including the misses that come while AUTO is not active (no decision);
 * - the times of decisions differ (a real message takes microseconds, a simulated one none): the
 *   comparison is on the order and the causes, not the times; `elapsed=1ms` timers are compared
 *   as causes;
 * - values: OBS:0 distances that changed a rule are named by their cause (`value=0.35`, `value=5`);
 *   those that changed none are replayed as 0.75, a distance that neither starts a safe stop
 *   (< 0.5) nor ends one (> 1.0), whatever the mode (the real one was 5 in AUTO or 0.35 in STOP:
 *   changing nothing either); joystick and navigation commands are `Twist` datatypes, logged as
 *   `{16 bytes}` and replayed as {0.0, 0.0}: the rules test only `v > 100.0` (false for both) and
 *   store them.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { RuleRecord } from '@contract-studio/build-service/trace';
import { loadScenario, runLoadedScenario, type ScenarioResult } from '../src/index.js';
import { prepared, ROBOT } from './support.js';
import { realDecisions, runForReal, scenarioOfRun, simulatedDecisions, type RealRun } from './differential/replay-run.js';

const SUPERVISORS = new Set(['MIS', 'DRV']);
let run: RealRun;

beforeAll(() => {
    run = runForReal(ROBOT, '7s');
}, 300_000);
afterAll(() => run?.cleanUp());

describe('simulator vs a real bwrap run of the mobile robot', () => {
    let sim: ScenarioResult;
    let real: RuleRecord[];
    let text: string;
    let counts: Map<string, number>;

    beforeAll(async () => {
        expect(run.code, run.output).toBe(0);
        ({ text, real, counts } = scenarioOfRun(run.records, {
            supervisors: SUPERVISORS,
            start: 'MIS.mission()',
            fallback: (module, port) => (module === 'OBS' && port === 0 ? '0.75' : undefined),
        }));
        const project = await prepared(ROBOT);
        const s = loadScenario('run.scenario', 'run.scenario', text, project.index);
        expect(s.diagnostics, text).toEqual([]);
        sim = await runLoadedScenario(project, s);
    }, 120_000);

    // which ends AUTO first, the obstacle (0.35 m) or a deadline miss, is timing: either is a safe stop
    it('the run went through its modes: teleop, autonomous on "auto", a safe stop, autonomous again when the way is clear', () => {
        const mis = realDecisions(real, 'MIS');
        const order = ['MIS mission.TELEOP active <- started(LINK)', 'MIS mission.AUTO active <- TEL:1 value="auto"', 'MIS mission.STOP active <- endof(AUTO)', 'MIS mission.STOP inactive <- OBS:0 value=5', 'MIS mission.AUTO active <- endof(STOP)'];
        let at = -1;
        for (const d of order) {
            const next = mis.indexOf(d, at + 1);
            expect(next, `${d} after ${order[order.indexOf(d) - 1] ?? 'the start'}; MIS decided:\n${mis.join('\n')}`).toBeGreaterThan(at);
            at = next;
        }
        expect(realDecisions(real, 'DRV').filter((d) => d.startsWith('DRV teleop.FOLLOW active <- TEL:0')).length).toBeGreaterThan(3);
        expect(realDecisions(real, 'DRV').filter((d) => d.startsWith('DRV autonomous.STEER active <- NAV:0')).length).toBeGreaterThan(3);
        expect(counts.get('OBS:0')).toBeGreaterThan(5);
    });

    it('every supervisor took the same decisions, in the same order, with the same causes', () => {
        expect(sim.error).toBeUndefined();
        const simulated = sim.steps.flatMap((s) => s.record.rules);
        for (const sup of SUPERVISORS) {
            expect(simulatedDecisions(simulated, sup), `${sup}; scenario replayed:\n${text}`).toEqual(realDecisions(real, sup));
        }
    });
});
