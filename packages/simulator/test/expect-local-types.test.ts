/**
 * `expect local` on the extension types (docs/simulation.md "Values and names"): an enumeration
 * local (`== Mode.FAST`), a string with escapes (`"say \\"hi\\""`), a bool and an array compare by value, like a struct local
 * that holds them; a value of the wrong member fails with the actual value, not an error.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { PROJECT_TEMPLATES } from '@contract-studio/language';
import { loadScenario, runLoadedScenario, type PreparedProject } from '../src/index.js';
import { prepared } from './support.js';

let dir: string;
let project: PreparedProject;

beforeAll(async () => {
    dir = mkdtempSync(join(tmpdir(), 'sim-locals-'));
    for (const [name, text] of Object.entries(PROJECT_TEMPLATES)) writeFileSync(join(dir, name), text);
    writeFileSync(join(dir, 'datatype.contract'), PROJECT_TEMPLATES['datatype.contract']! +
        'enum LineMode { SLOW, FAST };\ndatatype Report {string what, LineMode mode = LineMode.SLOW, bool ok = false};\n');
    writeFileSync(join(dir, 'supervisor.contract'), PROJECT_TEMPLATES['supervisor.contract']!.replace(
        'local { Position target = goal; string last; }',
        'local { Position target = goal; string last; LineMode m = LineMode.FAST; bool on = true; float[3] gains = {0.5, 1.0, 2.0}; float speed = 0.8; float whole = 2.0; Report r = {"x", LineMode.FAST, true}; string note = "say \\"hi\\" a\\\\b"; }'));
    project = await prepared(dir);
}, 240_000);
afterAll(() => rmSync(dir, { recursive: true, force: true }));

async function run(text: string) {
    const s = loadScenario(join(dir, 'locals.scenario'), 'locals.scenario', text, project.index);
    expect(s.diagnostics).toEqual([]);
    return runLoadedScenario(project, s);
}

describe('expect local on enumerations, bools and arrays', () => {
    it('compares them by value', async () => {
        const r = await run([
            'start MIS.mission()',
            'expect at 2ms local MIS.mission.m == LineMode.FAST',
            'expect local MIS.mission.on == true',
            'expect local MIS.mission.gains == {0.5, 1.0, 2.0}',
            'expect local MIS.mission.r == {"x", LineMode.FAST, true}',
            // a string written with the language's escapes, in the .contract and in the scenario
            'expect local MIS.mission.note == "say \\"hi\\" a\\\\b"',
        ].join('\n'));
        expect(r.error).toBeUndefined();
        expect(r.failures.map((f) => f.message)).toEqual([]);
        expect(r.passed).toBe(true);
    });

    it('shows a float local as Cactal writes it (0.8, 2.0), not with a double\'s 17 digits', async () => {
        const r = await run(['start MIS.mission()', 'expect at 2ms local MIS.mission.speed == 0.8'].join('\n'));
        expect(r.passed).toBe(true);
        const locals = r.steps.at(-1)!.record.locals ?? [];
        expect(locals.find((l) => l.name === 'speed')).toMatchObject({ type: 'float', value: '0.8' });
        expect(locals.find((l) => l.name === 'whole')).toMatchObject({ type: 'float', value: '2.0' });
    });

    it('a wrong value fails with the actual one', async () => {
        const r = await run(['start MIS.mission()', 'expect at 2ms local MIS.mission.m == LineMode.SLOW', 'expect local MIS.mission.gains == {0.5, 1.0, 3.0}'].join('\n'));
        expect(r.passed).toBe(false);
        expect(r.failures.map((f) => [f.record.expected, f.record.actual, f.record.error ?? ''])).toEqual([
            ['MIS.mission.m == LineMode.SLOW', 'FAST', ''],
            ['MIS.mission.gains == {0.5,1.0,3.0}', expect.stringContaining('0.5'), ''],
        ]);
    });
});
