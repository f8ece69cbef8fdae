/**
 * A module event's table names the supervisor input port whose deliveries it waits for
 * (`.in_port`): the engines match an event only on deliveries into that port. With one module port
 * subscribed to two input ports, the event's variable decides it. Before, every event of CTL:0 was
 * bound to the first port any rule subscribed CTL:0 to (:2), so the field test's LAND, waiting for
 * `status2` (:3), never fired in a run nor in the simulator.
 */
import { EmptyFileSystem } from 'langium';
import { createCactalServices } from '@contract-studio/language';
import { describe, expect, it } from 'vitest';
import { generateFiles } from './generators/generate-files.js';
import { architectureFromModels } from './model/from-langium.js';
import { loadProject } from './test-support/load-project.js';

const PROJECT = {
    'ctl.contract': 'asynchronous module CTL { event flows { out :0 string status; } }',
    'flt.contract': `import "ctl.contract";
supervisor FLT {
    event flows { in :2 string status; in :3 string status2; }
    fly() {
        local { string last; }
        rules {
            HOLD: [elapsed=2ms] subscribe CTL:0 =* :2; activate resttime module CTL [CTL:0<status == "low">]
            LAND: [endof(HOLD)] subscribe CTL:0 =* :3 [CTL:0<status2 == "landed">(last = status2)]
            SEEN: [CTL:0] [duration(SEEN)=1ms]
            BOTH: [CTL:0<status == "x" | status2 == "y">] [duration(BOTH)=1ms]
        }
    }
}`,
};

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
