/**
 * Two supervisors using the same modules and event flow (one event schema each activates): the
 * simulator decides their holds as a run's engines do (module_holds.c, sup_main.c) and says it in
 * the same records and words. The first one's undo leaves the modules running and the flow
 * connected for the other (`hold dropped (kept running: still used by 1 other supervisor(s))`),
 * the other's undo stops them (the module's run begun by the first START ends with that STOP); a
 * module that crashed meanwhile is said to have ended.
 */
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { renderStory, type KnownRecord } from '@contract-studio/build-service/trace';
import { loadScenario, runLoadedScenario, textReport, type PreparedProject } from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { prepared } from './support.js';

const FILES: Record<string, string> = {
    'scn.contract': 'asynchronous module SCN {\n    event flows { out :0 string seen; }\n}\n',
    'lgr.contract': 'asynchronous module LGR {\n    event flows { in :0 string line; }\n}\n',
    'watch.contract': 'import "scn.contract";\nimport "lgr.contract";\n\nevent schema watch() {\n    modules { SCN (); LGR (); }\n    communications { SCN:0 =* LGR:0; }\n}\n',
    'alf.contract': 'import "watch.contract";\n\nsupervisor ALF {\n    first() {\n        rules {\n            USE: [elapsed=1ms] activate schema watch() [elapsed=20ms]\n        }\n    }\n}\n',
    'bet.contract': 'import "watch.contract";\n\nsupervisor BET {\n    second() {\n        rules {\n            USE: [elapsed=5ms] activate schema watch() [elapsed=40ms]\n        }\n    }\n}\n',
};

let dir: string;
let project: PreparedProject;

beforeAll(async () => {
    dir = mkdtempSync(join(tmpdir(), 'sim-shared-holds-'));
    mkdirSync(join(dir, 'scenarios'));
    for (const [name, text] of Object.entries(FILES)) writeFileSync(join(dir, name), text);
    project = await prepared(dir);
}, 240_000);
afterAll(() => rmSync(dir, { recursive: true, force: true }));

async function run(text: string) {
    const s = loadScenario(join(dir, 'scenarios', 'share.scenario'), 'share.scenario', text, project.index);
    expect(s.diagnostics).toEqual([]);
    const r = await runLoadedScenario(project, s);
    expect(r.error).toBeUndefined();
    return r;
}

/** `contract trace`'s lines of the two supervisors, without the time column. */
const story = (r: Awaited<ReturnType<typeof run>>) => renderStory(stepsToTrace(r.steps.map(traceStepOf)))
    .map((l) => l.slice(11)).filter((l) => /^(ALF|BET) /.test(l) && !/ (rule|function) /.test(l));

/** SCN's runs as the trace holds them (run_started / run_finished: the Monitor's running modules). */
const scnRuns = (r: Awaited<ReturnType<typeof run>>) => stepsToTrace(r.steps.map(traceStepOf))
    .filter((x) => (x.kind === 'run_started' || x.kind === 'run_finished') && (x as KnownRecord).module === 'SCN') as KnownRecord[];

describe('modules and event flows two supervisors share', () => {
    it('stay running and connected until the last one lets them go, told as a run tells it', async () => {
        const r = await run([
            'start ALF.first()', 'start BET.second()',
            'expect at 10ms module SCN running',
            // ALF's undo (20 ms) keeps them for BET; the simulator used to stop them
            'expect at 30ms module SCN running', 'expect module LGR running',
            'expect at 50ms module SCN stopped', 'expect module LGR stopped',
        ].join('\n'));
        expect(r.failures.map((f) => f.message)).toEqual([]);
        expect(story(r)).toEqual([
            // the consumer first, then the producer's flow, then the producer (docs/semantics.md)
            'ALF  activate schema watch() (event schema)',
            'ALF  start module LGR (priority 30)',
            'ALF  connect SCN:0 =* LGR:0',
            'ALF  start module SCN (priority 30)',
            'BET  activate schema watch() (event schema)',
            'BET  module LGR: hold taken (it was running)',
            'BET  connect SCN:0 =* LGR:0',
            'BET  module SCN: hold taken (it was running)',
            'ALF  undo: deactivate schema watch (event schema)',
            'ALF  undo: disconnect SCN:0 =* LGR:0',
            'ALF  event flow SCN:0 -> LGR:0: hold dropped (kept connected: used by 1 other supervisor(s))',
            'ALF  undo: stop module SCN',
            'ALF  module SCN: hold dropped (kept running: still used by 1 other supervisor(s))',
            'ALF  undo: stop module LGR',
            'ALF  module LGR: hold dropped (kept running: still used by 1 other supervisor(s))',
            'BET  undo: deactivate schema watch (event schema)',
            'BET  undo: disconnect SCN:0 =* LGR:0',
            'BET  module SCN: last hold dropped (stopped)',
            'BET  module LGR: last hold dropped (stopped)',
        ]);
        // each hold record once, as the harness wrote it (none added from the action lines)
        const holds = stepsToTrace(r.steps.map(traceStepOf)).filter((x) => x.kind === 'module_hold' || x.kind === 'flow_hold') as KnownRecord[];
        expect(holds.map((h) => `${h.module} ${h.peer} ${h.detail}`)).toEqual([
            'ALF LGR hold taken (started it)',
            'ALF flow-SCN-0-LGR-0 hold taken',
            'ALF SCN hold taken (started it)',
            'BET LGR hold taken (it was running)',
            'BET flow-SCN-0-LGR-0 hold taken',
            'BET SCN hold taken (it was running)',
            'ALF flow-SCN-0-LGR-0 hold dropped (kept connected: used by 1 other supervisor(s))',
            'ALF SCN hold dropped (kept running: still used by 1 other supervisor(s))',
            'ALF LGR hold dropped (kept running: still used by 1 other supervisor(s))',
            'BET flow-SCN-0-LGR-0 last hold dropped (disconnected)',
            'BET SCN last hold dropped (stopped)',
            'BET LGR last hold dropped (stopped)',
        ]);
        // the modules' runs, as libmodule logs them: begun by ALF's START, ended by BET's STOP (the Monitor's running modules)
        const runs = scnRuns(r);
        expect(runs.map((x) => `${Number(x.monoNs) / 1e6}ms ${x.kind} ${x.peer} ${x.detail}`)).toEqual(['1ms run_started ALF activation=1', '40ms run_finished BET activation=1 cpu_ns=0 STOP']);
        // the verbose report says the same, after the action line each decides
        const report = textReport([r], { verbose: true }).split('\n').map((l) => l.trim().replace(/^\S+\s+/, ''));
        const at = (line: string) => report.indexOf(line);
        expect(at('BET: module SCN: hold taken (it was running)')).toBeGreaterThan(at('BET: connect SCN:0 =* LGR:0'));
        expect(at('ALF: module SCN: hold dropped (kept running: still used by 1 other supervisor(s))')).toBe(at('ALF: undo: stop module SCN') + 1);
        expect(at('ALF: event flow SCN:0 -> LGR:0: hold dropped (kept connected: used by 1 other supervisor(s))')).toBe(at('ALF: undo: disconnect SCN:0 =* LGR:0') + 1);
        // BET did not start them: no `stop module` line of its own (a run writes none either), the hold says it stopped them
        expect(at('BET: undo: stop module SCN')).toBe(-1);
        expect(at('BET: module SCN: last hold dropped (stopped)')).toBe(at('BET: undo: disconnect SCN:0 =* LGR:0') + 1);
        expect(report.filter((l) => l.includes('hold taken (started it)'))).toEqual([]); // confirms its line: not repeated
    }, 60_000);

    it('a module that crashed while held: its last holder is told it had ended', async () => {
        const r = await run(['start ALF.first()', 't=10ms crash SCN', 'expect at 30ms module SCN stopped'].join('\n'));
        expect(r.failures.map((f) => f.message)).toEqual([]);
        expect(story(r).filter((l) => l.includes('SCN'))).toEqual([
            'ALF  connect SCN:0 =* LGR:0',
            'ALF  start module SCN (priority 30)',
            'ALF  undo: disconnect SCN:0 =* LGR:0',
            'ALF  undo: stop module SCN',
            'ALF  module SCN: last hold dropped (it had ended)',
        ]);
    }, 60_000);

    it("a module whose code returned (finish) ends its run; the next supervisor that needs it starts it again", async () => {
        // SCN returns at 3ms, before BET's rule (5ms) needs it: BET starts it again, where
        // without `finish` it shares ALF's run (the first test's `hold taken (it was running)`)
        const r = await run([
            'start ALF.first()', 'start BET.second()',
            't=3ms finish SCN', 'expect module SCN stopped', 'expect module LGR running',
            'expect at 10ms module SCN running',
            'expect at 30ms module SCN running', // ALF's undo keeps BET's run
            'expect at 50ms module SCN stopped',
        ].join('\n'));
        expect(r.failures.map((f) => f.message)).toEqual([]);
        expect(story(r).filter((l) => l.includes('module SCN'))).toEqual([
            'ALF  start module SCN (priority 30)',
            'BET  start module SCN (priority 30)',
            'ALF  undo: stop module SCN',
            'ALF  module SCN: hold dropped (kept running: still used by 1 other supervisor(s))',
            'BET  undo: stop module SCN', // its hold's `last hold dropped (stopped)` confirms the line: not repeated
        ]);
        const runs = scnRuns(r);
        expect(runs.map((x) => `${Number(x.monoNs) / 1e6}ms ${x.kind} ${x.peer} ${x.detail}`)).toEqual([
            '1ms run_started ALF activation=1', '3ms run_finished  activation=1 cpu_ns=0', // returned: no STOP, no peer
            '5ms run_started BET activation=2', '40ms run_finished BET activation=2 cpu_ns=0 STOP',
        ]);
        // the verbose report tells the run's end under the step, in the words of `contract trace`
        const report = textReport([r], { verbose: true }).split('\n').map((l) => l.trim());
        expect(report[report.findIndex((l) => l.endsWith('t=3ms finish SCN')) + 1]).toBe('3ms    SCN| run #1 ended by its own code');
    }, 60_000);

    it('finish M after TIME: each run started from then on ends that long after its start (once: the next one only)', async () => {
        const r = await run(['finish SCN after 2ms', 'start ALF.first()', 'start BET.second()', 'expect at 4ms module SCN stopped', 'expect at 6ms module SCN running', 'expect at 8ms module SCN stopped'].join('\n'));
        expect(r.failures.map((f) => f.message)).toEqual([]);
        const runs = (x: typeof r) => scnRuns(x).map((y) => `${Number(y.monoNs) / 1e6}ms ${y.kind} ${y.detail}`);
        // ALF starts it at 1ms, it ends at 3ms; BET needs it at 5ms and starts it again, it ends at 7ms
        expect(runs(r)).toEqual(['1ms run_started activation=1', '3ms run_finished activation=1 cpu_ns=0', '5ms run_started activation=2', '7ms run_finished activation=2 cpu_ns=0']);
        const once = await run(['finish SCN after 2ms once', 'start ALF.first()', 'start BET.second()', 'expect at 50ms module SCN stopped'].join('\n'));
        expect(runs(once)).toEqual(['1ms run_started activation=1', '3ms run_finished activation=1 cpu_ns=0', '5ms run_started activation=2', '40ms run_finished activation=2 cpu_ns=0 STOP']);
        // a run stopped before its time is not ended again: ALF's undo at 20ms keeps it for BET, BET's at 40ms stops it
        const late = await run(['finish SCN after 100ms', 'start ALF.first()', 'start BET.second()', 'expect at 200ms module SCN stopped'].join('\n'));
        expect(runs(late)).toEqual(['1ms run_started activation=1', '40ms run_finished activation=1 cpu_ns=0 STOP']);
    }, 60_000);

    it('a module may crash before it is started; a second crash fails that step and says why (it was taken without a word)', async () => {
        const r = await run(['t=1ms crash SCN', 't=2ms crash SCN', 'expect at 3ms module SCN stopped'].join('\n'));
        expect(r.failures.map((f) => [f.line, f.message])).toEqual([[2, expect.stringContaining('crash failed: SCN has already crashed: there is no process of it left to crash')]]);
    }, 60_000);

    it("finish of a module that is not running fails that step and says why; the last holder of a finished module still stops it, as a run does", async () => {
        const r = await run(['t=1ms finish SCN', 'start ALF.first()', 't=3ms finish SCN', 'expect at 30ms module SCN stopped'].join('\n'));
        expect(r.failures.map((f) => f.message)).toEqual([expect.stringContaining('SCN is not running: it has no run to finish')]);
        expect(story(r).filter((l) => l.includes('module SCN'))).toEqual([
            'ALF  start module SCN (priority 30)',
            'ALF  undo: stop module SCN', // confirmed by `last hold dropped (stopped)`: the module is there, its STOP finds no run
        ]);
        const holds = stepsToTrace(r.steps.map(traceStepOf)).filter((x) => x.kind === 'module_hold' || ((x.kind === 'run_finished' || x.kind === 'run_started') && (x as KnownRecord).module === 'SCN')) as KnownRecord[];
        expect(holds.filter((h) => h.module === 'SCN' || h.peer === 'SCN').map((h) => `${Number(h.monoNs) / 1e6}ms ${h.module} ${h.kind} ${h.detail}`)).toEqual([
            '2ms ALF module_hold hold taken (started it)', // ALF started at 1ms, its rule 1ms later
            '2ms SCN run_started activation=1',
            '3ms SCN run_finished activation=1 cpu_ns=0', // no second run_finished at the STOP: there was no run to end
            '21ms ALF module_hold last hold dropped (stopped)',
        ]);
    }, 60_000);
});
