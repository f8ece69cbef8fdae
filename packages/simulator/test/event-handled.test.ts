/**
 * An asynchronous module's handler in the simulation: each event an event flow brings it (the
 * tutorial's `MAA:0 =* MAB:0` of schemaReceptionMessage) is taken (`event_received`) and handled
 * for `exec M TIME` of virtual time, then ended (`event_handled`, `handling_ns`), as libmodule
 * writes them when the module reads its mailbox again (docs/runtime-api.md). One at a time: an
 * event that comes while the handler runs is taken when it ends. A disconnected flow brings
 * nothing; a module that crashed while handling never ends it.
 */
import { describe, expect, it } from 'vitest';
import type { KnownRecord } from '@contract-studio/build-service/trace';
import { loadScenario, runLoadedScenario } from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { prepared, TUTORIAL } from './support.js';

const MESSAGE = 'message_type_notification = {"hello", 2, {0.5, 0.5, 0.5}}';

async function mabRecords(lines: string[]): Promise<string[]> {
    const project = await prepared(TUTORIAL);
    const s = loadScenario('handled.scenario', 'handled.scenario', ['until 1s', 'finish MAB after 0', 'start SUP.action(consigne = {1.0, 2.0, 3.0})', ...lines].join('\n'), project.index);
    expect(s.diagnostics).toEqual([]);
    const r = await runLoadedScenario(project, s);
    expect(r.error).toBeUndefined();
    expect(r.failures.map((f) => f.message)).toEqual([]);
    return (stepsToTrace(r.steps.map(traceStepOf)) as KnownRecord[])
        .filter((x) => x.module === 'MAB' && (x.kind === 'event_received' || x.kind === 'event_handled'))
        .map((x) => `${Number(x.monoNs) / 1e6}ms ${x.kind} ${x.peer}:${x.port} ${x.detail}`);
}

describe("an asynchronous module's handling of the events of its event flows", () => {
    it('takes each event, handles it for its exec time, one at a time, and writes event_handled when it ends', async () => {
        expect(await mabRecords(['exec MAB 2ms', `t=100ms MAA:0 ${MESSAGE}`, `MAA:0 ${MESSAGE}`, 'exec MAB 500us once', `t=200ms MAA:0 ${MESSAGE}`, `t=250ms MAA:0 ${MESSAGE}`])).toEqual([
            '100ms event_received MAA:0 from_port=0 latency_ns=0',
            '102ms event_handled MAA:0 from_port=0 handling_ns=2000000',
            // the second event of t=100ms waited for the first's handler
            '102ms event_received MAA:0 from_port=0 latency_ns=0',
            '104ms event_handled MAA:0 from_port=0 handling_ns=2000000',
            '200ms event_received MAA:0 from_port=0 latency_ns=0',
            '200.5ms event_handled MAA:0 from_port=0 handling_ns=500000',
            '250ms event_received MAA:0 from_port=0 latency_ns=0',
            '252ms event_handled MAA:0 from_port=0 handling_ns=2000000',
        ]);
    }, 240_000);

    it('counts the module among those an event was delivered to (the report says nobody received it only when no supervisor nor flow took it)', async () => {
        const project = await prepared(TUTORIAL);
        const s = loadScenario('d.scenario', 'd.scenario', ['finish MAB after 0', 'start SUP.action(consigne = {1.0, 2.0, 3.0})', `t=100ms MAA:0 ${MESSAGE}`, 't=300ms MAA:2 "disconnected"', `t=400ms MAA:0 ${MESSAGE}`].join('\n'), project.index);
        const r = await runLoadedScenario(project, s);
        // at 100 ms SUP (subscribed to MAA:0) and MAB (MAA:0 =* MAB:0); at 400 ms neither: FIRST's undo ended both
        expect(r.steps.filter((x) => x.kind === 'event').map((x) => x.record.delivered)).toEqual([2, 1, 0]);
    }, 240_000);

    it('takes no event once the flow is disconnected (SUP undoes schemaReceptionMessage on "disconnected"), and a handler whose module crashed never ends', async () => {
        expect(await mabRecords([`t=100ms MAA:0 ${MESSAGE}`, 't=300ms MAA:2 "disconnected"', `t=400ms MAA:0 ${MESSAGE}`])).toEqual([
            '100ms event_received MAA:0 from_port=0 latency_ns=0',
            '100ms event_handled MAA:0 from_port=0 handling_ns=0',
        ]);
        expect(await mabRecords(['exec MAB 5ms', `t=100ms MAA:0 ${MESSAGE}`, 't=101ms crash MAB'])).toEqual([
            '100ms event_received MAA:0 from_port=0 latency_ns=0',
        ]);
    }, 240_000);
});
