/**
 * `contract simulate --trace` of the field tester's line follower (line-follower.ts) whose FOLLOW
 * rule waits for "lsot" while the camera sends "lost": `contract trace` of the simulated trace tells
 * the events that changed no rule, with their values and counts, as it tells them of the real run
 * (event-values-run.test.ts). Before, the simulator's `event_received` records had no `rules=` and
 * no value, so the story of a simulation said nothing of them.
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { lineFollower } from './line-follower.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';
import { toldTrace } from './told-trace.js';

/** The camera as in the real run: it loses the line for 0.3 s every 1.2 s. */
const SCENARIO = `scenario the camera loses the line and finds it again
until 2500ms
start LFR.drive()
t=400ms CAM:0 status = "lost"
t=700ms CAM:0 status = "found"
t=1600ms CAM:0 status = "lost"
t=1900ms CAM:0 status = "found"
`;

let root: string;

/** Simulates project `name` with SCENARIO (plus `expect` lines), --trace NAME.jsonl, and tells the trace. */
async function simulated(name: string, expectations: string): Promise<{ story: string; json: Record<string, unknown>[] }> {
    mkdirSync(join(root, name, 'scenarios'), { recursive: true });
    writeFileSync(join(root, name, 'scenarios', 'camera.scenario'), SCENARIO + expectations);
    const io = capture(root);
    expect(await runCli(['simulate', name, `${name}/scenarios/camera.scenario`, '--trace', `${name}.jsonl`], io), io.stdout + io.stderr).toBe(0);
    return toldTrace(root, `${name}.jsonl`);
}

beforeAll(async () => {
    root = await makeSeededScratch('contract-simulate-event-values-');
    await lineFollower(root, 'linebot', 'lost');
    await lineFollower(root, 'typo', 'lsot');
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('contract trace of a simulated line follower', { timeout: 120_000 }, () => {
    it('with the rule waiting for "lsot": the story tells the "lost" and "found" that changed no rule, with their counts, as for the real run', async () => {
        const { story, json } = await simulated('typo', 'expect rule LFR.drive.FOLLOW active\nexpect rule LFR.drive.SEARCH inactive\n');
        expect(story).toContain('+0.400000s LFR  received CAM:0 = "lost": it changed no rule (no active rule waited for this value); later ones are counted at the end');
        expect(story).toContain('+0.700000s LFR  received CAM:0 = "found": it changed no rule (no active rule waited for this value); later ones are counted at the end');
        expect(story).toMatch(/^LFR got CAM:0 ×4 that changed no rule: "lost" ×2, "found" ×2$/m);
        const delivered = json.filter((r) => r['kind'] === 'event_received' && r['module'] === 'LFR');
        expect(delivered).toHaveLength(4);
        expect(delivered[0]).toMatchObject({ peer: 'CAM', port: 0, monoNs: '400000000', fields: { from_port: 0, latency_ns: 0, taken_ns: 400000000, rules: 0, value: '"lost"' } });
    });

    it('with the rule waiting for "lost": each event changed rules (rules=2: one ends, the next begins), and the story tells none as changing no rule', async () => {
        const { story, json } = await simulated('linebot', 'expect rule LFR.drive.FOLLOW active\n');
        expect(story).not.toContain('changed no rule');
        const delivered = json.filter((r) => r['kind'] === 'event_received' && r['module'] === 'LFR');
        expect(delivered.map((r) => (r['fields'] as Record<string, unknown>)['value'])).toEqual(['"lost"', '"found"', '"lost"', '"found"']);
        expect(delivered.map((r) => (r['fields'] as Record<string, unknown>)['rules'])).toEqual([2, 2, 2, 2]);
    });
});
