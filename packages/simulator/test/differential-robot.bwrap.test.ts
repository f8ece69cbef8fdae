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
 *   as causes; a miss that made MIS stop DRV.autonomous before its LOOPS' 1 ms came (DRV got the
 *   START late) is replayed as soon after the start as DRV really ran (replay-run.ts shortRuns);
 * - the end: the launcher stops the supervisors a few microseconds apart; a request MIS sent DRV
 *   just before (STOP safestop as the way clears) may never reach it, where the simulator delivers
 *   it at once: the comparison then ends before MIS's decision (replay-run.ts endBeforeUnreceived);
 * - values: OBS:0 distances that changed a rule are named by their cause (`value=0.35`, `value=5.0`);
 *   those that changed none are replayed as 0.75, a distance that neither starts a safe stop
 *   (< 0.5) nor ends one (> 1.0), whatever the mode (the real one was 5 in AUTO or 0.35 in STOP:
 *   changing nothing either); joystick and navigation commands are `Twist` datatypes, logged
 *   field by field (`{v=0.3,w=0}`) and replayed with that value when they changed a rule, else as
 *   {0.0, 0.0}: the rules test only `v > 100.0` (false for both) and store them;
 * - OBS:1 laser scans (180 beams) are logged abridged (`{ranges=[5,5,...],blocked=true}`): a scan
 *   that changed a rule is rebuilt as OBS sends it (beams 80 to 100 at 0.35 m when blocked, every
 *   other beam at 5 m), so the simulator's cause prints as the real one; a scan that changed none is
 *   replayed with the beam ahead at 0.75 m, neither starting AHEAD (< 0.5) nor ending it (> 1.0).
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { RuleRecord } from '@contract-studio/build-service/trace';
import type { ScenarioResult } from '../src/index.js';
import { ROBOT } from './support.js';
import { firstDifference, realDecisions, replayInSimulator, runForReal, simulatedDecisions, type RealRun } from './differential/replay-run.js';

const SUPERVISORS = new Set(['MIS', 'DRV']);
/** A LaserScan value in scenario syntax: 180 beams, then `blocked`. */
const scan = (range: (beam: number) => number, blocked: boolean): string =>
    `{{${Array.from({ length: 180 }, (_, i) => range(i).toFixed(2)).join(', ')}}, ${blocked}}`;
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
    let adjustments: string[];

    beforeAll(async () => {
        expect(run.code, run.output).toBe(0);
        let diagnostics: unknown[];
        ({ text, real, counts, adjustments, sim, diagnostics } = await replayInSimulator(ROBOT, run.records, {
            supervisors: SUPERVISORS,
            start: 'MIS.mission()',
            // mission.contract: TELEOP, AUTO and STOP each `activate supervisor DRV.…()`
            requestRules: { DRV: ['MIS mission.TELEOP', 'MIS mission.AUTO', 'MIS mission.STOP'] },
            fallback: (module, port) => (module === 'OBS' && port === 0 ? '0.75' : module === 'OBS' && port === 1 ? scan((i) => (i === 90 ? 0.75 : 5), false) : undefined),
            causeValue: (module, port, logged) => {
                if (module !== 'OBS' || port !== 1) return undefined;
                const blocked = /blocked=true/.test(logged);
                return scan((i) => (blocked && i >= 80 && i <= 100 ? 0.35 : 5), blocked);
            },
        }));
        expect(diagnostics, text).toEqual([]);
    }, 120_000);

    // which ends AUTO first, the obstacle (0.35 m) or a deadline miss, is timing: either is a safe stop
    it('the run went through its modes: teleop, autonomous on "auto", a safe stop, autonomous again when the way is clear', () => {
        const mis = realDecisions(real, 'MIS');
        const order = ['MIS mission.TELEOP active <- started(LINK)', 'MIS mission.AUTO active <- TEL:1 value="auto"', 'MIS mission.STOP active <- endof(AUTO)', 'MIS mission.STOP inactive <- OBS:0 value=5.0', 'MIS mission.AUTO active <- endof(STOP)'];
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
            const got = simulatedDecisions(simulated, sup);
            const want = realDecisions(real, sup);
            expect(got, firstDifference(sup, got, want, text, adjustments)).toEqual(want);
        }
    });
});
