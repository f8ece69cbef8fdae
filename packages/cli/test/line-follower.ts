/**
 * A field tester's line follower (supervisor LFR, rules LINK/FOLLOW/SEARCH, CAM:0 carrying
 * "lost"/"found"): `follow` feeds MOT:0 from CTL, `search` from SRC, never active together. The
 * FOLLOW rule ends on the supervisor's word for "lost": `lineFollower(root, name, 'lsot')` writes the
 * project whose rule never matches what the camera sends. Shared by the real run's test
 * (event-values-run.test.ts) and the simulation's (simulate-event-values.test.ts).
 */
import { readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { expect } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

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

/** Writes the project `name` in `root` with the supervisor's word for "lost", generates it and fills the exec regions. */
export async function lineFollower(root: string, name: string, lost: string): Promise<void> {
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
