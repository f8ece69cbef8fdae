/**
 * `contract simulate --trace` of the tutorial with MAB's handler taking 2 ms an event (`exec MAB
 * 2ms`), then `contract trace` of that trace: MAB's event_received / event_handled records are in
 * it, and the story ends with what MAB handled — the events, the handling time's p99 and max, the
 * longest with its event and when it was received. Before, the simulator wrote no event_handled
 * and `contract trace` told nothing of it.
 */
import { cpSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';
import { toldTrace } from './told-trace.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
const MESSAGE = 'MAA:0 message_type_notification = {"hello", 2, {0.5, 0.5, 0.5}}';
const SCENARIO = `scenario MAB handles MAA's messages, one of them for longer
until 1s
finish MAB after 0
exec MAB 2ms
start SUP.action(consigne = {1.0, 2.0, 3.0})
t=100ms ${MESSAGE}
t=200ms ${MESSAGE}
exec MAB 5ms once
t=250ms ${MESSAGE}
t=260ms ${MESSAGE}
`;

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-simulate-event-handling-');
    cpSync(TUTORIAL, join(root, 'tutorial'), { recursive: true, filter: (src) => !src.includes(`${join(TUTORIAL, 'logs')}`) });
    writeFileSync(join(root, 'handling.scenario'), SCENARIO);
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe("contract trace of a simulation where an asynchronous module handles events", { timeout: 120_000 }, () => {
    it("tells MAB's events handled, p99 and max of their handling, and the longest with its event and time", async () => {
        const io = capture(root);
        expect(await runCli(['simulate', 'tutorial', 'handling.scenario', '--trace', 'handling.jsonl'], io), io.stdout + io.stderr).toBe(0);
        const { story, json } = await toldTrace(root, 'handling.jsonl');
        const handled = json.filter((r) => r['kind'] === 'event_handled' && r['module'] === 'MAB');
        expect(handled.map((r) => [r['monoNs'], (r['fields'] as Record<string, unknown>)['handling_ns']])).toEqual([
            ['102000000', 2_000_000], ['202000000', 2_000_000], ['255000000', 5_000_000], ['262000000', 2_000_000],
        ]);
        expect(story).toMatch(/^MAB handled 4 events: handling p99 5 ms, max 5 ms; the longest, MAA:0 -> MAB:0 received at \+0\.250000s, 5 ms$/m);
    });
});
