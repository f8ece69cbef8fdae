/**
 * A simulation's trace holds what a real run's logs hold for the same supervisor actions
 * (runtime/src/engines/sup_main.c): the `supervisor` action record in the simulator's words (every
 * undo prefixed `undo: `), then the hold record a run writes (module_hold, flow_hold on the flow's
 * hold name), a priority claim's module_priority; so `contract trace` tells a simulation and a run
 * alike, and the verbose report says the same lines.
 */
import { describe, expect, it } from 'vitest';
import { parseTrace, renderStory, type KnownRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { actionAsLogged, stepsToTrace, type TraceStep } from '../src/trace/steps-to-trace.js';

const actions = (timeNs: number, ...what: string[]) => what.map((w, i) => ({ timeNs, seq: timeNs / 1000 + i, who: 'MIS', what: w }));

/** What the simulator's harness reports for an event schema activated then undone, and a priority claim and its undo. */
const STEPS: TraceStep[] = [
    {
        timeNs: 1_000_000, source: 'start MIS.mission(altitude = 2.0)', ok: true, rules: [], log: [], records: [],
        actions: actions(1_000_000,
            'activate schema groundLink(channel = 2) (event schema)',
            'parameterize GCS:0 link (8 bytes) = 2',
            'connect GCS:0 =* REC:0',
            'start module GCS (priority 30)',
            'start module REC (priority 30)',
            'set priority of NAV to 84 (claim #3)'),
    },
    {
        timeNs: 2_000_000, source: 'stop MIS.mission', ok: true, rules: [], log: [], records: [],
        actions: actions(2_000_000,
            'release priority claim #3 on NAV',
            'deactivate schema groundLink (event schema)',
            'disconnect GCS:0 =* REC:0',
            'stop module GCS',
            'stop module REC',
            'start module CAM (priority 30): it has crashed, it does not start'),
    },
];

/** The same actions as a real run's log of MIS writes them (sup_main.c), holds and priority answers included. */
const RUN_LOG = [
    'mono_ns,wall_time,module,event,peer,port,size,detail',
    '1000000,w,MIS,supervisor,,,0,activate schema groundLink(channel = 2) (event schema)',
    '1000000,w,MIS,supervisor,GCS,,0,parameterize GCS:0 link (8 bytes) = 2',
    '1000000,w,MIS,supervisor,GCS,,0,connect GCS:0 =* REC:0',
    '1000000,w,MIS,flow_hold,flow-GCS-0-REC-0,,0,hold taken',
    '1000000,w,MIS,supervisor,GCS,,0,start module GCS (priority 30)',
    '1000000,w,MIS,module_hold,GCS,,0,hold taken (started it)',
    '1000000,w,MIS,supervisor,REC,,0,start module REC (priority 30)',
    '1000000,w,MIS,module_hold,REC,,0,hold taken (started it)',
    '1000000,w,MIS,supervisor,NAV,,0,set priority of NAV to 84 (claim #3)',
    '1000000,w,MIS,module_priority,NAV,,0,nice level for priority 84 (was 30)',
    '2000000,w,MIS,supervisor,NAV,,0,undo: release priority claim #3 on NAV',
    '2000000,w,MIS,supervisor,,,0,undo: deactivate schema groundLink (event schema)',
    '2000000,w,MIS,supervisor,GCS,,0,undo: disconnect GCS:0 =* REC:0',
    '2000000,w,MIS,flow_hold,flow-GCS-0-REC-0,,0,last hold dropped (disconnected)',
    '2000000,w,MIS,supervisor,GCS,,0,undo: stop module GCS',
    '2000000,w,MIS,module_hold,GCS,,0,last hold dropped (stopped)',
    '2000000,w,MIS,supervisor,REC,,0,undo: stop module REC',
    '2000000,w,MIS,module_hold,REC,,0,last hold dropped (stopped)',
    '',
].join('\n');

const row = (r: TraceRecord) => { const k = r as KnownRecord; return `${k.kind} ${k.module} ${k.peer} ${k.detail}`; };
const supervisorSide = (records: TraceRecord[]) => records.filter((r) => ['supervisor', 'module_hold', 'flow_hold'].includes(r.kind) && (r as KnownRecord).module === 'MIS');

describe('stepsToTrace: a supervisor\'s actions as a run logs them', () => {
    const trace = stepsToTrace(STEPS);

    it('writes each action record in the run\'s words, then the hold record a run writes after it', () => {
        expect(supervisorSide(trace).map(row)).toEqual([
            'supervisor MIS  activate schema groundLink(channel = 2) (event schema)',
            'supervisor MIS GCS parameterize GCS:0 link (8 bytes) = 2',
            'supervisor MIS GCS connect GCS:0 =* REC:0',
            'flow_hold MIS flow-GCS-0-REC-0 hold taken',
            'supervisor MIS GCS start module GCS (priority 30)',
            'module_hold MIS GCS hold taken (started it)',
            'supervisor MIS REC start module REC (priority 30)',
            'module_hold MIS REC hold taken (started it)',
            'supervisor MIS NAV set priority of NAV to 84 (claim #3)',
            'supervisor MIS NAV undo: release priority claim #3 on NAV',
            'supervisor MIS  undo: deactivate schema groundLink (event schema)',
            'supervisor MIS GCS undo: disconnect GCS:0 =* REC:0',
            'flow_hold MIS flow-GCS-0-REC-0 last hold dropped (disconnected)',
            'supervisor MIS GCS undo: stop module GCS',
            'module_hold MIS GCS last hold dropped (stopped)',
            'supervisor MIS REC undo: stop module REC',
            'module_hold MIS REC last hold dropped (stopped)',
            // a module the simulation made crash is not started: no hold (a run's start that cannot be sent takes none)
            'supervisor MIS CAM start module CAM (priority 30): it has crashed, it does not start',
        ]);
        // each with the peer a run's log gives it (the module, or none for an event schema's own line)
        const runRows = parseTrace([{ name: 'MIS_1.csv', text: RUN_LOG }]).filter((r) => r.kind === 'supervisor').map(row);
        expect(supervisorSide(trace).filter((r) => r.kind === 'supervisor').map(row).slice(0, runRows.length)).toEqual(runRows);
        // typed by the trace reader, as a run's records are; the claim's module_priority as before
        const start = trace.find((r) => (r as KnownRecord).detail === 'start module GCS (priority 30)') as KnownRecord;
        expect(start.fields).toEqual({ what: 'action', action: 'start_module', module: 'GCS', priority: 30 });
        const claim = trace.filter((r) => r.kind === 'module_priority').map(row);
        expect(claim).toEqual(['module_priority MIS NAV set priority of NAV to 84 (claim #3)']);
    });

    it('is told by contract trace as a run with the same actions, in the words of the verbose report', () => {
        const told = (records: TraceRecord[]) => renderStory(records).slice(0, -1).map((l) => l.slice(11)).filter((l) => l.startsWith('MIS '));
        const run = told(parseTrace([{ name: 'MIS_1.csv', text: RUN_LOG }]));
        const sim = told(trace);
        expect(sim.slice(0, run.length)).toEqual(run);
        expect(run).toEqual([
            'MIS  activate schema groundLink(channel = 2) (event schema)',
            'MIS  parameterize GCS:0 link (8 bytes) = 2',
            'MIS  connect GCS:0 =* REC:0',
            'MIS  start module GCS (priority 30)',
            'MIS  start module REC (priority 30)',
            'MIS  set priority of NAV to 84 (claim #3)',
            'MIS  undo: release priority claim #3 on NAV',
            'MIS  undo: deactivate schema groundLink (event schema)',
            'MIS  undo: disconnect GCS:0 =* REC:0',
            'MIS  undo: stop module GCS',
            'MIS  undo: stop module REC',
        ]);
        // the verbose report's action lines (`  MIS: ...`) are the same words
        expect(STEPS.flatMap((s) => s.actions).map((a) => `MIS  ${actionAsLogged(a.what)}`).slice(0, run.length)).toEqual(run);
    });

    it('writes ORD\'s parameters and data flows at an activation as a run\'s ORD logs them, and contract trace tells them the same', () => {
        const ord = (timeNs: number, ...what: string[]) => what.map((w, i) => ({ timeNs, seq: timeNs / 1000 + i, who: 'ORD', what: w }));
        const steps: TraceStep[] = [
            { timeNs: 1_000_000, source: 'x', ok: true, rules: [], log: [], records: [], actions: ord(1_000_000, 'parameterize CTL:0 setpoint (8 bytes) = 3', 'connect ALT:0 -> CTL:0 * 1') },
            { timeNs: 2_000_000, source: 'y', ok: true, rules: [], log: [], records: [], actions: ord(2_000_000, 'disconnect ALT:0 -> CTL:0', 'ORD:0 "altHold" (deadline miss)') },
        ];
        const sim = stepsToTrace(steps).filter((r) => r.kind === 'scheduler');
        // the peer a run's ORD writes: the module (a flow's source)
        expect(sim.map((r) => [row(r), (r as KnownRecord).fields['what']])).toEqual([
            ['scheduler ORD CTL parameterize CTL:0 setpoint (8 bytes) = 3', 'parameterize'],
            ['scheduler ORD ALT connect ALT:0 -> CTL:0 * 1', 'connect'],
            ['scheduler ORD ALT disconnect ALT:0 -> CTL:0', 'disconnect'],
        ]);
        const runLog = ['mono_ns,wall_time,module,event,peer,port,size,detail',
            '1000000,w,ORD,scheduler,CTL,,0,parameterize CTL:0 setpoint (8 bytes) = 3', '1000000,w,ORD,scheduler,ALT,,0,connect ALT:0 -> CTL:0 * 1',
            '2000000,w,ORD,scheduler,ALT,,0,disconnect ALT:0 -> CTL:0', ''].join('\n');
        const told = (records: TraceRecord[]) => renderStory(records).slice(0, -1).map((l) => l.slice(11)).filter((l) => l.startsWith('ORD '));
        expect(told(stepsToTrace(steps))).toEqual(told(parseTrace([{ name: 'ORD_1.csv', text: runLog }])));
        expect(told(parseTrace([{ name: 'ORD_1.csv', text: runLog }]))).toEqual([
            'ORD  parameterize CTL:0 setpoint (8 bytes) = 3', 'ORD  connect ALT:0 -> CTL:0 * 1', 'ORD  disconnect ALT:0 -> CTL:0']);
    });

    it('names a flow\'s hold as the runtime does, hashed when the name is 64 characters or more', () => {
        const long = 'M'.repeat(30);
        const t = stepsToTrace([{ timeNs: 0, source: 'x', ok: true, rules: [], log: [], records: [], actions: [{ timeNs: 0, who: 'MIS', what: `connect ${long}:1 =* ${long}:2` }] }]);
        expect(t.filter((r) => r.kind === 'flow_hold').map(row)).toEqual(['flow_hold MIS flow-3d6ad01208bf6728 hold taken']);
    });
});
