/**
 * The differential test's race, on a recorded bwrap run of the tutorial where it happened: the
 * Monitor's fixture run (packages/web-ide/src/monitor/fixtures/tutorial-run, read from there: MAA's
 * script ended its run 0.67 ms after SUP received its "disconnected", while SUP's STOP of it was on
 * its way; the first test fails, saying so, should that fixture be recorded again without the
 * race): the scenario replays MAA's
 * end before that event (replay-run.ts ownEndBeforeStop), and the simulator takes the same
 * supervisor decisions and tells the same runs ended by their own code. The live run of
 * differential.bwrap.test.ts meets this race about 1 time in 8; here it is met every time.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { parseTrace, renderStory, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import type { ScenarioResult } from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { REPO, TUTORIAL } from './support.js';
import { firstDifference, realDecisions, replayInSimulator, simulatedDecisions, TUTORIAL_PLAN } from './differential/replay-run.js';

const FIXTURE = join(REPO, 'packages/web-ide/src/monitor/fixtures/tutorial-run');
const SUPERVISORS = TUTORIAL_PLAN.supervisors;
const records = parseTrace(readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') })));
const ownRunEnds = (rs: TraceRecord[]): string[] => renderStory(rs).filter((l) => l.includes(' ended by its own code ')).map((l) => l.slice(11));

describe('simulator vs a recorded run of the tutorial where MAA ended its run before SUP\'s STOP reached it', () => {
    let sim: ScenarioResult;
    let real: RuleRecord[];
    let text: string;
    let adjustments: string[];

    beforeAll(async () => {
        let diagnostics: unknown[];
        ({ text, real, adjustments, sim, diagnostics } = await replayInSimulator(TUTORIAL, records, TUTORIAL_PLAN));
        expect(diagnostics, text).toEqual([]);
    }, 120_000);

    it('replays MAA\'s end before the "disconnected" SUP decided on, and says so', () => {
        const lines = text.split('\n');
        const finish = lines.findIndex((l) => / finish MAA$/.test(l));
        expect(finish, text).toBeGreaterThan(0);
        expect(lines[finish + 1], text).toMatch(/ MAA:2 "disconnected"$/);
        expect(adjustments.filter((a) => a.startsWith('finish MAA: moved')), `the fixture run no longer holds the race (MAA's run ended while SUP's STOP of it was on its way)?\n${adjustments.join('\n')}`).toHaveLength(1);
    });

    it('the simulator takes the same decisions and tells the same own run ends', () => {
        expect(sim.error, text).toBeUndefined();
        const simulated = sim.steps.flatMap((s) => s.record.rules);
        for (const sup of SUPERVISORS) {
            const got = simulatedDecisions(simulated, sup);
            const want = realDecisions(real, sup);
            expect(got, firstDifference(sup, got, want, text, adjustments)).toEqual(want);
        }
        expect(realDecisions(real, 'SUP')).toContain('SUP action.SECOND active <- MAA:2 value="disconnected"');
        const known = records.filter((r): r is KnownRecord => r.kind !== 'unknown');
        const stop = known.find((r) => r.kind === 'request_received' && r.peer === 'contract-launch' && /^(STOP|KILL)/.test(r.detail));
        const want = ownRunEnds(known.filter((r) => BigInt(r.monoNs) < BigInt(stop!.monoNs)));
        expect(want).toContain('MAA  run #1 ended by its own code (started by SUP)');
        expect(ownRunEnds(stepsToTrace(sim.steps.map(traceStepOf))), text).toEqual(want);
        expect(sim.failures.map((f) => f.message), text).toEqual([]);
    });
});
