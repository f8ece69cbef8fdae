/**
 * A real run (bwrap) of a field tester's line follower (supervisor LFR, rules LINK/FOLLOW/SEARCH,
 * CAM:0 carrying "lost"/"found"): `follow` feeds MOT:0 from CTL, `search` from SRC, never active
 * together. Before, each schema switch printed `MOT: warning: input data port 0 now fed by SRC`
 * on stderr though the design is right; and with the rule's "lost" mistyped "lsot", nothing in
 * the run's story said that CAM's events arrived and changed no rule, nor their values.
 */
import { readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const FILES: Record<string, string> = {
    'types.contract': `datatype LineReading {float offset = 0.0, bool seen = true};
datatype Command {float v = 0.0, float w = 0.0};
`,
    'camera.contract': `import "types.contract";
synchronous module CAM {
    scheduling { C=1ms; }
    data flows { out :0 LineReading line; }
    event flows { out :0 string status; }
}
`,
    'controller.contract': `import "types.contract";
synchronous module CTL {
    parameters { float kp = 1.5 :0; }
    scheduling { C=1ms; }
    data flows { in :0 LineReading line; out :1 Command cmd; }
}
`,
    'search.contract': `import "types.contract";
synchronous module SRC {
    parameters { float spin = 0.8 :0; }
    scheduling { C=500us; }
    data flows { out :0 Command cmd; }
}
`,
    'motor.contract': `import "types.contract";
synchronous module MOT {
    scheduling { C=500us; }
    data flows { in :0 Command cmd; }
}
`,
    'follow.contract': `import "types.contract";
import "camera.contract";
import "controller.contract";
import "motor.contract";
periodic schema follow(float gain = 1.5) {
    realtime { PERIOD=20ms; CRITICAL_DELAY=10ms; }
    modules { CAM (); CTL (gain:0); MOT (); }
    scheduling graph { CAM -> CTL; CTL -> MOT; }
    communications { CAM:0 -> CTL:0 * 1; CTL:1 -> MOT:0 * 1; }
}
`,
    'searching.contract': `import "types.contract";
import "camera.contract";
import "search.contract";
import "motor.contract";
periodic schema search() {
    realtime { PERIOD=20ms; CRITICAL_DELAY=10ms; }
    modules { CAM (); SRC (); MOT (); }
    scheduling graph { CAM -> SRC; SRC -> MOT; }
    communications { SRC:0 -> MOT:0 * 1; }
}
`,
    'sched.contract': `import "camera.contract";
import "controller.contract";
import "motor.contract";
import "follow.contract";
import "searching.contract";
import "search.contract";
scheduler configuration {
    modules { CAM; CTL; SRC; MOT; }
    schemas { follow; search; }
}
`,
};

/** The supervisor, its FOLLOW rule ending on CAM's `lost` (spelled `lost` by the camera). */
const supervisor = (lost: string) => `import "types.contract";
import "camera.contract";
import "follow.contract";
import "searching.contract";
import "sched.contract";
supervisor LFR {
    event flows { in :0 string status; }
    drive() {
        local { string why; }
        rules {
            LINK: [elapsed=1ms] subscribe CAM:0 =* :0 [CAM:0<status == "stop">]
            FOLLOW: [started(LINK) or endof(SEARCH)] activate schema follow(gain = 1.5) [CAM:0<status == "${lost}">(why = status)]
            SEARCH: [endof(FOLLOW)] activate schema search() [CAM:0<status == "found">(why = status)]
        }
    }
}
`;

/** The exec regions: CAM loses the line for 0.3 s every 1.2 s (20 ms releases); CTL and SRC command MOT. */
const EXEC: Record<string, string> = {
    CAM: `
    { static int tick = 0; static int seen = 1;
      int now_seen = !((tick % 60) >= 20 && (tick % 60) < 35);
      line.seen = now_seen; line.offset = now_seen ? 0.1 : 0.0; PostData(&line);
      if (seen && !now_seen) { strcpy(status, "lost"); PostEvent(&status); }
      if (!seen && now_seen) { strcpy(status, "found"); PostEvent(&status); }
      seen = now_seen; tick++; }
    *stateindex = -1;
`,
    CTL: `
    if (GetLatestData(&line, NULL, NULL)) { cmd.v = 0.2; cmd.w = -kp * line.offset; PostData(&cmd); }
    *stateindex = -1;
`,
    SRC: `
    cmd.v = 0.0; cmd.w = spin; PostData(&cmd);
    *stateindex = -1;
`,
    MOT: `
    GetLatestData(&cmd, NULL, NULL);
    *stateindex = -1;
`,
};

let root: string;

/** Writes the project `name` with the supervisor's word for "lost", generates it and fills the exec regions. */
async function project(name: string, lost: string): Promise<void> {
    expect(await runCli(['new', name], capture(root))).toBe(0);
    // the new project's own files give way to the tester's
    for (const f of readdirSync(join(root, name)).filter((f) => f.endsWith('.contract'))) rmSync(join(root, name, f));
    for (const [file, text] of Object.entries(FILES)) writeFileSync(join(root, name, file), text);
    writeFileSync(join(root, name, 'supervisor.contract'), supervisor(lost));
    expect(await runCli(['generate', name], capture(root))).toBe(0);
    for (const [m, code] of Object.entries(EXEC)) {
        const file = join(root, name, `src-gen/generated/architecture/modules/${m}_mod/module.c`);
        const source = readFileSync(file, 'utf8');
        const edited = source.replace(new RegExp(`(PROTECTED REGION ID\\(protect_exec_${m}\\) ENABLED START\\*/)[\\s\\S]*?(/\\*PROTECTED REGION END\\*/)`), `$1${code}    $2`);
        expect(edited).not.toBe(source);
        writeFileSync(file, edited);
    }
}

/** The story `contract trace` tells of a run's logs, and its records as JSON lines. */
async function trace(logs: string): Promise<{ story: string; json: Record<string, unknown>[] }> {
    const text = capture(root);
    expect(await runCli(['trace', logs], text)).toBe(0);
    const json = capture(root);
    expect(await runCli(['trace', logs, '--format', 'json'], json)).toBe(0);
    return { story: text.stdout, json: json.stdout.trim().split('\n').map((l) => JSON.parse(l) as Record<string, unknown>) };
}

beforeAll(async () => {
    root = await makeSeededScratch('contract-event-values-');
    await project('linebot', 'lost');
    await project('typo', 'lsot');
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
        const { story } = await trace(join(root, 'linebot-logs'));
        expect(story).toMatch(/MOT {2}input MOT:0 now fed by SRC \(was CTL\): a schema switch/);
        expect(story).toMatch(/^input MOT:0 changed producer \d+ times \(CTL, SRC\)$/m);
        expect(story).not.toContain('warning: input MOT:0');
    }, 240_000);

    it('with the rule waiting for "lsot": the story tells the "lost" and "found" that changed no rule, with their counts', async () => {
        const io = capture(root);
        expect(await runCli(['run', 'typo', '--sandbox', 'bwrap', '--duration', '2500ms', '--logs', 'typo-logs', '--cpus', '1'], io)).toBe(0);
        expect(io.stdout).not.toContain('[LFR] rule drive.SEARCH active');
        const { story, json } = await trace(join(root, 'typo-logs'));
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
