/**
 * A real run (bwrap) of the field test's defect: one module port (CTL:0) subscribed to two input
 * ports of the supervisor, HOLD's on :0 and LAND's on :1 after HOLD's end; LAND ends on
 * `CTL:0<status2 == "landed">`, status2 being the variable of :1. Before, the generated tables
 * bound every CTL:0 event to :0 (the first subscribe of CTL:0), so the "landed" that came in on :1
 * matched nothing: LAND never ended, with no warning.
 */
import { readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const SUPERVISOR = `import "datatype.contract";
import "module2.contract";
import "schema.contract";
import "sched.contract";

supervisor MIS {
    event flows { in :0 string status; in :1 string status2; }
    mission(Position goal = {1.0, 2.0, 0.0}) {
        local { Position target = goal; string last; }
        rules {
            FLY: [elapsed=1ms] activate schema goTo(goal = target) [endof(LAND)]
            HOLD: [started(FLY)] subscribe CTL:0 =* :0 [CTL:0<status == "holding">]
            LAND: [endof(HOLD)] subscribe CTL:0 =* :1 [CTL:0<status2 == "landed">(last = status2)]
        }
    }
}
`;

/** CTL (every 10 ms): "holding" at its 5th release, then "landed" every 10th from the 30th. */
const CTL_EXEC = `
    { static int releases = 0; releases++;
      if (releases == 5) { strcpy(status, "holding"); PostEvent(&status); }
      if (releases >= 30 && releases % 10 == 0) { strcpy(status, "landed"); PostEvent(&status); } }
    *stateindex = -1;
`;

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-event-port-');
    expect(await runCli(['new', 'twoports'], capture(root))).toBe(0);
    writeFileSync(join(root, 'twoports', 'supervisor.contract'), SUPERVISOR);
    expect(await runCli(['generate', 'twoports'], capture(root))).toBe(0);
    const file = join(root, 'twoports/src-gen/generated/architecture/modules/CTL_mod/module.c');
    const source = readFileSync(file, 'utf8');
    const edited = source.replace(/(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)[\s\S]*?(\/\*PROTECTED REGION END\*\/)/, `$1${CTL_EXEC}    $2`);
    expect(edited).not.toBe(source);
    writeFileSync(file, edited);
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('a module port subscribed to two input ports, in a real run', () => {
    it('checks without a warning, and LAND ends on the "landed" that comes in on status2\'s port', async () => {
        const check = capture(root);
        expect(await runCli(['check', 'twoports'], check)).toBe(0);
        expect(check.stdout + check.stderr).toContain('0 errors, 0 warnings');
        const io = capture(root);
        expect(await runCli(['run', 'twoports', '--sandbox', 'bwrap', '--duration', '1500ms', '--logs', 'twoports-logs', '--cpus', '1'], io)).toBe(0);
        expect(io.stdout).toContain('[MIS] rule mission.HOLD inactive');
        expect(io.stdout).toContain('[MIS] rule mission.LAND active');
        const mis = readdirSync(join(root, 'twoports-logs')).find((f) => f.startsWith('MIS_'))!;
        const log = readFileSync(join(root, 'twoports-logs', mis), 'utf8');
        expect(log).toContain('event_received,CTL,1,');
        expect(log).toContain('"mission.LAND inactive cause=CTL:0 value=""landed"""');
        // LAND's end ends FLY, which deactivates goTo
        expect(log).toContain('mission.FLY inactive cause=endof(LAND)');
    }, 240_000);
});
