/**
 * A module event's table names the supervisor input port whose deliveries it waits for
 * (`.in_port`): the engines match an event only on deliveries into that port. With one module port
 * subscribed to two input ports, the event's variable decides it. Before, every event of CTL:0 was
 * bound to the first port any rule subscribed CTL:0 to (:2), so the field test's LAND, waiting for
 * `status2` (:3), never fired in a run nor in the simulator.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { EmptyFileSystem } from 'langium';
import { createCactalServices } from '@contract-studio/language';
import { describe, expect, it } from 'vitest';
import { generateFiles } from './generators/generate-files.js';
import { architectureFromModels } from './model/from-langium.js';
import { loadProject } from './test-support/load-project.js';

/** The project (test-support/fixtures/event-in-port, the simulator's event-in-port test runs it too): file name -> text. */
const FIXTURE = join(fileURLToPath(new URL('.', import.meta.url)), 'test-support', 'fixtures', 'event-in-port');
const PROJECT = Object.fromEntries(readdirSync(FIXTURE).map((name) => [name, readFileSync(join(FIXTURE, name), 'utf8')]));

/** The `.in_port` of each module event table of FLT's vocabulary.c, by table name. */
async function eventPorts(): Promise<Record<string, number>> {
    const { models, errors } = await loadProject(createCactalServices(EmptyFileSystem).Cactal, PROJECT);
    expect(errors).toEqual([]);
    const vocabulary = generateFiles(architectureFromModels(models)).find((f) => f.path.endsWith('FLT_mod/vocabulary.c'))!.content;
    const ports: Record<string, number> = {};
    // `static const ContractEvent fly_LAND_post_c0_events[] = {\n    {.kind = CONTRACT_EV_MODULE, .module = "CTL", .port = 0, .in_port = 3, ...`
    for (const m of vocabulary.matchAll(/(\w+)_c0_events\[\d*\] = \{\s*\{\.kind = CONTRACT_EV_MODULE, \.module = "CTL", \.port = 0, \.in_port = (-?\d+)/g)) ports[m[1]!] = Number(m[2]);
    return ports;
}

describe('the input port of a module event in the supervisor tables', () => {
    it('is the one of the subscribe that delivers into the variable the event reads; any of them when it reads none, or both', async () => {
        expect(await eventPorts()).toEqual({
            fly_HOLD_post: 2,
            fly_LAND_post: 3, // reads status2: the deliveries into :3 (was 2: never matched)
            fly_SEEN_pre: -1, // reads no port variable: a delivery into either
            fly_BOTH_pre: -1, // reads both (warned: supervisor-event-variable)
        });
    });
});
