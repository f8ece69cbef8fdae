/**
 * A real run (bwrap) of an event flow a supervisor connects whose producer never posts: MIS's rule
 * mission.RELAY activates the event schema relay, which connects PRD:0 =* CNS:0, and PRD's exec
 * region never calls PostEvent. `contract trace` tells the flow at the end with who connected it,
 * as it tells a data flow ORD connected that delivered nothing; `--format json` holds the records
 * that say it (the connect action after the rule's line, and no post of PRD's).
 */
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const FILES: Record<string, string> = {
    'producer.contract': 'asynchronous module PRD {\n    event flows { out :0 float reading; }\n}\n',
    'consumer.contract': 'asynchronous module CNS {\n    event flows { in :0 float reading; }\n}\n',
    'relay.contract': 'import "producer.contract";\nimport "consumer.contract";\n\nevent schema relay() {\n    modules { PRD (); CNS (); }\n    communications { PRD:0 =* CNS:0; }\n}\n',
    'supervisor.contract': 'import "relay.contract";\n\nsupervisor MIS {\n    event flows { in :0 string status; }\n    mission() {\n        rules {\n' +
        '            RELAY: [elapsed=1ms] activate schema relay() [elapsed=10s]\n        }\n    }\n}\n',
};

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-silent-event-flow-');
    expect(await runCli(['new', 'relay'], capture(root))).toBe(0);
    for (const [name, text] of Object.entries(FILES)) writeFileSync(join(root, 'relay', name), text);
    const io = capture(root);
    expect(await runCli(['run', 'relay', '--sandbox', 'bwrap', '--duration', '2s', '--logs', 'relay-logs', '--cpus', '1'], io)).toBe(0);
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('an event flow a supervisor connected whose producer never posts, in a real run', () => {
    it('is told at the end of the story with its schema and who connected it, and counted', async () => {
        const io = capture(root);
        expect(await runCli(['trace', 'relay-logs'], io)).toBe(0);
        const lines = io.stdout.split('\n');
        const told = lines.filter((l) => l.startsWith('event flow '));
        expect(told).toHaveLength(1);
        const m = /^event flow PRD:0 =\* CNS:0 connected for (\d+(?:\.\d+)?) s \(schema relay, connected by MIS's rule mission\.RELAY\): 0 events delivered \(PRD posted none on its output :0\); CNS received nothing$/.exec(told[0]!);
        expect(m, told[0]).not.toBeNull();
        // connected from RELAY's start (1 ms in) to the run's stop (2 s)
        expect(Number(m![1])).toBeGreaterThan(1.5);
        expect(Number(m![1])).toBeLessThan(3);
        expect(lines.find((l) => / records: /.test(l))).toContain(', 1 event flow a supervisor connected that delivered nothing, ');
    }, 60_000);

    it('--format json holds the records that tell it: the rule, then its connect action, and no post of PRD', async () => {
        const io = capture(root);
        expect(await runCli(['trace', 'relay-logs', '--format', 'json'], io)).toBe(0);
        const records = io.stdout.trim().split('\n').map((l) => JSON.parse(l) as { kind: string; module: string; fields?: Record<string, unknown> });
        const mis = records.filter((r) => r.module === 'MIS' && r.kind === 'supervisor');
        const at = mis.findIndex((r) => r.fields?.['action'] === 'connect');
        expect(mis[at]!.fields).toMatchObject({ module: 'PRD', port: 0, to_module: 'CNS', to_port: 0 });
        expect(mis.slice(0, at).filter((r) => r.fields?.['what'] === 'rule').at(-1)!.fields).toMatchObject({ function: 'mission', rule: 'RELAY', state: 'active' });
        expect(records.filter((r) => r.module === 'PRD' && r.kind === 'event_posted')).toEqual([]);
    }, 60_000);
});
