/**
 * `contract simulate --trace` of the tutorial keeping the event schema's flow MAA:0 =* MAB:0
 * connected 1.5 s (a scenario's message of MAA reaches MAB on it) and then schemaCommande1's data
 * flows 2 s, read by `contract trace`: a simulation runs no module code, so no flow finding blames
 * module code — before, the story said `MSC never read its input :0: GetData or GetLatestData`
 * and `0 events delivered (MAA posted none on its output :0); MAB received nothing` (MAB did
 * receive the scenario's message). The same findings are still made of real recorded runs (the
 * Monitor's fixtures silent-flow-run and silent-event-flow-run, `contract run` logs).
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
const FIXTURES = fileURLToPath(new URL('../../web-ide/src/monitor/fixtures', import.meta.url));
const SCENARIO = `scenario the event schema's flow MAA:0 =* MAB:0 for 1.5 s, then schemaCommande1's data flows for 2 s
until 3.5s
finish MAB after 0
start SUP.action(consigne = {1.0, 2.0, 3.0})
expect at 1ms rule SUP.action.FIRST active
t=100ms MAA:0 message_type_notification = {"hello", 2, {0.5, 0.5, 0.5}}
t=1.5s MAA:2 connection_status = "disconnected"
expect rule SUP.action.SECOND active
expect schema schemaCommande1 active
`;
/** The findings of flows that delivered nothing, as `contract trace` words them. */
const SILENT = /never read its input|posted none|received nothing|that delivered nothing/;

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-simulate-flows-');
    cpSync(TUTORIAL, join(root, 'tutorial'), { recursive: true, filter: (src) => !src.includes(`${join(TUTORIAL, 'logs')}`) });
    writeFileSync(join(root, 'flows.scenario'), SCENARIO);
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('contract trace of a simulation does not blame module code that never ran', { timeout: 120_000 }, () => {
    it('tells no silent data flow nor event flow, and says why once', async () => {
        const io = capture(root);
        expect(await runCli(['simulate', 'tutorial', 'flows.scenario', '--trace', 'flows.jsonl'], io), io.stdout + io.stderr).toBe(0);
        const { story, json } = await toldTrace(root, 'flows.jsonl');
        // the trace has what the old findings were made of: flows connected over 1 s, values posted, MAB's event received, no data read
        const kinds = json.map((r) => r['kind']);
        expect(kinds).toContain('data_posted');
        expect(json.some((r) => r['kind'] === 'event_received' && r['module'] === 'MAB')).toBe(true);
        expect(kinds).not.toContain('data_received');
        expect(story).toMatch(/connect MSA:0 -> MSC:0/);
        expect(story).toMatch(/connect MAA:0 =\* MAB:0/);
        expect(story.split('\n').filter((l) => SILENT.test(l))).toEqual([]);
        expect(story).toContain('\na simulation runs no module code: data values are not simulated, nor the events its modules post: what 2 data flows and 1 event flow connected over 1 s delivered is not told\n');
        expect(story).toMatch(/^MAB handled 1 event: /m);
    });

    it('still tells the silent flows of real recorded runs', async () => {
        const data = await toldTrace(root, join(FIXTURES, 'silent-flow-run'));
        expect(data.story).toContain('data flow SRT:1 -> BLT:0 connected for 3.705 s (schema sortLoop): 0 values delivered (SRT posted none on its output :1); BLT read nothing in its 529 releases\n');
        expect(data.story).toContain("data flow CAM:0 -> SRT:0 connected for 3.705 s (schema sortLoop): 26 values delivered (7 a second), read 26 times in SRT's 529 releases (140 a second): 1 value for 20 releases\n");
        expect(data.story).toMatch(/1 data flow that delivered nothing, 1 data flow written far less often than read, /);
        expect(data.story).not.toContain('a simulation runs no module code');
        const events = await toldTrace(root, join(FIXTURES, 'silent-event-flow-run'));
        expect(events.story).toContain("event flow PRD:0 =* CNS:0 connected for 3.002 s (schema relay, connected by MIS's rule mission.RELAY): 0 events delivered (PRD posted none on its output :0); CNS received nothing\n");
        expect(events.story).toMatch(/1 event flow a supervisor connected that delivered nothing, /);
    });
});
