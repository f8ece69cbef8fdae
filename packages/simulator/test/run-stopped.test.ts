/**
 * A scenario whose run is stopped short (its wall-time bound) says how far it got: the last step
 * answered and the next one, the virtual time reached of the scenario's, and the expectations it
 * never reached — not "86400s simulated" and "0/0 expectations", as a day of a 100 Hz loop did.
 */
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import { jsonReport, loadScenario, runLoadedScenario, textReport, type PreparedProject } from '../src/index.js';
import { prepared, ROBOT } from './support.js';

let project: PreparedProject;

beforeAll(async () => {
    project = await prepared(ROBOT);
}, 240_000);

describe('a scenario stopped by its wall-time bound', () => {
    it('says the last step it answered, the next one, how far it got, and the expectations not reached', async () => {
        const text = ['scenario a day of the robot', 'until 86400s', 'start MIS.mission()', 'expect at 1ms rule MIS.mission.TELEOP active', 'expect at 86400s rule MIS.mission.TELEOP active', ''].join('\n');
        const s = loadScenario(join(ROBOT, 'scenarios', 'day.scenario'), 'day.scenario', text, project.index);
        expect(s.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
        const r = await runLoadedScenario(project, s, { timeoutMs: 1500 });
        expect(r.passed).toBe(false);
        expect(r.error).toMatch(/^the simulation did not finish within 1\.5 s of wall time: it had answered the steps up to line 4 \(at 1ms of virtual time\), the next one is line 5 at 86400s \(a user function that never returns, or more virtual time than the simulator goes through in that time/);
        expect(r.reachedNs).toBe(1_000_000);
        expect(r.expectationsPlanned).toBe(2);
        const summary = textReport([r]).split('\n').find((l) => /FAILED: /.test(l));
        expect(summary).toMatch(/^ {2}FAILED: 1\/2 expectations \(1 not reached\), 0 failure\(s\); 1ms of 86400000ms simulated in \d+ ms/);
        expect(JSON.parse(jsonReport([r])).scenarios[0]).toMatchObject({ reachedNs: 1_000_000, expectations: 2, endNs: 86_400e9 });
    }, 60_000);
});
