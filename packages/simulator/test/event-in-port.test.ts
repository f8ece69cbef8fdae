/**
 * One module port subscribed to two supervisor input ports, by two rules (the field test's HOLD on
 * :2, LAND on :3 after it): an event that reads an input port's variable waits for the deliveries
 * into that port. Before, every CTL:0 event was bound to :2 (the first subscribe of CTL:0), so
 * LAND, waiting for `status2`, never ended: CTL's "landed" came in on :3 and matched nothing.
 */
import { cpSync, mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { loadScenario, runLoadedScenario, type PreparedProject } from '../src/index.js';
import { prepared, REPO } from './support.js';

/** The project, codegen's test fixture (its event-in-port test checks the tables generated from it). */
const FIXTURE = join(REPO, 'packages', 'codegen', 'src', 'test-support', 'fixtures', 'event-in-port');

let dir: string;
let project: PreparedProject;

beforeAll(async () => {
    dir = mkdtempSync(join(tmpdir(), 'sim-event-in-port-'));
    mkdirSync(join(dir, 'scenarios'));
    cpSync(FIXTURE, dir, { recursive: true });
    project = await prepared(dir);
}, 240_000);
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('an event of a module port subscribed to two input ports', () => {
    it('waits for the deliveries into the port whose variable it reads', async () => {
        const text = [
            'start FLT.fly()',
            'expect at 5ms rule FLT.fly.HOLD active',
            't=10ms CTL:0 status = "low"',
            'expect rule FLT.fly.HOLD inactive',
            'expect rule FLT.fly.LAND active',
            // LAND subscribed CTL:0 to :3: this one comes in on :3, into status2
            't=20ms CTL:0 status = "landed"',
            'expect rule FLT.fly.LAND inactive',
            'expect local FLT.fly.last == "landed"',
        ].join('\n');
        const s = loadScenario(join(dir, 'scenarios', 'land.scenario'), 'land.scenario', text, project.index);
        expect(s.diagnostics).toEqual([]);
        const r = await runLoadedScenario(project, s);
        expect(r.error).toBeUndefined();
        expect(r.failures.map((f) => f.message)).toEqual([]);
    });
});
