/**
 * The committed example scenarios pass (examples/<example>/scenarios), and deliberately wrong
 * expectations fail with a message naming the step, the expected and the actual state.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { harnessKey, loadScenario, runLoadedScenario, type PreparedProject } from '../src/index.js';
import { prepared, ROBOT, TUTORIAL } from './support.js';

async function runFile(project: PreparedProject, dir: string, name: string, text?: string) {
    const file = join(dir, 'scenarios', name);
    const s = loadScenario(file, `scenarios/${name}`, text ?? readFileSync(file, 'utf8'), project.index);
    expect(s.diagnostics).toEqual([]);
    return runLoadedScenario(project, s);
}

describe.each([['tutorial', TUTORIAL], ['mobile-robot', ROBOT]])('the %s scenarios', (_name, dir) => {
    const files = readdirSync(join(dir, 'scenarios')).filter((f) => f.endsWith('.scenario'));

    it('are there', () => expect(files.length).toBeGreaterThan(0));

    it.each(files)('%s passes', async (file) => {
        const project = await prepared(dir);
        const r = await runFile(project, dir, file);
        expect(r.error).toBeUndefined();
        expect(r.failures.map((f) => f.message)).toEqual([]);
        expect(r.passed).toBe(true);
        expect(r.steps.filter((s) => s.kind === 'expect').length).toBeGreaterThan(5);
    });
});

describe('a second preparation of the same project', () => {
    it('reuses the built harness (same key, nothing compiled)', async () => {
        const a = await prepared(TUTORIAL);
        const b = await prepared(TUTORIAL);
        expect(b.build.cached).toBe(true);
        expect(harnessKey(b.build.exe)).toBe(harnessKey(a.build.exe));
    });
});

describe('wrong expectations', () => {
    it('fail, naming the step, the expected and the actual state', async () => {
        const project = await prepared(TUTORIAL);
        const text = readFileSync(join(TUTORIAL, 'scenarios', 'commutation.scenario'), 'utf8')
            .replace('expect rule SUP.action.SECOND active', 'expect rule SUP.action.SECOND inactive')
            .replace('expect local SUP.action.failure_data == {"overheat", 3}', 'expect local SUP.action.failure_data == {"overheat", 4}')
            .replace('expect schema schemaCommande2 active', 'expect schema schemaCommande1 active');
        const r = await runFile(project, TUTORIAL, 'commutation.scenario', text);
        expect(r.passed).toBe(false);
        const lineOf = (needle: string) => text.split('\n').findIndex((l) => l.includes(needle)) + 1;
        const lastLineOf = (needle: string) => text.split('\n').length - [...text.split('\n')].reverse().findIndex((l) => l.includes(needle));
        expect(r.failures.map((f) => f.message)).toEqual([
            `scenarios/commutation.scenario:${lineOf('SECOND inactive')}: at 300ms (expect rule SUP.action.SECOND inactive): expected rule SUP.action.SECOND inactive, but it is active`,
            `scenarios/commutation.scenario:${lineOf('{"overheat", 4}')}: at 1200ms (expect local SUP.action.failure_data == {"overheat", 4}): expected SUP.action.failure_data == {"overheat",4}, but it is {dataname="overheat",datavalue=3}`,
            `scenarios/commutation.scenario:${lastLineOf('expect schema schemaCommande1 active')}: at 1200ms (expect schema schemaCommande1 active): expected schema schemaCommande1 active, but it is inactive`,
        ]);
        // the other expectations still pass, and the steps still carry the story
        expect(r.steps.filter((s) => s.kind === 'expect' && s.ok).length).toBe(16);
        const changes = r.steps.flatMap((s) => s.record.rules).map((c) => `${c.rule} ${c.active} ${c.cause}`);
        expect(changes).toContain('SECOND true MAA:2 value="disconnected"');
    });

    it('a count of deadline misses or overruns that is not ORD\'s fails with both figures', async () => {
        const project = await prepared(ROBOT);
        const text = readFileSync(join(ROBOT, 'scenarios', 'modes.scenario'), 'utf8')
            .replace('expect at 1.1s deadline misses velocityLoop == 1', 'expect at 1.1s deadline misses velocityLoop == 2')
            .replace('expect overruns velocityLoop == 1', 'expect overruns velocityLoop == 0');
        const r = await runFile(project, ROBOT, 'modes.scenario', text);
        const lineOf = (needle: string) => text.split('\n').findIndex((l) => l.includes(needle)) + 1;
        expect(r.failures.map((f) => f.message)).toEqual([
            `scenarios/modes.scenario:${lineOf('misses velocityLoop == 2')}: at 1100ms (expect at 1.1s deadline misses velocityLoop == 2): expected deadline misses velocityLoop == 2, but it is 1`,
            `scenarios/modes.scenario:${lineOf('overruns velocityLoop == 0')}: at 1100ms (expect overruns velocityLoop == 0): expected overruns velocityLoop == 0, but it is 1`,
        ]);
    });
});
