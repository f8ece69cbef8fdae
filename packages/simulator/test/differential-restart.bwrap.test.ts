/**
 * Differential test of a module a supervisor still holds, whose own code has ended its run, needed
 * again by another rule of that supervisor: a cell (written for this test) whose supervisor SUP
 * starts the logger LGR for a warning (WARN: `activate resttime module LGR`), then activates the
 * event schema telemetry, HMI =* LGR (HOLD), while WARN still holds LGR. LGR's exec region sets
 * `*stateindex = -1`: each of its runs ends at once, by itself. The event schema starts the modules
 * that are not running: LGR is started again (`start module LGR` a second time, its run #2), not
 * taken for running because WARN holds it. A real run (`contract run --sandbox bwrap`) and the
 * simulator (`finish LGR after 0`: each run of LGR ends at its start) tell the same story of SUP
 * and of LGR. Before, SUP started HMI alone and telemetry ran without its logger. And HMI, posting a
 * note every 10 ms, gets its disconnection and its STOP together at HOLD's undo: the STOP ends its run
 * before its next state (the generated loop ran one more state between them, a post to no subscriber).
 */
import { rmSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { renderStory, type KnownRecord } from '@contract-studio/build-service/trace';
import { loadScenario, runLoadedScenario } from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { runForReal, type RealRun } from './differential/replay-run.js';
import { generatedProject, prepared } from './support.js';

const FILES: Record<string, string> = {
    'hmi.contract': 'asynchronous module HMI {\n    event flows { out :0 string note; }\n}\n',
    'lgr.contract': 'asynchronous module LGR {\n    event flows { in :0 string note; }\n}\n',
    'telemetry.contract': 'import "hmi.contract";\nimport "lgr.contract";\n\nevent schema telemetry() {\n    modules { HMI (); LGR (); }\n    communications { HMI:0 =* LGR:0; }\n}\n',
    'sup.contract': [
        'import "lgr.contract";', 'import "telemetry.contract";', '',
        'supervisor SUP {',
        '    cell() {',
        '        rules {',
        '            WARN: [elapsed=1ms] activate resttime module LGR [elapsed=400ms]',
        '            HOLD: [elapsed=100ms] activate schema telemetry() [elapsed=200ms]',
        '        }',
        '    }',
        '}', '',
    ].join('\n'),
};

/** The module code, in the protected regions `contract generate` made. */
const REGIONS: Array<{ module: string; body: string }> = [
    // the logger's run ends at once, by its own code (it still gets its events)
    { module: 'LGR', body: '\n    *stateindex = -1;\n    ' },
    // the operator panel posts a note every 10 ms while it runs
    { module: 'HMI', body: '\n    nanosleep(&(struct timespec){0, 10 * 1000000L}, NULL);\n    snprintf(note, sizeof note, "tick");\n    PostEvent(&note);\n    ' },
];

let dir: string;
let run: RealRun;

beforeAll(() => {
    dir = generatedProject('sim-diff-restart-', FILES, REGIONS);
    run = runForReal(dir, '1s');
}, 300_000);
afterAll(() => {
    run?.cleanUp();
    rmSync(dir, { recursive: true, force: true });
});

/**
 * A story's lines of SUP and LGR without their time, each module's on their own (which of two
 * processes logs first is timing); not the processes' starts and ends, nor the launcher's stop of
 * the function at the end of the run (the scenario ends without one).
 */
function perModule(lines: string[]): Map<string, string[]> {
    const out = new Map<string, string[]>();
    for (const line of lines.map((l) => l.slice(11))) {
        const [module] = line.split(' ');
        if ((module !== 'SUP' && module !== 'LGR') || / started \(pid=|exited|stopped by|function cell stopped/.test(line)) continue;
        (out.get(module!) ?? out.set(module!, []).get(module!)!).push(line);
    }
    return out;
}

describe('a held module whose own code ended its run, needed again: a real bwrap run and the simulator', () => {
    it('start it again, and tell the same story', async () => {
        expect(run.code, run.output).toBe(0);
        const real = perModule(renderStory(run.records));
        const sup = real.get('SUP') ?? [];
        expect(sup.filter((l) => /start module LGR/.test(l)), sup.join('\n')).toHaveLength(2);
        expect(real.get('LGR'), (real.get('LGR') ?? []).join('\n')).toEqual([
            'LGR  run #1 ended by its own code (started by SUP)',
            'LGR  run #2 ended by its own code (started by SUP)',
        ]);
        const text = ['until 1s', 'finish LGR after 0', 'start SUP.cell()', 'expect at 150ms schema telemetry active'].join('\n');
        const project = await prepared(dir);
        const s = loadScenario(join(dir, 'real.scenario'), 'real.scenario', text, project.index);
        expect(s.diagnostics, text).toEqual([]);
        const sim = await runLoadedScenario(project, s);
        expect(sim.failures.map((f) => f.message), text).toEqual([]);
        const simulated = perModule(renderStory(stepsToTrace(sim.steps.map(traceStepOf))));
        expect(simulated.get('LGR')).toEqual(real.get('LGR'));
        expect(simulated.get('SUP')).toEqual(sup);
    }, 120_000);

    it('a STOP read with the disconnection before it ends the run before its next state: nothing posted after its run ended', () => {
        // HOLD's undo sends HMI an UNSUB_EVENT, then its STOP: read together while HMI sleeps in a state; the
        // generated loop ran one more state between them (a post to no subscriber after `run_finished ... STOP`)
        const hmi = run.records.filter((r): r is KnownRecord => r.kind !== 'unknown' && (r as KnownRecord).module === 'HMI');
        const stopped = hmi.findIndex((r) => r.kind === 'run_finished' && / STOP$/.test(r.detail));
        expect(stopped, hmi.map((r) => `${r.kind} ${r.detail}`).join('\n')).toBeGreaterThan(0);
        expect(hmi.slice(stopped).filter((r) => r.kind === 'event_posted').map((r) => `${r.kind} ${r.peer} ${r.detail}`)).toEqual([]);
    });
});
