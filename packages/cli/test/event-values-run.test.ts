/**
 * A real run (bwrap) of a field tester's line follower (supervisor LFR, rules LINK/FOLLOW/SEARCH,
 * CAM:0 carrying "lost"/"found"): `follow` feeds MOT:0 from CTL, `search` from SRC, never active
 * together. Before, each schema switch printed `MOT: warning: input data port 0 now fed by SRC`
 * on stderr though the design is right; and with the rule's "lost" mistyped "lsot", nothing in
 * the run's story said that CAM's events arrived and changed no rule, nor their values.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { lineFollower } from './line-follower.js';
import { toldTrace } from './told-trace.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

let root: string;

beforeAll(async () => {
    root = await makeSeededScratch('contract-event-values-');
    await lineFollower(root, 'linebot', 'lost');
    await lineFollower(root, 'typo', 'lsot');
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('a line follower whose schemas feed MOT:0 from CTL and from SRC, in a real run', () => {
    it('switches schemas with no stderr warning; the trace tells each change of producer as a plain line', async () => {
        const check = capture(root);
        expect(await runCli(['check', 'linebot'], check)).toBe(0);
        const io = capture(root);
        expect(await runCli(['run', 'linebot', '--sandbox', 'bwrap', '--duration', '2500ms', '--logs', 'linebot-logs', '--cpus', '1'], io)).toBe(0);
        expect(io.stdout).toContain('[LFR] rule drive.SEARCH active');
        expect(io.stdout + io.stderr).not.toContain('warning: input data port');
        const mot = readFileSync(join(root, 'linebot-logs', readdirSync(join(root, 'linebot-logs')).find((f) => f.startsWith('MOT_'))!), 'utf8');
        expect(mot).toContain(',MOT,producer_changed,SRC,0,16,was CTL: a new producer (a schema switch)');
        expect(mot).not.toContain('interleaved');
        const { story } = await toldTrace(root, join(root, 'linebot-logs'));
        expect(story).toMatch(/MOT {2}input MOT:0 now fed by SRC \(was CTL\): a schema switch/);
        expect(story).toMatch(/^input MOT:0 changed producer \d+ times \(CTL, SRC\)$/m);
        expect(story).not.toContain('warning: input MOT:0');
    }, 240_000);

    it('with the rule waiting for "lsot": the story tells the "lost" and "found" that changed no rule, with their counts', async () => {
        const io = capture(root);
        expect(await runCli(['run', 'typo', '--sandbox', 'bwrap', '--duration', '2500ms', '--logs', 'typo-logs', '--cpus', '1'], io)).toBe(0);
        expect(io.stdout).not.toContain('[LFR] rule drive.SEARCH active');
        const { story, json } = await toldTrace(root, join(root, 'typo-logs'));
        expect(story).toMatch(/LFR {2}received CAM:0 = "lost": it changed no rule/);
        expect(story).toMatch(/LFR {2}received CAM:0 = "found": it changed no rule/);
        const counted = /^LFR got CAM:0 ×(\d+) that changed no rule: "lost" ×(\d+), "found" ×(\d+)$/m.exec(story);
        expect(counted).not.toBeNull();
        expect(Number(counted![1])).toBe(Number(counted![2]) + Number(counted![3]));
        expect(Number(counted![2])).toBeGreaterThanOrEqual(1);
        const delivered = json.filter((r) => r['kind'] === 'event_received' && r['module'] === 'LFR');
        expect(delivered.length).toBe(Number(counted![1]));
        expect(delivered[0]).toMatchObject({ peer: 'CAM', port: 0, fields: { from_port: 0, rules: 0, value: '"lost"' } });
    }, 240_000);
});
