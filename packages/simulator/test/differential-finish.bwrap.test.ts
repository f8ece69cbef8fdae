/**
 * Differential test of a module whose own code ends its run: a pan-tilt tracker (written for this
 * test) whose supervisor PAN homes the unit when an axis hits its limit. The homing module HOM posts
 * "homed" and its exec region sets `*stateindex = -1`: its run ends by itself, then PAN's rule
 * ends and its undo stops HOM. A real run (`contract run --sandbox bwrap`) and the simulator given
 * the same events, with `finish HOM` where the real HOM's run ended, tell the same story per module:
 * `HOM  run #1 ended by its own code (started by PAN)`, then PAN's `undo: stop module HOM` (its STOP
 * finds no run, the module is still there: `last hold dropped (stopped)` in both) and PAN's
 * decisions with their causes. Compared per module (PAN's lines, HOM's lines): which of two
 * processes logs first is timing, not semantics (under load HOM logs its run's end after PAN's reaction).
 */
import { rmSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { renderStory, type KnownRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { loadScenario, runLoadedScenario } from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { runForReal, type RealRun } from './differential/replay-run.js';
import { generatedProject, prepared } from './support.js';

const FILES: Record<string, string> = {
    'cam.contract': 'synchronous module CAM {\n    scheduling { C=1ms; }\n    data flows { out :0 float u; }\n}\n',
    'trk.contract': 'synchronous module TRK {\n    scheduling { C=1ms; }\n    data flows { in :0 float u; }\n}\n',
    'ptu.contract': 'asynchronous module PTU {\n    event flows { out :0 string axis; }\n}\n',
    'hom.contract': 'asynchronous module HOM {\n    event flows { out :0 string result; }\n}\n',
    'track.contract': 'import "cam.contract";\nimport "trk.contract";\n\nperiodic schema track() {\n    realtime { PERIOD=20ms; CRITICAL_DELAY=20ms; }\n    modules { CAM (); TRK (); }\n    scheduling graph { CAM -> TRK; }\n    communications { CAM:0 -> TRK:0 * 1; }\n}\n',
    'drive.contract': 'import "ptu.contract";\n\nevent schema drive() {\n    modules { PTU (); }\n}\n',
    'homing.contract': 'import "hom.contract";\n\nevent schema homing() {\n    modules { HOM (); }\n}\n',
    'sched.contract': 'import "cam.contract";\nimport "trk.contract";\nimport "track.contract";\n\nscheduler configuration {\n    modules { CAM; TRK; }\n    schemas { track; }\n}\n',
    'pan.contract': [
        'import "ptu.contract";', 'import "hom.contract";', 'import "track.contract";', 'import "drive.contract";',
        'import "homing.contract";', 'import "sched.contract";', '',
        'supervisor PAN {',
        '    event flows { in :0 string axis; in :1 string result; }',
        '    follow() {',
        '        rules {',
        '            TRACK: [elapsed=1ms or HOM:0<result == "homed">]',
        '                subscribe PTU:0 =* :0; activate schema drive(); activate schema track()',
        '                [PTU:0]',
        '            HOME: [endof(TRACK)]',
        '                subscribe HOM:0 =* :1; activate schema homing()',
        '                [HOM:0<result == "homed">]',
        '        }',
        '    }',
        '}', '',
    ].join('\n'),
};

/** The module code, in the protected regions `contract generate` made. */
const REGIONS: Array<{ module: string; body: string }> = [
    // the pan axis reaches its limit 300 ms after PTU starts, then PTU idles until stopped
    { module: 'PTU', body: `
    if (*stateindex < 6) {
        nanosleep(&(struct timespec){0, 50 * 1000000L}, NULL);
        (*stateindex)++;
    } else if (*stateindex == 6) {
        snprintf(axis, sizeof axis, "pan");
        PostEvent(&axis);
        *stateindex = 7;
    } else {
        nanosleep(&(struct timespec){0, 10 * 1000000L}, NULL);
    }
    ` },
    // homing: 100 ms, then "homed", and the run ends by itself
    { module: 'HOM', body: `
    if (*stateindex < 2) {
        nanosleep(&(struct timespec){0, 50 * 1000000L}, NULL);
        (*stateindex)++;
    } else {
        snprintf(result, sizeof result, "homed");
        PostEvent(&result);
        *stateindex = -1;
    }
    ` },
];

let dir: string;
let run: RealRun;

beforeAll(() => {
    dir = generatedProject('sim-diff-finish-', FILES, REGIONS);
    // HOM ends its run at ~0.4 s after the start; the second limit comes at ~0.7 s
    run = runForReal(dir, '1.5s'); // (a margin for a loaded machine: only the first homing is compared)
}, 300_000);
afterAll(() => {
    run?.cleanUp();
    rmSync(dir, { recursive: true, force: true });
});

const mono = (r: TraceRecord) => BigInt((r as KnownRecord).monoNs);
/**
 * A story's lines without their time, per module: PAN's up to its second TRACK (the one after the
 * homing), HOM's first run. Each module's lines on their own: under load HOM logs the end of its run
 * after PAN has already reacted to its "homed", which is timing, not semantics.
 */
function perModule(lines: string[]): Map<string, string[]> {
    const out = new Map<string, string[]>();
    for (const line of lines.map((l) => l.slice(11))) {
        const [module] = line.split(' ');
        if ((module !== 'PAN' && module !== 'HOM') || / started \(pid=/.test(line)) continue; // not the processes' starts
        (out.get(module!) ?? out.set(module!, []).get(module!)!).push(line);
    }
    const pan = out.get('PAN') ?? [];
    let tracks = 0;
    const second = pan.findIndex((l) => /^PAN {2}rule follow\.TRACK active/.test(l) && ++tracks === 2);
    if (second >= 0) out.set('PAN', pan.slice(0, second + 1));
    out.set('HOM', (out.get('HOM') ?? []).slice(0, 1));
    return out;
}

describe('a module whose own code ends its run: a real bwrap run and the simulator with finish', () => {
    it('tell the same story, per module, up to the tracking that follows the homing', async () => {
        expect(run.code, run.output).toBe(0);
        const known = run.records.filter((r): r is KnownRecord => r.kind !== 'unknown' && !('rule' in r)) as KnownRecord[];
        const started = known.find((r) => r.module === 'PAN' && r.kind === 'supervisor' && r.fields['what'] === 'function_started');
        const limit = known.find((r) => r.module === 'PAN' && r.kind === 'event_received' && r.peer === 'PTU');
        const ended = known.find((r) => r.module === 'HOM' && r.kind === 'run_finished' && /^activation=1 cpu_ns=\d+$/.test(r.detail));
        expect(started && limit && ended, run.output).toBeTruthy();
        const ms = (r: TraceRecord) => Number(mono(r) - mono(started!)) / 1e6;
        // HOM's "homed" and the end of its run come together: the run's end first, as HOM posts
        // then returns (the scenario's steps at one time run in file order)
        const text = ['until 1s', 'start PAN.follow()', `t=${ms(limit!).toFixed(3)}ms PTU:0 "pan"`,
            `t=${ms(ended!).toFixed(3)}ms finish HOM`, 'HOM:0 "homed"'].join('\n');
        const project = await prepared(dir);
        const s = loadScenario(join(dir, 'real.scenario'), 'real.scenario', text, project.index);
        expect(s.diagnostics, text).toEqual([]);
        const sim = await runLoadedScenario(project, s);
        expect(sim.failures.map((f) => f.message), text).toEqual([]);

        const real = perModule(renderStory(run.records));
        const simulated = perModule(renderStory(stepsToTrace(sim.steps.map(traceStepOf))));
        expect(real.get('HOM')).toEqual(['HOM  run #1 ended by its own code (started by PAN)']);
        expect(real.get('PAN')).toContain('PAN  undo: stop module HOM');
        expect(real.get('PAN')!.some((l) => l.includes('it had ended'))).toBe(false);
        expect(simulated.get('HOM'), text).toEqual(real.get('HOM'));
        expect(simulated.get('PAN'), text).toEqual(real.get('PAN'));
    }, 120_000);
});
