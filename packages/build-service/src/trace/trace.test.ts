import { readdirSync, readFileSync } from 'node:fs';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { CSV_HEADER, CUT_RECORD, MAX_LINE_CHARS, STORY_FOLLOWED, StoryTeller, missedTicksOf, overrunningAfter, skippedReleasesOf, TRACE_KINDS, confirmingHold, flowHoldName, isRule, isUnknown, missWaitText, parseLogFile, parseRecordLine, parseTrace, readableCause, renderStory, renderTraceTable, splitCsvLine, traceFileToLogs, type KnownRecord, type RuleRecord } from './index.js';

const DOC = new URL('../../../../docs/runtime-api.md', import.meta.url);

/** The story of one log: `lines` (records, without their line ends) after the CSV header. */
const storyOfLog = (name: string, lines: string[]): string[] => renderStory(parseTrace([{ name, text: [CSV_HEADER, ...lines, ''].join('\n') }]));

describe('trace record kinds', () => {
    it('docs/runtime-api.md holds the table generated from record-kinds.ts (npm run docs:trace -w packages/build-service)', () => {
        expect(readFileSync(DOC, 'utf8')).toContain(renderTraceTable());
    });

    it('lists every event the runtime writes, and only those (ContractLog calls of runtime/src, the log\'s own from put_record, ORD\'s from ord_fact_record)', () => {
        const src = new URL('../../../../runtime/src/', import.meta.url);
        const written = new Set<string>();
        const computed: string[] = [];
        for (const entry of readdirSync(src, { recursive: true, encoding: 'utf8' }).filter((f) => f.endsWith('.c'))) {
            const text = readFileSync(new URL(entry, src), 'utf8');
            for (const call of text.matchAll(/ContractLog\(([^;]*?),/g)) {
                const names = [...call[1]!.matchAll(/"([a-z_]+)"/g)].map((n) => n[1]!);
                for (const name of names) written.add(name);
                if (!names.length && !/^const\b/.test(call[1]!.trim())) computed.push(`${entry}: ${call[1]!.trim()}`);
            }
            // the log's own records (written by csvlog.c without ContractLog: log-capped)
            for (const call of text.matchAll(/put_record\([^,]*,[^,]*, "([a-z_-]+)"/g)) written.add(call[1]!);
            // ORD's timeline records: the event name is what ord_fact_record returns (the simulator writes them with it too)
            const facts = /const char \*ord_fact_record\([^)]*\)\s*\{([\s\S]*?)\n\}/.exec(text);
            if (facts) for (const r of facts[1]!.matchAll(/return "([a-z_]+)";/g)) written.add(r[1]!);
        }
        expect(computed).toEqual(['engines/ord_main.c: event']); // the one event name not written out: ord_fact_record's
        // `user`: no event the runtime writes, the kind of what a module's own code logs under a name of its own
        expect([...written].sort()).toEqual(TRACE_KINDS.map((k) => k.kind).filter((k) => k !== 'user').sort());
    });

    it('every example line of the table is read as its kind, with its detail keys', () => {
        for (const k of TRACE_KINDS) {
            const r = parseRecordLine('X.csv', 2, k.example);
            expect(r.kind, k.example).toBe(k.kind);
            for (const key of k.detailKeys ?? []) expect((r as KnownRecord).fields[key], `${k.kind} ${key}`).toBeDefined();
        }
    });
});

describe('reading a log', () => {
    it('marks a last line with no line end that reads as a record cut (its detail may have lost its end), and tells it so', () => {
        const text = [CSV_HEADER, '1000,w,CTL,module_started,,,0,pid=4 priority=40', '2000,w,CTL,burst,,,0,seq=20 padding=xx'].join('\n');
        const records = parseLogFile({ name: 'CTL_1.csv', text });
        expect(records.map((r) => (r as { cut?: true }).cut)).toEqual([undefined, true]);
        expect(parseLogFile({ name: 'CTL_1.csv', text: `${text}\n` }).map((r) => (r as { cut?: true }).cut)).toEqual([undefined, undefined]);
        expect(renderStory(parseTrace([{ name: 'CTL_1.csv', text }]))[1]).toBe(`+0.000001s CTL  burst: seq=20 padding=xx${CUT_RECORD}`);
    });

    it('says of a last line with no line end that is no record that the file ends inside it (a writer stopped mid-line)', () => {
        const rule = '2001000000,w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns';
        const cut = parseLogFile({ name: 'SUP_1.csv', text: `${CSV_HEADER}\n2000000000,w,SUP,sup\n${rule}\n2002000000,w,SUP,super` });
        expect(cut.filter(isUnknown).map((u) => [u.line, u.reason])).toEqual([
            [2, '4 fields, expected 8'],
            [4, '4 fields, expected 8 (the file ends inside this line: its writer was stopped, or is still writing it)'],
        ]);
        // a whole last record without its line end is read as any other
        expect(parseLogFile({ name: 'SUP_1.csv', text: `${CSV_HEADER}\n${rule}` }).filter(isUnknown)).toEqual([]);
        expect(traceFileToLogs('run.jsonl', '{"kind":"sup_rule","mono').problems).toEqual(['line 1: not JSON (the file ends inside this line: its writer was stopped, or is still writing it)']);
    });
    it('reads a rule change with its cause, event values included', () => {
        const r = parseRecordLine('SUP.csv', 2, '3000,2026-11-24T18:30:15.123456Z,SUP,sup_rule,,,0,"action.SECOND active cause=MAA:2 value=""disconnected"""') as RuleRecord;
        expect(isRule(r)).toBe(true);
        expect(r).toMatchObject({ function: 'action', rule: 'SECOND', active: true, cause: 'MAA:2 value="disconnected"', causeEvent: { kind: 'event', module: 'MAA', port: 2, value: '"disconnected"' } });
        const causes = ['elapsed=1000000ns', 'duration(FIRST)=5ns', 'started(A)', 'endof(B)', 'stop', 'ORD:0 value="S"', 'what?'];
        expect(causes.map((c) => (parseRecordLine('S', 2, `1,w,SUP,sup_rule,,,0,f.R inactive cause=${c}`) as RuleRecord).causeEvent.kind))
            .toEqual(['elapsed', 'duration', 'started', 'endof', 'stop', 'event', 'other']);
    });

    it('reads causes whose value is a bool, an enum member, an array or a datatype with fields (extension types)', () => {
        const line = '3000,w,MIS,sup_rule,,,0,"mission.AHEAD active cause=OBS:1 value={ranges=[5,5,5,5,5,5,5,5,5,5,...],mode=AUTO,ok=true,tag=""a, b""}"';
        const r = parseRecordLine('MIS.csv', 2, line) as RuleRecord;
        expect(r).toMatchObject({ function: 'mission', rule: 'AHEAD', active: true,
            causeEvent: { kind: 'event', module: 'OBS', port: 1, value: '{ranges=[5,5,5,5,5,5,5,5,5,5,...],mode=AUTO,ok=true,tag="a, b"}' } });
        for (const value of ['true', 'AUTO', '[[1,0],[0,1]]', '[{id=1,w=0.5},...]'])
            expect((parseRecordLine('S', 2, `1,w,SUP,sup_rule,,,0,"f.R inactive cause=M:0 value=${value}"`) as RuleRecord).causeEvent).toEqual({ kind: 'event', module: 'M', port: 0, value });
    });

    it('reads ORD releases with cycle, tick and release times as numbers', () => {
        const r = parseRecordLine('ORD.csv', 5, '1201,w,ORD,ord_release,MSC,,0,schema=S cycle=3 tick_ns=1200 release_ns=1201 release=9') as KnownRecord;
        expect(r).toMatchObject({ kind: 'ord_release', peer: 'MSC', port: null, fields: { schema: 'S', cycle: 3, tick_ns: 1200, release_ns: 1201, release: 9 } });
    });

    it('takes a detail\'s key=value words: the first of each key, whole words only, plain integers as numbers', () => {
        const fields = (detail: string) => (parseRecordLine('L', 2, `1,w,ORD,ord_release,MSC,,0,${detail}`) as KnownRecord).fields;
        expect(fields('xschema=A schema=S cycle=-4 cycle=9 tick_ns=1234567890123456 release_ns=12a release=')).toEqual({ schema: 'S', cycle: -4, tick_ns: '1234567890123456', release_ns: '12a', release: '' });
        expect(fields('schema==S  cycle=1 release_ns')).toEqual({ schema: '=S', cycle: 1 });
        expect(fields('')).toEqual({});
        expect(Object.getPrototypeOf(fields('__proto__=1 constructor=2 schema=S'))).toBe(Object.prototype);
    });

    it('types the engines\' readable lines: what they are and the names they hold', () => {
        const fields = (event: string, detail: string) => (parseRecordLine('L', 2, `1,w,${event === 'scheduler' ? 'ORD' : 'X'},${event},,,0,"${detail}"`) as KnownRecord).fields;
        expect(fields('scheduler', 'activate schemaCommande1')).toEqual({ what: 'activate', schema: 'schemaCommande1' }); // older logs
        expect(fields('scheduler', 'activate schemaCommande1 (activation #4 from SUP)')).toEqual({ what: 'activate', schema: 'schemaCommande1', activation: 4, requester: 'SUP' });
        expect(fields('scheduler', 'deactivate conveyor (activation #2 from LIN)')).toEqual({ what: 'deactivate', schema: 'conveyor', activation: 2, requester: 'LIN' });
        expect(fields('scheduler', 'activate conveyor (activation #2)')).toEqual({ what: 'activate', schema: 'conveyor', activation: 2 });
        expect(fields('scheduler', 'missed tick of SLW (cycle 12)')).toEqual({ what: 'missed_tick', schema: 'SLW', cycle: 12 });
        expect(fields('scheduler', 'deadline miss: DIA cycle 7 (ORD:0)')).toEqual({ what: 'deadline_miss', schema: 'DIA', cycle: 7 });
        expect(fields('scheduler', 'deadline miss: DIA (ORD:0)')).toEqual({ what: 'deadline_miss', schema: 'DIA' }); // older logs
        // ORD released the cycle past its CRITICAL_DELAY itself: its miss, no ORD:0
        expect(fields('scheduler', 'late release: DIA cycle 1 released 7000 us after its tick, past CRITICAL_DELAY 6000 us (ORD late, no ORD:0)'))
            .toEqual({ what: 'late_release', schema: 'DIA', cycle: 1, late_us: 7000, critical_delay_us: 6000 });
        expect(fields('scheduler', 'activate conveyor (activation #2 from LIN) and more')).toEqual({ what: 'other' });
        expect(fields('scheduler', 'conflict: ICF shares a module with active ISC (ORD:1)')).toEqual({ what: 'conflict', schema: 'ICF', active: 'ISC' });
        expect(fields('scheduler', 'overrun: DIA cycle still running, release skipped')).toEqual({ what: 'overrun', schema: 'DIA', state: 'running' }); // older logs
        // the modules the cycle still runs (released, not finished), named by ORD's line
        expect(fields('scheduler', 'overrun: DIA cycle still running (D), release skipped')).toEqual({ what: 'overrun', schema: 'DIA', state: 'running', modules: 'D' });
        expect(fields('scheduler', 'overrun: DIA cycle still running (B, C), release skipped')).toEqual({ what: 'overrun', schema: 'DIA', state: 'running', modules: 'B, C' });
        expect(fields('scheduler', 'late ack: B finished release #12 of an earlier cycle of DIA (not counted)')).toEqual({ what: 'late_ack', module: 'B', release: 12, schema: 'DIA' });
        expect(fields('scheduler', 'overrun: DIA cycle ended after 3 skipped releases')).toEqual({ what: 'overrun_ended', schema: 'DIA', skipped: 3 });
        expect(fields('scheduler', 'B finished release #12 at last (reported stuck, DIA)')).toEqual({ what: 'unstuck', module: 'B', release: 12, schema: 'DIA' });
        expect(fields('scheduler', 'release B (DIA)')).toEqual({ what: 'release', module: 'B', schema: 'DIA' });
        expect(fields('scheduler', 'something new')).toEqual({ what: 'other' });
        // what ORD does at an activation (since 2026-12-04), in the simulator's words
        expect(fields('scheduler', 'parameterize CTL:0 setpoint (8 bytes) = 3')).toEqual({ what: 'parameterize', module: 'CTL', port: 0, name: 'setpoint' });
        expect(fields('scheduler', 'connect ALT:0 -> CTL:0 * 1')).toEqual({ what: 'connect', module: 'ALT', port: 0, to_module: 'CTL', to_port: 0, periodicity: 1 });
        expect(fields('scheduler', 'disconnect ALT:0 -> CTL:0')).toEqual({ what: 'disconnect', module: 'ALT', port: 0, to_module: 'CTL', to_port: 0 });
        expect(fields('scheduler', 'connect ALT:0 -> CTL:0 * 1 twice')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'function action started')).toEqual({ what: 'function_started', function: 'action' }); // older logs
        // a call without parameters is written as the source writes it: `land()`
        expect(fields('supervisor', 'function land() started')).toEqual({ what: 'function_started', function: 'land' });
        expect(fields('supervisor', 'activate supervisor FLT.land() (activation #4)')).toEqual({ what: 'action', supervisor: 'FLT', function: 'land', activation: 4 });
        expect(fields('supervisor', 'activate schema altHold() (activation #1, to ORD)')).toEqual({ what: 'action', schema: 'altHold', activation: 1 });
        expect(fields('supervisor', 'activate schema watch() (event schema)')).toEqual({ what: 'action', schema: 'watch' });
        expect(fields('supervisor', 'function action(consigne = {i=0,j=0,k=0}, mode = AUTO) started')).toEqual({ what: 'function_started', function: 'action' });
        expect(fields('supervisor', 'refused: function action already running')).toEqual({ what: 'function_refused', function: 'action' });
        expect(fields('supervisor', 'refused: no function nope')).toEqual({ what: 'function_refused', function: 'nope' });
        expect(fields('supervisor', 'rule action.FIRST inactive')).toEqual({ what: 'rule', function: 'action', rule: 'FIRST', state: 'inactive' });
        expect(fields('supervisor', 'subscribe MAA:2 =* :2')).toEqual({ what: 'action', module: 'MAA', port: 2, in_port: 2 });
        expect(fields('supervisor', 'undo: unsubscribe MAA:2 :2')).toEqual({ what: 'action', module: 'MAA', port: 2, in_port: 2 });
        expect(fields('supervisor', 'subscribe MAA:0 => :1 (activation #2)')).toEqual({ what: 'action', module: 'MAA', port: 0, in_port: 1, activation: 2 });
        expect(fields('supervisor', 'undo: unsubscribe MAA:0 :1 (activation #2)')).toEqual({ what: 'action', module: 'MAA', port: 0, in_port: 1, activation: 2 });
        expect(fields('supervisor', 'parameterize VEL:0 (16 bytes) = {v=0.3,w=0}')).toEqual({ what: 'action', module: 'VEL', port: 0 });
        expect(fields('supervisor', 'parameterize MSC:1 (8 bytes)')).toEqual({ what: 'action', module: 'MSC', port: 1 }); // older logs
        expect(fields('supervisor', 'parameterize MSC:0 consigne (24 bytes) = {i=1,j=2,k=3}')).toEqual({ what: 'action', module: 'MSC', port: 0, name: 'consigne' });
        expect(fields('supervisor', 'parameterize MSC:0 consigne extra (24 bytes) = 1')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'notify :1 (string) = "paused"')).toEqual({ what: 'action', out_port: 1, type: 'string' });
        expect(fields('supervisor', 'activate supervisor SUP.action(consigne = {i=0,j=0,k=0}) (activation #2)')).toEqual({ what: 'action', supervisor: 'SUP', function: 'action', activation: 2 });
        expect(fields('supervisor', 'undo: stop SUP.action (activation #2)')).toEqual({ what: 'action', supervisor: 'SUP', function: 'action', activation: 2 });
        expect(fields('supervisor', 'activation #3 of SUP.action refused: its undo stops nothing')).toEqual({ what: 'activation_refused', activation: 3, supervisor: 'SUP', function: 'action' });
        // a line no engine writes (another version's, or forged in a log folder) is not taken for an action
        expect(fields('supervisor', 'launch the missiles')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'subscribe MAA:2 =* :2 and more')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'activate schema schemaReceptionMessage (event schema)')).toEqual({ what: 'action', schema: 'schemaReceptionMessage' });
        expect(fields('supervisor', 'activate schema schemaReceptionMessage(param = {i=27.12,j=0,k=0.04}) (event schema)')).toEqual({ what: 'action', schema: 'schemaReceptionMessage' });
        expect(fields('supervisor', 'undo: deactivate schema console (event schema)')).toEqual({ what: 'action', schema: 'console' });
        expect(fields('supervisor', 'activate schema S (activation #3, to ORD)')).toEqual({ what: 'action', schema: 'S', activation: 3 });
        expect(fields('supervisor', 'activate schema conveyor(speed = 0.6) (activation #2, to ORD)')).toEqual({ what: 'action', schema: 'conveyor', activation: 2 });
        expect(fields('supervisor', 'undo: deactivate schema S (activation #3, to ORD)')).toEqual({ what: 'action', schema: 'S', activation: 3 });
        expect(fields('supervisor', 'compute record')).toEqual({ what: 'action', function: 'record' });
        // the modules it starts and stops, the flows it connects, the priorities it claims: field `action`
        // names the line (its outcome is a record of its own); the claim's number is its activation
        expect(fields('supervisor', 'start module GCS (priority 30)')).toEqual({ what: 'action', action: 'start_module', module: 'GCS', priority: 30 });
        expect(fields('supervisor', 'start module GCS (priority 30): it has crashed, it does not start')).toEqual({ what: 'action', action: 'start_module', module: 'GCS', priority: 30 }); // a simulation
        expect(fields('supervisor', 'undo: stop module GCS')).toEqual({ what: 'action', action: 'stop_module', module: 'GCS' });
        expect(fields('supervisor', 'connect GCS:0 =* REC:0')).toEqual({ what: 'action', action: 'connect', module: 'GCS', port: 0, to_module: 'REC', to_port: 0 });
        expect(fields('supervisor', 'connect SCN:1 => DIV:2')).toEqual({ what: 'action', action: 'connect', module: 'SCN', port: 1, to_module: 'DIV', to_port: 2 });
        expect(fields('supervisor', 'undo: disconnect GCS:0 =* REC:0')).toEqual({ what: 'action', action: 'disconnect', module: 'GCS', port: 0, to_module: 'REC', to_port: 0 });
        expect(fields('supervisor', 'undo: disconnect SCN:1 => DIV:2')).toEqual({ what: 'action', action: 'disconnect', module: 'SCN', port: 1, to_module: 'DIV', to_port: 2 });
        expect(fields('supervisor', 'set priority of MAA to 84 (claim #5)')).toEqual({ what: 'action', action: 'claim_priority', module: 'MAA', priority: 84, activation: 5 });
        expect(fields('supervisor', 'undo: release priority claim #5 on MAA')).toEqual({ what: 'action', action: 'release_priority', activation: 5, module: 'MAA' });
        // the simulator's words without the run's `undo: `, or something more: not these actions
        expect(fields('supervisor', 'stop module GCS')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'disconnect GCS:0 =* REC:0')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'start module GCS (priority 30) twice')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'set priority of MAA to 84')).toEqual({ what: 'other' });
        expect(fields('supervisor', 'connect GCS:0 -> REC:0')).toEqual({ what: 'other' });
    });

    it('counts ORD\'s overruns from its lines as ORD counts them: the first skip of a cycle, the rest at its end, each restart of a held cycle', () => {
        const fields = (event: string, detail: string) => (parseRecordLine('L', 2, `1,w,ORD,${event},,,0,"${detail}"`) as KnownRecord).fields;
        const lines = [
            'overrun: SLW cycle still running, release skipped', // 1
            'overrun: SLW cycle ended after 3 skipped releases', // + 2
            'overrun: SLW cycle still running, release skipped', // 1: a second cycle, one skip, no end line
            'overrun: FST cycle still running, release skipped', // 1
            'overrun: FST cycle ended after 333 skipped releases', // + 332
            'overrun: FST cycle still held, restarted', // 1
            'missed tick of SLW (cycle 12)', 'deadline miss: DIA cycle 7 (ORD:0)', 'activate SLW (activation #2 from SUP)',
        ];
        const told = lines.map((l) => fields('scheduler', l) as Record<string, unknown>);
        expect(told.reduce((n, f) => n + skippedReleasesOf(f), 0)).toBe(338); // 3 + 1 + 333 + 1
        expect(told.map(overrunningAfter)).toEqual([true, false, true, true, false, false, undefined, undefined, undefined]);
        // a forged count adds nothing it cannot stand for: not a number, unsafe, zero or one
        for (const skipped of ['3', 2 ** 60, 0, 1, -5, Number.NaN]) expect(skippedReleasesOf({ what: 'overrun_ended', skipped })).toBe(0);
        expect(fields('scheduler', 'overrun: SLW cycle ended after 99999999999999999999 skipped releases')).not.toMatchObject({ skipped: expect.any(Number) });
        // ORD's missed ticks the same way: one line each when no cycle runs, a running cycle's first, then its count at its end
        const missed = ['missed tick of SLW (cycle 3)', 'missed tick of SLW (cycle 5)', 'missed ticks: SLW cycle ended after 7 missed ticks', 'overrun: SLW cycle ended after 7 skipped releases']
            .map((l) => fields('scheduler', l) as Record<string, unknown>);
        expect(missed[2]).toEqual({ what: 'missed_ticks_ended', schema: 'SLW', missed: 7 });
        expect(missed.map(missedTicksOf)).toEqual([1, 1, 6, 0]);
        for (const n of ['7', 2 ** 60, 1, -2]) expect(missedTicksOf({ what: 'missed_ticks_ended', missed: n })).toBe(0);
    });

    it('names the hold record that only confirms an action line, with the runtime\'s flow hold names', () => {
        expect(flowHoldName('SCN', 0, 'DIV', 0)).toBe('flow-SCN-0-DIV-0');
        // 64 characters or more: value_ops.c engine_flow_hold_name's FNV-1a hash (the C code run on these names)
        const long = 'M'.repeat(30);
        expect(flowHoldName(long, 1, long, 2)).toBe('flow-3d6ad01208bf6728');
        expect(flowHoldName('A'.repeat(27), 0, 'B'.repeat(27), 0)).toBe('flow-232cbf124a7b62a0'); // 64 characters
        expect(flowHoldName('A'.repeat(27), 0, 'B'.repeat(26), 0)).toBe(`flow-${'A'.repeat(27)}-0-${'B'.repeat(26)}-0`); // 63: as it is
        // the 16-bit-lane hash is engine_flow_hold_name's 64-bit arithmetic, byte for byte, on any name (multi-byte, up to a line's length)
        const reference = (full: string) => {
            let h = 1469598103934665603n;
            for (const byte of new TextEncoder().encode(full)) h = ((h ^ BigInt(byte)) * 1099511628211n) & 0xffff_ffff_ffff_ffffn;
            return `flow-${h.toString(16).padStart(16, '0')}`;
        };
        let seed = 7;
        const next = () => (seed = (seed * 1103515245 + 12345) % 2147483648);
        for (let i = 0; i < 500; i++) {
            const src = Array.from({ length: 40 + (next() % 4000) }, () => String.fromCharCode(65 + (next() % 2000))).join('');
            expect(flowHoldName(src, i, 'DST', i % 9)).toBe(reference(`flow-${src}-${i}-DST-${i % 9}`));
        }
        const of = (line: string) => confirmingHold((parseRecordLine('L', 2, `1,w,SUP,supervisor,,,0,${line}`) as KnownRecord).fields);
        expect(of('start module GCS (priority 30)')).toEqual({ kind: 'module_hold', peer: 'GCS', detail: 'hold taken (started it)' });
        expect(of('undo: stop module GCS')).toEqual({ kind: 'module_hold', peer: 'GCS', detail: 'last hold dropped (stopped)' });
        expect(of('connect GCS:0 =* REC:0')).toEqual({ kind: 'flow_hold', peer: 'flow-GCS-0-REC-0', detail: 'hold taken' });
        expect(of('undo: disconnect GCS:0 => REC:1')).toEqual({ kind: 'flow_hold', peer: 'flow-GCS-0-REC-1', detail: 'last hold dropped (disconnected)' });
        expect(of('set priority of MAA to 84 (claim #5)')).toBeUndefined();
        expect(of('subscribe MAA:2 =* :2')).toBeUndefined();
    });

    it('reads a line whose quoted field is not closed as no record: a rule change forged or cut inside its detail is not told', () => {
        const text = [CSV_HEADER, '500,w,SUP,sup_rule,,,0,"cell.RUN active cause=', '600,w,SUP,sup_rule,,,0,"cell.RUN inactive cause=ORD:0 value=""loop"""', ''].join('\n');
        const records = parseLogFile({ name: 'SUP_1.csv', text });
        expect(records.map((r) => (isUnknown(r) ? r.reason : `${r.kind} ${(r as RuleRecord).cause}`))).toEqual([
            'a quoted field is not closed (the line was cut or forged)', 'sup_rule ORD:0 value="loop"',
        ]);
        expect(renderStory(parseTrace([{ name: 'SUP_1.csv', text }])).filter((l) => l.includes('cell.RUN'))).toEqual(['+0.000000s SUP  rule cell.RUN inactive <- ORD:0 = "loop"']);
    });

    it('reads a rule turned active with cause=stop as no record: a stopping function only turns rules off', () => {
        const text = [CSV_HEADER, '500,w,SUP,sup_rule,,,0,cell.RUN active cause=stop', '600,w,SUP,sup_rule,,,0,cell.RUN inactive cause=stop', ''].join('\n');
        const records = parseLogFile({ name: 'SUP_1.csv', text });
        expect(records.map((r) => (isUnknown(r) ? r.reason : `${r.kind} ${(r as RuleRecord).active} ${(r as RuleRecord).cause}`))).toEqual([
            'a rule turned active with cause=stop (only a stopping function gives that cause, to the rules it turns inactive)', 'sup_rule false stop',
        ]);
        expect(renderStory(parseTrace([{ name: 'SUP_1.csv', text }])).filter((l) => l.includes('cell.RUN'))).toEqual(['+0.000000s SUP  rule cell.RUN inactive <- its function stopped']);
    });

    it('keeps what it cannot read as unknown records saying why, and never throws', () => {
        const text = [CSV_HEADER, 'garbage', `1,w,MSC,${'x'.repeat(65)},,,0,`, `1,w,MSC,error,,,0,${'y'.repeat(MAX_LINE_CHARS)}`, 'a,w,MSC,error,,,0,', '1,w,M/S,error,,,0,', '\u0000\u00ff,",,', ''].join('\n');
        const records = parseLogFile({ name: 'MSC_1.csv', text });
        expect(records.map((r) => r.kind)).toEqual(['unknown', 'unknown', 'unknown', 'unknown', 'unknown', 'unknown']);
        expect(records.map((r) => (isUnknown(r) ? r.reason : ''))).toEqual([
            '1 fields, expected 8', `unknown event '${'x'.repeat(64)}'`, `line longer than ${MAX_LINE_CHARS} characters`, 'mono_ns is not a number', 'bad module name', 'a quoted field is not closed (the line was cut or forged)',
        ]);
        fc.assert(fc.property(fc.string({ maxLength: 300 }), (s) => {
            const lines = s.split('\n').map((l) => (l.endsWith('\r') ? l.slice(0, -1) : l)).filter((l, i) => l !== '' && !(i === 0 && l === CSV_HEADER));
            expect(parseLogFile({ name: 'F', text: s }).length).toBe(lines.length);
        }));
    });

    it('reads a line with no quote (its fields found in place) as the same record as the line with every field quoted (split by the CSV reader), any fields', () => {
        const example = (k: (typeof TRACE_KINDS)[number]) => k.example.split(',');
        const field = (i: number) => fc.oneof(
            fc.constantFrom(...TRACE_KINDS.map((k) => example(k)[i] ?? '')),
            fc.constantFrom('', '12', '007', 'ORD', 'x y', '99999999999999999999', '-3'),
            fc.string({ maxLength: 12 }),
        ).map((t) => t.replace(/"/g, ''));
        const line = fc.array(fc.nat(7), { maxLength: 10 }).chain((slots) => fc.tuple(...slots.map((slot) => field(slot)))).map((fields) => fields.join(','));
        // the table's example lines (quotes taken out), some fields changed (each a record, or why not), and any others
        const examples = TRACE_KINDS.map((k) => splitCsvLine(k.example).map((f) => f.replace(/"/g, '')));
        const changed = fc.tuple(fc.constantFrom(...examples), fc.array(fc.nat(7), { maxLength: 2 }))
            .chain(([fields, slots]) => fc.tuple(fc.constant(fields), ...slots.map((slot) => fc.tuple(fc.constant(slot), field(slot)))))
            .map(([fields, ...changes]) => {
                const out = [...fields];
                for (const [slot, value] of changes) out[slot] = value;
                return out.join(',');
            });
        fc.assert(fc.property(fc.oneof({ arbitrary: changed, weight: 4 }, { arbitrary: line, weight: 1 }), (l) => {
            const plain = parseRecordLine('MSC_1.csv', 2, l);
            const quoted = parseRecordLine('MSC_1.csv', 2, l.split(',').map((f) => `"${f}"`).join(','));
            if (isUnknown(quoted)) expect(isUnknown(plain) && plain.reason).toBe(quoted.reason);
            else expect(plain).toEqual(quoted);
        }), { numRuns: 2000 });
    });

    it('orders the records of several files by mono_ns, equal times in file order, unknown lines after their predecessor', () => {
        const a = { name: 'B_1.csv', text: `${CSV_HEADER}\n5,w,B,error,,,0,b5\nbad\n9,w,B,error,,,0,b9\n` };
        const b = { name: 'A_1.csv', text: `${CSV_HEADER}\n5,w,A,error,,,0,a5\n7,w,A,error,,,0,a7\n` };
        const order = parseTrace([a, b]).map((r) => (r.kind === 'unknown' ? 'bad' : (r as KnownRecord).detail));
        expect(order).toEqual(['a5', 'b5', 'bad', 'a7', 'b9']);
    });

    it('parseTrace orders as one stable sort of every record by time, then file name, then line (any files, times out of order included)', () => {
        /** The definition: every record keyed by its time (an unknown line by the time before it in its file), one stable sort. */
        const reference = (files: { name: string; text: string }[]) => [...files].sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0))
            .flatMap((file, fi) => {
                let last = 0n;
                return parseLogFile(file).map((record, index) => {
                    if (record.kind !== 'unknown') last = BigInt((record as KnownRecord).monoNs);
                    return { key: last, fi, index, record };
                });
            })
            .sort((a, b) => (a.key < b.key ? -1 : a.key > b.key ? 1 : a.fi - b.fi || a.index - b.index))
            .map((k) => k.record);
        const line = fc.oneof(fc.constant('bad'), fc.tuple(fc.integer({ min: 0, max: 50 }), fc.constantFrom('A', 'B')).map(([t, m]) => `${t},w,${m},error,,,0,d${t}`));
        const file = fc.tuple(fc.constantFrom('A_1.csv', 'B_1.csv', 'C_1.csv'), fc.array(line, { maxLength: 30 })).map(([name, lines]) => ({ name, text: [CSV_HEADER, ...lines].join('\n') + '\n' }));
        fc.assert(fc.property(fc.array(file, { maxLength: 4 }), (files) => {
            expect(parseTrace(files)).toEqual(reference(files));
        }));
    });

    it('counts event deliveries as unknown for a supervisor whose rules changed on module events its log does not record (logs of an older version), not as 0', () => {
        const rule = '2000000000,w,SUP,sup_rule,,,0,"action.SECOND active cause=MAA:2 value=""disconnected"""';
        const received = '1999000000,w,SUP,event_received,MAA,2,16,"from_port=2 latency_ns=1000 taken_ns=1999000000 rules=1 value=""disconnected"""';
        const moduleTook = '1500000000,w,EST,event_received,MAA,0,4,from_port=0 latency_ns=1000';
        const countsOf = (...lines: string[]) => renderStory(parseTrace([{ name: 'X_1.csv', text: [CSV_HEADER, ...lines].join('\n') }])).at(-1)!.replace(/^.* rule changes?, /, '');
        // today's supervisor records each event it takes: counted
        expect(countsOf(received, rule)).toBe('0 data and 1 event delivery, 0 unreadable lines');
        // an older version's: no record of the event the rule changed on
        expect(countsOf(rule)).toBe("0 data and an unknown number of event deliveries (SUP's log is of an older version, which records no event a supervisor takes, though its rules changed on module events), 0 unreadable lines");
        expect(countsOf(moduleTook, rule)).toBe("0 data and 1 event delivery and an unknown number more (SUP's log is of an older version, which records no event a supervisor takes, though its rules changed on module events), 0 unreadable lines");
        // rules that changed on no module event say nothing of deliveries
        expect(countsOf('1000000000,w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns')).toBe('0 data and 0 event deliveries, 0 unreadable lines');
    });

    it('tells the run: rule changes with causes, deadline misses with their cycle, counts', () => {
        const text = [CSV_HEADER, '1000000000,w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns',
            '1000000000,w,SUP,supervisor,MAA,,0,"parameterize MAA:0 (24 bytes) = {i=27.12,j=0,k=0.04}"',
            '1000000000,w,SUP,supervisor,MAA,,0,subscribe MAA:2 =* :2',
            '1500000000,w,ORD,ord_deadline_miss,,,0,schema=S cycle=4 tick_ns=1',
            '1500000000,w,SUP,supervisor,,,0,"notify :1 (string) = ""commutation"""', '2000000000,w,SUP,sup_rule,,,0,"action.SECOND active cause=MAA:2 value=""disconnected"""', 'junk'].join('\n');
        expect(renderStory(parseTrace([{ name: 'X_1.csv', text }]))).toEqual([
            '+0.000000s SUP  rule action.FIRST active   <- elapsed=1ms',
            '+0.000000s SUP  parameterize MAA:0 (24 bytes) = {i=27.12,j=0,k=0.04}',
            '+0.000000s SUP  subscribe MAA:2 =* :2',
            '+0.500000s ORD  deadline miss (ORD:0): S cycle 4',
            '+0.500000s SUP  notify :1 (string) = "commutation"',
            '+1.000000s SUP  rule action.SECOND active   <- MAA:2 = "disconnected"',
            'schema S: 0 completed cycles, 1 deadline miss, 0 overruns',
            // the records are the readable ones (as the IDE's Monitor counts them), the unreadable line apart
            '6 records: 0 module releases, 0 completed cycles, 1 deadline miss, 0 overruns, 0 held cycles, 2 rule changes, 0 data and an unknown number of event deliveries (SUP\'s log is of an older version, which records no event a supervisor takes, though its rules changed on module events), 1 unreadable line',
        ]);
    });

    it('says the figures and counts are partial when a log stopped before the run\'s end (log-capped): ORD\'s misses after its cap are not counted', () => {
        const ord = [CSV_HEADER,
            '1000000000,w,ORD,ord_complete,,,0,schema=fastLoop cycle=0 tick_ns=0 response_ns=500000',
            '1001000000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=1 tick_ns=0',
            '3000000000,w,ORD,log-capped,,,5242880,log stopped at 5242880 bytes: its disk had 1040384 bytes free; less than the logs\' 1048576-byte reserve (CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES) and the 6144 bytes to write: later records are not written',
            '9000000000,w,ORD,log-capped,,,5242880,120000 records not written after the log stopped at 5242880 bytes (its disk below the logs\' 1048576-byte reserve)', ''].join('\n');
        const cur = [CSV_HEADER, '2500000000,w,CUR,log-capped,,,4194304,log stopped at 4194304 bytes: its disk had 3000000 bytes free; less than the logs\' 4194304-byte reserve (CONTRACT_LOG_DISK_RESERVE_BYTES) and the 6144 bytes to write: later records are not written', ''].join('\n');
        const story = renderStory(parseTrace([{ name: 'ORD_1.csv', text: ord }, { name: 'CUR_1.csv', text: cur }]));
        expect(story.slice(-3)).toEqual([
            'schema fastLoop: 1 completed cycle (response max 500 µs), 1 deadline miss, 0 overruns — up to +2.000000s only: ORD\'s log stopped then (log-capped), its later cycles are not counted',
            'partial counts: the logs of CUR (from +1.500000s), ORD (from +2.000000s) stopped before the run\'s end (log-capped): the figures above and the counts below hold only their records up to then',
            '5 records: 0 module releases, 1 completed cycle, 1 deadline miss, 0 overruns, 0 held cycles, 0 rule changes, 0 data and 0 event deliveries, 0 unreadable lines',
        ]);
        // a run whose logs are whole says nothing of the kind
        expect(renderStory(parseTrace([{ name: 'ORD_1.csv', text: ord.split('\n').slice(0, 3).join('\n') + '\n' }])).join('\n')).not.toMatch(/partial counts|up to \+/);
    });

    it('tells once why the run stopped when the launcher\'s KILL says it (the build service\'s limit), not a plain KILL', () => {
        const why = "the build service's memory limit was reached";
        const text = [CSV_HEADER, '1000000000,w,MAA,request_received,contract-launch,,0,KILL',
            `2000000000,w,MAA,request_received,contract-launch,,45,KILL (${why})`, `2000100000,w,MSC,request_received,contract-launch,,45,KILL (${why})`,
            // a KILL from another sender, or a reason with a control character, is no launcher's stop
            '1500000000,w,MSC,request_received,SUP,,20,KILL (not the launcher)'].join('\n');
        const story = renderStory(parseTrace([{ name: 'X_1.csv', text }]));
        expect(story.filter((l) => l.includes('asked to stop'))).toEqual([`+1.000000s MAA  asked to stop by contract-launch: ${why} (every module's KILL says so; the first is told)`]);
    });

    it('counts the readable records apart from the unreadable lines, also for logs of unreadable lines only', () => {
        const teller = new StoryTeller();
        const records = parseTrace([{ name: 'X_1.csv', text: [CSV_HEADER, '1000,w,SUP,error,,,0,x', 'junk', '2000,w,SUP,error,,,0,y', 'more junk', '3000,w,SUP'].join('\n') }]);
        for (const r of records) teller.tell(r);
        expect(teller.recordCounts).toEqual({ records: 2, unreadable: 3 });
        expect(teller.summary()).toMatch(/^2 records: .*, 3 unreadable lines$/);
        expect(renderStory(parseTrace([{ name: 'X_1.csv', text: `${CSV_HEADER}\njunk\n` }])).at(-1)).toMatch(/^0 records: .*, 1 unreadable line$/);
    });

    it("tells a module's own record with the peer, port and size it was logged with, those given", () => {
        const text = [CSV_HEADER,
            '1000,w,MAA,gripper_closed,MAB,2,16,force=12.5 N',
            '2000,w,MAA,homed,,0,0,',          // port 0 is a port
            '3000,w,MAA,waiting,,,0,for the gripper', // ContractLog(event, "", -1, 0, detail): nothing more
            '4000,w,MAA,sent,SUP,,1,',
            '',
        ].join('\n');
        expect(renderStory(parseTrace([{ name: 'MAA_1.csv', text }])).slice(0, 4)).toEqual([
            '+0.000000s MAA  gripper_closed: force=12.5 N (peer MAB, port 2, 16 bytes)',
            '+0.000001s MAA  homed (port 0)',
            '+0.000002s MAA  waiting: for the gripper',
            '+0.000003s MAA  sent (peer SUP, 1 byte)',
        ]);
    });

    it('tells each periodic schema\'s figures before the counts: cycles completed with the longest response, misses, every skipped release, held cycles, ORD\'s missed ticks', () => {
        const text = [CSV_HEADER,
            '1000,w,ORD,ord_complete,,,0,schema=velocityLoop cycle=0 tick_ns=0 response_ns=2500000',
            '2000,w,ORD,ord_complete,,,0,schema=velocityLoop cycle=1 tick_ns=0 response_ns=100312000',
            '3000,w,ORD,ord_deadline_miss,,,0,schema=velocityLoop cycle=2 tick_ns=0',
            '4000,w,ORD,scheduler,,,0,"overrun: velocityLoop cycle still running, release skipped"',
            '5000,w,ORD,scheduler,,,0,overrun: velocityLoop cycle ended after 8 skipped releases',
            '6000,w,ORD,scheduler,,,0,cycle of velocityLoop held: VEL still runs a release of an earlier activation',
            '7000,w,ORD,scheduler,,,0,missed tick of localisationLoop (cycle 12)',
            '7500,w,ORD,scheduler,,,0,missed ticks: localisationLoop cycle ended after 4 missed ticks',
            '8000,w,ORD,ord_complete,,,0,schema=localisationLoop cycle=13 tick_ns=0 response_ns=900',
            '9000,w,ORD,ord_complete,,,0,schema=ALPHA cycle=0 tick_ns=0 response_ns=-5',
            '',
        ].join('\n');
        const story = renderStory(parseTrace([{ name: 'ORD_1.csv', text }]));
        expect(story.slice(-4)).toEqual([
            'schema ALPHA: 1 completed cycle (response max 0 ns), 0 deadline misses, 0 overruns', // a forged negative response is no maximum
            'schema localisationLoop: 1 completed cycle (response max 900 ns), 0 deadline misses, 0 overruns, 4 missed ticks (ORD itself late)',
            'schema velocityLoop: 2 completed cycles (response max 100.312 ms), 1 deadline miss, 8 overruns, 1 held cycle',
            '10 records: 0 module releases, 4 completed cycles, 1 deadline miss, 8 overruns, 1 held cycle, 0 rule changes, 0 data and 0 event deliveries, 0 unreadable lines',
        ]);
        // a forged log naming more schemas than the story follows: bounded, and said
        const many = [CSV_HEADER, ...Array.from({ length: STORY_FOLLOWED + 3 }, (_, i) => `${i + 1},w,ORD,ord_deadline_miss,,,0,schema=S${i} cycle=0 tick_ns=0`)].join('\n');
        const told = renderStory(parseTrace([{ name: 'ORD_1.csv', text: many }]));
        expect(told.filter((l) => l.startsWith('schema S'))).toHaveLength(STORY_FOLLOWED);
        expect(told.at(-2)).toBe(`(3 records of schemas past the ${STORY_FOLLOWED} followed: in the counts below only)`);
    });

    it('tells how late ORD released each periodic schema\'s cycles (release_ns - tick_ns of each cycle\'s first release): p50, p99, max', () => {
        // 100 cycles of a 10 ms schema: 98 released 20 µs late, one 965 µs, one 8.8 ms; the second release of a cycle is not ORD's lateness
        const lines = Array.from({ length: 100 }, (_, c) => {
            const tick = 1_000_000_000 + c * 10_000_000;
            const late = c === 40 ? 965_000 : c === 70 ? 8_800_000 : 20_000;
            return [`${tick + late},w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=${c} tick_ns=${tick} release_ns=${tick + late} release=${2 * c + 1}`,
                `${tick + late + 500_000},w,ORD,ord_release,CUR,,0,schema=fastLoop cycle=${c} tick_ns=${tick} release_ns=${tick + late + 500_000} release=${2 * c + 2}`,
                `${tick + late + 600_000},w,ORD,ord_complete,,,0,schema=fastLoop cycle=${c} tick_ns=${tick} response_ns=${late + 600_000}`];
        }).flat();
        const story = storyOfLog('ORD_1.csv', lines);
        expect(story.at(-2)).toBe('schema fastLoop: 100 completed cycles (response max 9.4 ms), 0 deadline misses, 0 overruns; release lateness p50 20 µs, p99 965 µs, max 8.8 ms');
    });

    it('tells a supervisor\'s start, stop, connect, disconnect and priority claims in the simulator\'s words, and not again the hold records that only confirm them', () => {
        const text = [CSV_HEADER,
            '1000,w,MIS,supervisor,,,0,activate schema groundLink(channel = 2) (event schema)',
            '1010,w,MIS,supervisor,GCS,,0,parameterize GCS:0 (8 bytes) = 2',
            '1020,w,MIS,supervisor,GCS,,0,connect GCS:0 =* REC:0',
            '1030,w,MIS,flow_hold,flow-GCS-0-REC-0,,0,hold taken',
            '1040,w,MIS,supervisor,GCS,,0,start module GCS (priority 30)',
            '1050,w,MIS,module_priority,GCS,,0,nice level for priority 30 (was 40)',
            '1060,w,MIS,module_hold,GCS,,0,hold taken (started it)',
            '1070,w,MIS,supervisor,REC,,0,start module REC (priority 30)',
            '1075,w,REC,request_received,MIS,,0,START',
            '1080,w,MIS,module_hold,REC,,0,hold taken (started it)',
            // says more than the action: told
            '1090,w,MIS,module_hold,NAV,,0,hold taken (it was running)',
            '1100,w,MIS,supervisor,NAV,,0,set priority of NAV to 84 (claim #3)',
            '1110,w,MIS,module_priority,NAV,,0,nice level for priority 84 (was 30)',
            '2000,w,MIS,supervisor,NAV,,0,undo: release priority claim #3 on NAV',
            '2010,w,MIS,supervisor,,,0,undo: deactivate schema groundLink (event schema)',
            '2020,w,MIS,supervisor,GCS,,0,undo: disconnect GCS:0 =* REC:0',
            '2030,w,MIS,flow_hold,flow-GCS-0-REC-0,,0,hold dropped (kept connected: used by 1 other supervisor(s))',
            '2040,w,MIS,supervisor,GCS,,0,undo: stop module GCS',
            '2050,w,MIS,module_hold,GCS,,0,last hold dropped (stopped)',
            '2060,w,MIS,supervisor,REC,,0,undo: stop module REC',
            '2070,w,MIS,module_hold,REC,,0,hold dropped (kept running: still used by 1 other supervisor(s))',
            '2080,w,MIS,module_hold,NAV,,0,last hold dropped (stopped)',
            // a start it could not send: no hold; a hold of another module than the action's: told
            '3000,w,MIS,supervisor,CAM,,0,start module CAM (priority 30)',
            '3010,w,MIS,supervisor,CAM,,0,"error: not sent: start module CAM (priority 30): no such module"',
            '3020,w,MIS,supervisor,GCS,,0,start module GCS (priority 30)',
            '3030,w,MIS,module_hold,GCS,,0,cannot record the hold in the run directory',
            '3040,w,MIS,supervisor,GCS,,0,undo: stop module GCS',
            '3050,w,MIS,module_hold,GCS,,0,last hold dropped (stop failed)',
            '',
        ].join('\n');
        const story = renderStory(parseTrace([{ name: 'MIS_1.csv', text }])).slice(0, -1).map((l) => l.slice(11));
        expect(story).toEqual([
            'MIS  activate schema groundLink(channel = 2) (event schema)',
            'MIS  parameterize GCS:0 (8 bytes) = 2',
            'MIS  connect GCS:0 =* REC:0',
            'MIS  start module GCS (priority 30)',
            'MIS  start module REC (priority 30)',
            'MIS  module NAV: hold taken (it was running)',
            'MIS  set priority of NAV to 84 (claim #3)',
            'MIS  undo: release priority claim #3 on NAV',
            'MIS  undo: deactivate schema groundLink (event schema)',
            'MIS  undo: disconnect GCS:0 =* REC:0',
            'MIS  event flow GCS:0 -> REC:0: hold dropped (kept connected: used by 1 other supervisor(s))',
            'MIS  undo: stop module GCS',
            'MIS  undo: stop module REC',
            'MIS  module REC: hold dropped (kept running: still used by 1 other supervisor(s))',
            // the last holder of a module it only shared stops it: no action line before it
            'MIS  module NAV: last hold dropped (stopped)',
            'MIS  start module CAM (priority 30)',
            'MIS  error: not sent: start module CAM (priority 30): no such module',
            'MIS  start module GCS (priority 30)',
            'MIS  module GCS: cannot record the hold in the run directory',
            'MIS  undo: stop module GCS',
            'MIS  module GCS: last hold dropped (stop failed)',
        ]);
        // a hold record confirms only its own supervisor's action line, the one just before it
        const two = storyOfLog('A_1.csv', [
            '1000,w,SUA,supervisor,GCS,,0,start module GCS (priority 30)',
            '1010,w,SUB,module_hold,GCS,,0,hold taken (started it)',
            '1020,w,SUA,supervisor,,,0,rule f.R active',
            '1030,w,SUA,module_hold,GCS,,0,hold taken (started it)',
        ]).slice(0, -1).map((l) => l.slice(11));
        expect(two).toEqual(['SUA  start module GCS (priority 30)', 'SUB  module GCS: hold taken (started it)', 'SUA  module GCS: hold taken (started it)']);
    });

    it('tells the modules a supervisor starts and stops, the event flows it connects, and a request it could not send', () => {
        const text = [CSV_HEADER,
            '1000,w,LIN,supervisor,,,0,activate schema sorting (event schema)',
            '1100,w,LIN,flow_hold,flow-SCN-0-DIV-0,,0,hold taken',
            '1200,w,LIN,module_hold,SCN,,0,hold taken (started it)',
            '1300,w,LIN,module_priority,SCN,,0,nice level for priority 30 (was 30)',
            '1400,w,LIN,supervisor,ORD,,0,"activate schema conveyor(speed = 0.6) (activation #2, to ORD)"',
            '1500,w,LIN,supervisor,ORD,,0,"error: not sent: activate schema conveyor(speed = 0.6) (activation #2, to ORD): no such module"',
            '2000,w,LIN,flow_hold,flow-SCN-0-DIV-0,,0,last hold dropped (disconnected)',
            '2100,w,LIN,module_hold,SCN,,0,last hold dropped (stopped)',
            '2200,w,STA,supervisor,contract-launch,,0,refused: start request from contract-launch: STA.station has no parameter \'sped\'',
            '2300,w,LIN,supervisor,,,0,activation #3 of STA.station refused: its undo stops nothing',
            '2400,w,LIN,supervisor,,,0,launch the missiles',
            '',
        ].join('\n');
        expect(renderStory(parseTrace([{ name: 'LIN_1.csv', text }])).slice(0, -1)).toEqual([
            '+0.000000s LIN  activate schema sorting (event schema)',
            '+0.000000s LIN  event flow SCN:0 -> DIV:0: hold taken',
            '+0.000000s LIN  module SCN: hold taken (started it)',
            '+0.000000s LIN  activate schema conveyor(speed = 0.6) (activation #2, to ORD)',
            '+0.000000s LIN  error: not sent: activate schema conveyor(speed = 0.6) (activation #2, to ORD): no such module',
            '+0.000001s LIN  event flow SCN:0 -> DIV:0: last hold dropped (disconnected)',
            '+0.000001s LIN  module SCN: last hold dropped (stopped)',
            "+0.000001s STA  refused: start request from contract-launch: STA.station has no parameter 'sped'",
            '+0.000001s LIN  activation #3 of STA.station refused: its undo stops nothing',
            // a line no engine writes is told, but not as an action
            '+0.000001s LIN  (a supervisor line this reader does not know) launch the missiles',
        ]);
        // a module that had exited (a crash the simulator made) is not told to set *stateindex = -1
        const crashed = storyOfLog('X_1.csv', [
            '1500000000,w,SPC,module_exit,,,0,crashed (simulated)',
            '2502000000,w,ORD,scheduler,,,0,stuck: SPC has not finished release #228 after 50 periods (of a deactivated activation): does its exec region set *stateindex = -1? (conveyor)',
            '2503000000,w,ORD,scheduler,,,0,stuck: ENC has not finished release #229 after 50 periods: does its exec region set *stateindex = -1? (conveyor)',
        ]);
        // a crash the runtime's signal handler wrote (module_crashed): told as the crash, and a later stuck report says it
        const segv = storyOfLog('X_1.csv', [
            '1500000000,w,SPC,module_crashed,,,0,signal 11 (SIGSEGV) records=42',
            '2502000000,w,ORD,scheduler,,,0,stuck: SPC has not finished release #228 after 50 periods: does its exec region set *stateindex = -1? (conveyor)',
        ]);
        expect(segv.slice(0, 2)).toEqual([
            '+0.000000s SPC  crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array',
            '+1.002000s ORD  stuck: SPC has not finished release #228 after 50 periods: it had exited before (crashed: signal 11 (SIGSEGV)) (conveyor)',
        ]);
        // started again after its exit: a later stuck report gets ORD's advice again
        const again = storyOfLog('X_1.csv', [
            '1500000000,w,SPC,module_exit,,,0,crashed (simulated)',
            '1600000000,w,SPC,module_started,,,0,pid=7 priority=84',
            '2502000000,w,ORD,scheduler,,,0,stuck: SPC has not finished release #228 after 50 periods: does its exec region set *stateindex = -1? (conveyor)',
        ]);
        expect(again.filter((l) => l.includes('stuck:'))).toEqual(['+1.002000s ORD  stuck: SPC has not finished release #228 after 50 periods: does its exec region set *stateindex = -1? (conveyor)']);
        expect(crashed.filter((l) => l.includes('stuck:'))).toEqual([
            '+1.002000s ORD  stuck: SPC has not finished release #228 after 50 periods (of a deactivated activation): it had exited before (crashed (simulated)) (conveyor)',
            '+1.003000s ORD  stuck: ENC has not finished release #229 after 50 periods: does its exec region set *stateindex = -1? (conveyor)',
        ]);
    });

    it("tells a run a supervisor or a control tool began that its module's own code ended (no STOP, no ack); not a release's end or a stopped run", () => {
        const story = storyOfLog('X_1.csv', [
            '1000000,w,MAB,run_started,SUP,,0,activation=1',
            '1200000,w,MAB,run_finished,,,0,activation=1 cpu_ns=41000',                // its code set *stateindex = -1
            '2000000,w,SCN,run_started,ALF,,0,activation=1',
            '3000000,w,SCN,run_finished,BET,,0,activation=1 cpu_ns=41000 STOP',       // stopped: the holds tell it
            '4000000,w,MSC,run_started,ORD,,0,activation=7',
            '4500000,w,MSC,run_finished,ORD,,0,activation=7 cpu_ns=41000 ACK_FINISHED', // a release's end
            '5000000,w,TEL,run_started,,,0,activation=2',                 // a control tool's START
            '6000000,w,TEL,run_finished,,,0,activation=2 cpu_ns=41000',
            '7000000,w,TEL,run_finished,,,0,activation=3 cpu_ns=41000',               // no start read: not told
        ]);
        expect(story.slice(0, -1)).toEqual([
            '+0.000200s MAB  run #1 ended by its own code (started by SUP)',
            '+0.005000s TEL  run #2 ended by its own code (started by a control tool)',
        ]);
    });

    it('tells the first value each data flow dropped, with why, and counts every drop at the end', () => {
        const story = storyOfLog('X_1.csv', [
            '1000000,w,CAM,data_posted,SRT,0,24,to_port=0',
            '2000000,w,CAM,data_dropped,SRT,0,24,to_port=0 queue full',      // SRT never reads: told once
            '3000000,w,CAM,data_dropped,SRT,0,24,to_port=0 queue full',
            '3000000,w,CAM,data_dropped,LOG,0,24,to_port=2 queue full',      // another flow of the same port
            '4000000,w,CAM,data_dropped,SRT,0,24,to_port=0 queue full',
            '5000000,w,GPS,data_dropped,NAV,1,16,to_port=3 Connection refused',
        ]);
        expect(story).toEqual([
            '+0.001000s CAM  data CAM:0 -> SRT:0 dropped: queue full (SRT does not read its input :0 as fast as it comes: its exec region calls GetData or GetLatestData too seldom, or not at all); its later drops are counted at the end',
            '+0.002000s CAM  data CAM:0 -> LOG:2 dropped: queue full (LOG does not read its input :2 as fast as it comes: its exec region calls GetData or GetLatestData too seldom, or not at all); its later drops are counted at the end',
            '+0.004000s GPS  data GPS:1 -> NAV:3 dropped: Connection refused; its later drops are counted at the end',
            '6 records: 0 module releases, 0 completed cycles, 0 deadline misses, 0 overruns, 0 held cycles, 0 rule changes, 0 data and 0 event deliveries, 5 data values dropped, 0 unreadable lines',
        ]);
    });

    it('tells the first event of each port that no one received (no subscriber), and counts them all at the end', () => {
        const story = storyOfLog('X_1.csv', [
            '1000000,w,DET,event_posted,PRD,0,32,to_port=1',
            '2000000,w,DET,event_posted,,0,32,no subscriber',      // PRD had unsubscribed: why its rule did not fire
            '3000000,w,DET,event_posted,,0,32,no subscriber',
            '4000000,w,HMI,event_posted,,2,8,no subscriber',
        ]);
        expect(story).toEqual([
            '+0.001000s DET  event DET:0 posted with no subscriber: no one received it (no supervisor or module subscribed to DET:0 then); its later ones are counted at the end',
            '+0.003000s HMI  event HMI:2 posted with no subscriber: no one received it (no supervisor or module subscribed to HMI:2 then); its later ones are counted at the end',
            '4 records: 0 module releases, 0 completed cycles, 0 deadline misses, 0 overruns, 0 held cycles, 0 rule changes, 0 data and 0 event deliveries, 3 events with no subscriber, 0 unreadable lines',
        ]);
    });

    it('names the modules a missed cycle still waits for, or the module its held cycle waits for; tells held, resumed and stuck; a record before the first is at a negative time', () => {
        const text = [CSV_HEADER,
            '1000000000,w,ORD,ord_release,CAM,,0,schema=pick cycle=7 tick_ns=1000000000 release_ns=1000000000 release=20',
            '1000000000,w,ORD,ord_release,GRP,,0,schema=pick cycle=7 tick_ns=1000000000 release_ns=1000000000 release=21',
            '1001000000,w,ORD,ord_finished,CAM,,0,schema=pick cycle=7 release=20 response_ns=1000000',
            '1015000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=7 tick_ns=1000000000',
            '1016000000,w,ORD,scheduler,,,0,deactivate pick',
            '1017000000,w,ORD,scheduler,,,0,activate pick',
            '1017000000,w,ORD,scheduler,,,0,cycle of pick held: GRP still runs a release of an earlier activation',
            '1032000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=0 tick_ns=1017000000',
            '2000000000,w,ORD,scheduler,,,0,stuck: GRP has not finished release #21 after 50 periods (of a deactivated activation): does its exec region set *stateindex = -1? (pick)',
            '2100000000,w,ORD,scheduler,,,0,late ack: GRP finished release #21 of an earlier cycle of pick (not counted, reported stuck)',
            '2100000000,w,ORD,scheduler,,,0,cycle of pick resumed',
            '2100000000,w,ORD,ord_release,CAM,,0,schema=pick cycle=0 tick_ns=1017000000 release_ns=2100000000 release=22',
            '2130000000,w,ORD,ord_deadline_miss,,,0,schema=pick cycle=0 tick_ns=1017000000',
            '',
        ].join('\n');
        const told = renderStory(parseTrace([{ name: 'ORD_1.csv', text }]));
        expect(told.filter((l) => / ORD {2}(deadline|cycle|stuck)/.test(l))).toEqual([
            '+0.015000s ORD  deadline miss (ORD:0): pick cycle 7 (not finished: GRP)',
            '+0.017000s ORD  cycle of pick held: GRP still runs a release of an earlier activation',
            '+0.032000s ORD  deadline miss (ORD:0): pick cycle 0 (held: nothing released, GRP still runs an earlier release)',
            '+1.000000s ORD  stuck: GRP has not finished release #21 after 50 periods (of a deactivated activation): does its exec region set *stateindex = -1? (pick)',
            '+1.100000s ORD  cycle of pick resumed',
            '+1.130000s ORD  deadline miss (ORD:0): pick cycle 0 (not finished: CAM; ORD released the cycle 1083.0 ms after its tick)',
        ]);
        // a stuck record that says its module is no longer running (a crash, ORD's words on stderr too): the cycles
        // held for it and their misses do not say it "still runs" its release; started again, it is followed afresh
        const dead = storyOfLog('ORD_1.csv', [
            '1000000000,w,ORD,scheduler,,,0,cycle of loop held: VEL still runs a release of an earlier activation',
            '1500000000,w,ORD,scheduler,,,0,stuck: VEL has not finished release #204 after 100 periods: it is no longer running (it crashed or was killed) (loop)',
            '1518000000,w,ORD,scheduler,,,0,activate loop (activation #4 from DRV)',
            '1518000000,w,ORD,scheduler,,,0,cycle of loop held: VEL still runs a release of an earlier activation',
            '1531000000,w,ORD,ord_deadline_miss,,,0,schema=loop cycle=0 tick_ns=1518000000',
            '1600000000,w,VEL,module_started,,,0,pid=9 priority=84',
            '1700000000,w,ORD,scheduler,,,0,cycle of loop held: VEL still runs a release of an earlier activation',
            '1710000000,w,ORD,ord_deadline_miss,,,0,schema=loop cycle=0 tick_ns=1700000000',
        ]);
        expect(dead.filter((l) => / ORD {2}(deadline|cycle|stuck)/.test(l))).toEqual([
            '+0.000000s ORD  cycle of loop held: VEL still runs a release of an earlier activation',
            '+0.500000s ORD  stuck: VEL has not finished release #204 after 100 periods: it is no longer running (it crashed or was killed) (loop)',
            '+0.518000s ORD  cycle of loop held: VEL never finished a release of an earlier activation: it is no longer running',
            '+0.531000s ORD  deadline miss (ORD:0): loop cycle 0 (held: nothing released, VEL never finished an earlier release: it is no longer running)',
            '+0.700000s ORD  cycle of loop held: VEL still runs a release of an earlier activation',
            '+0.710000s ORD  deadline miss (ORD:0): loop cycle 0 (held: nothing released, VEL still runs an earlier release)',
        ]);
        expect(missWaitText('VEL', '', undefined, true)).toBe(' (held: nothing released, VEL never finished an earlier release: it is no longer running)');
        expect(missWaitText('VEL', '')).toBe(' (held: nothing released, VEL still runs an earlier release)');
        // every line ORD writes to its CSV log is typed; those a reader needs are told (an overrun's end, a stuck
        // module finishing at last, a table warning), the expected ones are not, and a line no version writes is told as such
        const ord = storyOfLog('ORD_1.csv', [
            '1000,w,ORD,scheduler,,,0,"overrun: alt cycle still running, release skipped"',
            '2000,w,ORD,scheduler,,,0,overrun: alt cycle ended after 2 skipped releases',
            '3000,w,ORD,scheduler,,,0,"GRP finished release #21 at last (reported stuck, pick)"',
            '4000,w,ORD,scheduler,,,0,late ack: GRP finished release #21 of an earlier cycle of pick (not counted)',
            '5000,w,ORD,scheduler,,,0,ignored: GRP finished outside a cycle (release #22 is not outstanding)',
            '6000,w,ORD,scheduler,,,0,"warning: alt activated with 4 parameter bytes, its tables say 8 (tables of ORD and FLT from different generations?)"',
            '7000,w,ORD,scheduler,,,0,reboot the drone',
        ]);
        expect(ord.slice(0, -1)).toEqual([
            '+0.000000s ORD  overrun: alt cycle still running, release skipped',
            '+0.000001s ORD  overrun: alt cycle ended after 2 skipped releases',
            '+0.000002s ORD  GRP finished release #21 at last (reported stuck, pick)',
            '+0.000005s ORD  warning: alt activated with 4 parameter bytes, its tables say 8 (tables of ORD and FLT from different generations?)',
            '+0.000006s ORD  (an ORD line this reader does not know) reboot the drone',
            'schema alt: 0 completed cycles, 0 deadline misses, 2 overruns',
        ]);
        // the summary counts every skipped release, as ORD does: the first line is one, its end says 2 in all
        expect(ord.at(-1)).toContain(', 2 overruns, 0 held cycles, ');
        // a cycle ORD released late (it woke 13.4 ms after the tick): said, not only the module that then missed
        const late = storyOfLog('ORD_1.csv', [
            '3000000000,w,ORD,ord_release,ENC,,0,schema=conveyor cycle=66 tick_ns=2986600000 release_ns=3000000000 release=300',
            '3000100000,w,ORD,ord_release,SPC,,0,schema=conveyor cycle=66 tick_ns=2986600000 release_ns=3000100000 release=301',
            '3001600000,w,ORD,ord_deadline_miss,,,0,schema=conveyor cycle=66 tick_ns=2986600000',
            '3020000000,w,ORD,ord_release,ENC,,0,schema=conveyor cycle=67 tick_ns=3006600000 release_ns=3006600500 release=302',
            '3021700000,w,ORD,ord_deadline_miss,,,0,schema=conveyor cycle=67 tick_ns=3006600000',
        ]);
        expect(late.filter((l) => l.includes(' deadline miss ('))).toEqual([
            '+0.001600s ORD  deadline miss (ORD:0): conveyor cycle 66 (not finished: ENC, SPC; ORD released the cycle 13.4 ms after its tick)',
            '+0.021700s ORD  deadline miss (ORD:0): conveyor cycle 67 (not finished: ENC)', // 500 ns late: on time
        ]);
        // a miss that says its CRITICAL_DELAY (800 µs): the release lateness is measured against it, not 1 ms. ORD
        // released cycle 67 826 µs after its tick (the field test's fastLoop, 7 µs before the miss): ORD was late, not
        // ENC; cycle 68 with 20 µs of the 800 left: ORD late too; cycle 69 released 200 µs late: noted, ENC named;
        // cycle 70 released 50 µs late (under a tenth): ENC named alone
        const cd = storyOfLog('ORD_1.csv', [
            '5000826000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=67 tick_ns=5000000000 release_ns=5000826000 release=1',
            '5000833000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=67 tick_ns=5000000000 critical_delay_ns=800000',
            '5001780000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=68 tick_ns=5001000000 release_ns=5001780000 release=2',
            '5001800000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=68 tick_ns=5001000000 critical_delay_ns=800000',
            '5002200000,w,ORD,ord_release,CUR,,0,schema=fastLoop cycle=69 tick_ns=5002000000 release_ns=5002200000 release=3',
            '5002200000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=69 tick_ns=5002000000 release_ns=5002200000 release=4',
            '5002800000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=69 tick_ns=5002000000 critical_delay_ns=800000',
            '5003050000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=70 tick_ns=5003000000 release_ns=5003050000 release=5',
            '5003800000,w,ORD,ord_deadline_miss,,,0,schema=fastLoop cycle=70 tick_ns=5003000000 critical_delay_ns=800000',
        ]);
        expect(cd.filter((l) => l.includes(' deadline miss ('))).toEqual([
            '+0.000007s ORD  deadline miss (ORD:0): fastLoop cycle 67 (ORD late: it released the cycle 826 µs after its tick, past CRITICAL_DELAY 800 µs, leaving ENC no time)',
            '+0.000974s ORD  deadline miss (ORD:0): fastLoop cycle 68 (ORD late: it released the cycle 780 µs after its tick, 20 µs before CRITICAL_DELAY 800 µs, leaving ENC 20 µs)',
            '+0.001974s ORD  deadline miss (ORD:0): fastLoop cycle 69 (not finished: CUR, ENC; ORD released the cycle 200 µs after its tick, of CRITICAL_DELAY 800 µs)',
            '+0.002974s ORD  deadline miss (ORD:0): fastLoop cycle 70 (not finished: ENC)',
        ]);
        // since 2026-12-07 ORD sends no ORD:0 for a cycle it released itself at or past CRITICAL_DELAY (no miss
        // record): its own line tells that miss as ORD's
        const ordLate = storyOfLog('ORD_1.csv', [
            '5000826000,w,ORD,ord_release,ENC,,0,schema=fastLoop cycle=67 tick_ns=5000000000 release_ns=5000826000 release=1',
            '5000826000,w,ORD,scheduler,,,0,"late release: fastLoop cycle 67 released 826 us after its tick, past CRITICAL_DELAY 800 us (ORD late, no ORD:0)"',
            '5001100000,w,ORD,ord_complete,,,0,schema=fastLoop cycle=67 tick_ns=5000000000 response_ns=1100000',
        ]);
        expect(ordLate.filter((l) => l.includes('late release') || l.includes('deadline miss'))).toEqual([
            '+0.000000s ORD  late release: fastLoop cycle 67 released 826 us after its tick, past CRITICAL_DELAY 800 us (ORD late, no ORD:0)',
            'schema fastLoop: 1 completed cycle (response max 1.1 ms), 0 deadline misses, 0 overruns, 1 cycle released past CRITICAL_DELAY (ORD itself late, no ORD:0); release lateness p50 826 µs, p99 826 µs, max 826 µs',
            '3 records: 1 module release, 1 completed cycle, 0 deadline misses, 0 overruns, 0 held cycles, 0 rule changes, 0 data and 0 event deliveries, 0 unreadable lines',
        ]);
        // the auditor's miss (slow cycle 152, nice levels under load): HOG finished 2.24 ms after the tick and sent its ack
        // at 2.25 ms; ORD read it 13.82 ms after the tick, past CRITICAL_DELAY 10 ms. HOG is not blamed: ORD was late
        const T = 7_000_000_000;
        const ordLog = [
            `${T + 1_724_000},w,ORD,ord_release,HOG,,0,schema=slow cycle=152 tick_ns=${T} release_ns=${T + 1_724_000} release=684`,
            `${T + 1_730_000},w,ORD,ord_release,ARM,,0,schema=slow cycle=152 tick_ns=${T} release_ns=${T + 1_730_000} release=685`,
            `${T + 10_010_000},w,ORD,ord_deadline_miss,,,0,schema=slow cycle=152 tick_ns=${T} critical_delay_ns=10000000`,
            `${T + 13_820_000},w,ORD,ack_received,HOG,,0,ACK_FINISHED id=684`,
            `${T + 13_822_000},w,ORD,ord_finished,HOG,,0,schema=slow cycle=152 release=684 response_ns=13822000`,
            `${T + 14_100_000},w,ORD,ack_received,ARM,,0,ACK_FINISHED id=685`,
            `${T + 14_102_000},w,ORD,ord_finished,ARM,,0,schema=slow cycle=152 release=685 response_ns=14102000`,
        ];
        const hogLog = [
            `${T + 1_750_000},w,HOG,request_received,ORD,,0,START`,
            `${T + 1_751_000},w,HOG,run_started,ORD,,0,activation=152`,
            `${T + 2_240_000},w,HOG,run_finished,,,0,activation=152 cpu_ns=41000 ACK_FINISHED`,
            `${T + 2_250_000},w,HOG,ack_sent,ORD,,0,ACK_FINISHED id=684`,
        ];
        // ARM really finished after the deadline (its ack at +12 ms): it is still named
        const armLog = [
            `${T + 1_760_000},w,ARM,request_received,ORD,,0,START`,
            `${T + 12_000_000},w,ARM,ack_sent,ORD,,0,ACK_FINISHED id=685`,
        ];
        const logOf = (name: string, lines: string[]) => ({ name, text: [CSV_HEADER, ...lines, ''].join('\n') });
        const hogOnly = renderStory(parseTrace([logOf('ORD_1.csv', ordLog.filter((l) => !l.includes('ARM'))), logOf('HOG_1.csv', hogLog)]));
        expect(hogOnly.filter((l) => / deadline miss \(|ORD  read /.test(l))).toEqual([
            '+0.008286s ORD  deadline miss (ORD:0): slow cycle 152 (HOG finished at +2.250 ms (its ack sent), ORD had not read it at the deadline, 7.75 ms later: ORD was late; ORD released the cycle 1.724 ms after its tick, of CRITICAL_DELAY 10 ms)',
            '+0.012098s ORD  read HOG\'s ack of slow cycle 152 at +13.822 ms, 11.572 ms after HOG sent it (ORD\'s response_ns counts to this read, not to HOG\'s finish)',
        ]);
        const both = renderStory(parseTrace([logOf('ORD_1.csv', ordLog), logOf('HOG_1.csv', hogLog), logOf('ARM_1.csv', armLog)]));
        expect(both.filter((l) => l.includes(' deadline miss ('))).toEqual([
            '+0.008286s ORD  deadline miss (ORD:0): slow cycle 152 (not finished: ARM; HOG finished at +2.250 ms (its ack sent), ORD had not read it at the deadline, 7.75 ms later: ORD was late reading it; ORD released the cycle 1.724 ms after its tick, of CRITICAL_DELAY 10 ms)',
        ]);
        // its run_finished alone (the ack_sent record lost): said so; HOG's ack after the deadline: HOG is named
        const runOnly = renderStory(parseTrace([logOf('ORD_1.csv', ordLog.filter((l) => !l.includes('ARM'))), logOf('HOG_1.csv', hogLog.slice(0, 3))]));
        expect(runOnly.filter((l) => l.includes(' deadline miss ('))[0]).toContain('(HOG finished at +2.240 ms (its run finished), ORD had not read it at the deadline, 7.76 ms later: ORD was late;');
        const lateHog = renderStory(parseTrace([logOf('ORD_1.csv', ordLog.filter((l) => !l.includes('ARM'))), logOf('HOG_1.csv', hogLog.slice(0, 2).concat(`${T + 10_500_000},w,HOG,ack_sent,ORD,,0,ACK_FINISHED id=684`))]));
        expect(lateHog.filter((l) => / deadline miss \(|ORD  read /.test(l))).toEqual([
            '+0.008286s ORD  deadline miss (ORD:0): slow cycle 152 (not finished: HOG; ORD released the cycle 1.724 ms after its tick, of CRITICAL_DELAY 10 ms)',
        ]);
        // a new activation's cycle 0 waits for its own releases only: DRV's release of the deactivated
        // activation's cycle 0, acknowledged late, is not one of them (field test 7)
        const again = storyOfLog('ORD_1.csv', [
            '4000000000,w,ORD,scheduler,,,0,activate armLoop (activation #1 from CEL)',
            '4000100000,w,ORD,ord_release,DRV,,0,schema=armLoop cycle=0 tick_ns=4000000000 release_ns=4000100000 release=641',
            '4000500000,w,ORD,scheduler,,,0,deactivate armLoop (activation #1 from CEL)',
            '4000800000,w,ORD,scheduler,,,0,late ack: DRV release #641 (armLoop, deactivated): not counted',
            '4300000000,w,ORD,scheduler,,,0,activate armLoop (activation #2 from CEL)',
            '4300010000,w,ORD,ord_release,ENC,,0,schema=armLoop cycle=0 tick_ns=4300000000 release_ns=4300010000 release=642',
            '4301000000,w,ORD,ord_deadline_miss,,,0,schema=armLoop cycle=0 tick_ns=4300000000',
        ]);
        expect(again.filter((l) => l.includes(' deadline miss ('))).toEqual(['+0.301000s ORD  deadline miss (ORD:0): armLoop cycle 0 (not finished: ENC)']);
        // a trace file's record placed before the first one (times are the file's): a negative offset, not "+-"
        const teller = new StoryTeller();
        teller.tell(parseRecordLine('X_1.csv', 2, '5000000000,w,X,error,,,0,first'));
        expect(teller.tell(parseRecordLine('X_1.csv', 3, '4999900000,w,X,error,,,0,earlier'))).toBe('-0.000100s X    error: earlier');
    });

    it('says after ORD\'s start whether the run was real-time: ORD\'s priority record, SCHED_FIFO or a nice level', () => {
        const rt = storyOfLog('ORD_1.csv', ['1000,w,ORD,module_started,,,0,pid=24 priority=90', '2000,w,ORD,priority,,,0,SCHED_FIFO 90']);
        expect(rt.slice(0, 2)).toEqual(['+0.000000s ORD  started (pid=24 priority=90)', '+0.000001s ORD  priority SCHED_FIFO 90 (real-time)']);
        const nice = storyOfLog('ORD_1.csv', ['1000,w,ORD,module_started,,,0,pid=24 priority=90', '2000,w,ORD,priority,,,0,nice 1 (priority 90)']);
        expect(nice.slice(0, 2)).toEqual(['+0.000000s ORD  started (pid=24 priority=90)', '+0.000001s ORD  priority nice 1 (priority 90): not real-time, a nice level']);
        // a module's own priority record is not told (ORD's says which mode the run had)
        expect(storyOfLog('MSC_1.csv', ['1000,w,MSC,module_started,,,0,pid=41 priority=40', '2000,w,MSC,priority,,,0,nice 11 (priority 40)'])
            .filter((l) => l.includes(' priority '))).toEqual([]);
    });

    it('tells an error as an error, and a request to a module gone while the launcher stopped the run as such', () => {
        const text = [CSV_HEADER, '1000000000,w,OBS,error,,,0,input data port 0: dropped a malformed datagram of 3 bytes',
            '2000000000,w,OBS,error,,,0,EVENT request to MIS: unknown module (no mailbox in the run directory) (No such file or directory; the run is stopping)', ''].join('\n');
        expect(renderStory(parseTrace([{ name: 'OBS_1.csv', text }])).slice(0, 2)).toEqual([
            '+0.000000s OBS  error: input data port 0: dropped a malformed datagram of 3 bytes',
            '+1.000000s OBS  while the run stopped: EVENT request to MIS: unknown module (no mailbox in the run directory) (No such file or directory; the run is stopping)',
        ]);
    });
});

describe("a supervisor's undo that reached ORD's mailbox after ORD's last read of it", () => {
    // field test 68: a service manager's stop signalled ORD itself; BSE's undo at the stop was sent, ORD ended without serving it
    const bse = (lines: string[]) => [CSV_HEADER, '1000000000,w,BSE,supervisor,ORD,,0,"activate schema fastLoop() (activation #4, to ORD)"', ...lines, ''].join('\n');
    const ord = (lines: string[]) => [CSV_HEADER, '1000100000,w,ORD,scheduler,,,0,activate fastLoop (activation #4 from BSE)', ...lines, ''].join('\n');
    const story = (b: string[], o: string[]) => renderStory(parseTrace([{ name: 'BSE_1.csv', text: bse(b) }, { name: 'ORD_1.csv', text: ord(o) }]));

    it('tells ORD ended mid-run at its own last record, with the first sign another module gives that it is gone as the evidence', () => {
        // field test 69: ORD SIGKILLed at +2.69 s; the supervisor's undo at the stop, +5.09 s, found it ended
        const notSent = '6000000150,w,BSE,error,,,0,"STOP request to ORD: not sent, it has ended (it had already ended; the run is stopping)"';
        const killed = story([
            '3000000000,w,BSE,supervisor,,,0,rule drive.GO active',
            '6000000000,w,BSE,request_received,contract-launch,,0,KILL',
            '6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"',
            notSent,
        ], ['1700000000,w,ORD,ord_release,CAM,,0,schema=fastLoop cycle=1 release=1']);
        expect(killed).toContain('+0.700000s ORD  its records stop here (its last record), before the run\'s stop, with no exit record: it had ended mid-run ' +
            '(killed, crashed, or its code called exit(); the launcher\'s output says which); the first sign, at +5.000000s: BSE while the run stopped: ' +
            'STOP request to ORD: not sent, it has ended (it had already ended; the run is stopping)');
        expect(killed.filter((l) => l.includes('STOP request to ORD'))).toHaveLength(1);
        // ORD stopped by the launcher at the stop (its last record after the KILL): nothing added
        const atStop = story(['6000000000,w,BSE,request_received,contract-launch,,0,KILL', notSent],
            ['6000000050,w,ORD,request_received,contract-launch,,0,KILL']);
        expect(atStop).toContain('+5.000000s BSE  while the run stopped: STOP request to ORD: not sent, it has ended (it had already ended; the run is stopping)');
    });

    it("tells a module gone mid-run at its last record from ORD's stuck record or a request that found it not running, once", () => {
        // SRT SIGKILLed at +0.2 s; ORD's next START to it found its mailbox stale at +0.3 s, its stuck report came at +2.5 s
        const srt = [CSV_HEADER, '1100000000,w,SRT,module_started,,,0,pid=41 priority=40', '1200000000,w,SRT,run_finished,,,0,activation=1 cpu_ns=41000', ''].join('\n');
        const ordLog = (lines: string[]) => [CSV_HEADER, '1000000000,w,ORD,module_started,,,0,pid=40 priority=90', ...lines, ''].join('\n');
        const stuck = '3500000000,w,ORD,scheduler,,,0,stuck: SRT has not finished release #3 after 200 periods: it is no longer running (it crashed or was killed)';
        const byStuck = renderStory(parseTrace([{ name: 'SRT_1.csv', text: srt }, { name: 'ORD_1.csv', text: ordLog([stuck]) }]));
        expect(byStuck).toContain('+0.200000s SRT  its records stop here (its last record), while the others went on, with no exit record: it had ended mid-run ' +
            '(killed, crashed, or its code called exit(); the launcher\'s output says which); the first sign, at +2.500000s: ORD stuck: SRT has not finished release #3 ' +
            'after 200 periods: it is no longer running (it crashed or was killed)');
        const notRunning = '1300000000,w,ORD,error,,,0,START request to SRT: module not running (its mailbox is stale) (Connection refused)';
        const both = renderStory(parseTrace([{ name: 'SRT_1.csv', text: srt }, { name: 'ORD_1.csv', text: ordLog([notRunning, stuck]) }]));
        expect(both.filter((l) => l.includes('its records stop here'))).toEqual(['+0.200000s SRT  its records stop here (its last record), while the others went on, with no exit record: ' +
            'it had ended mid-run (killed, crashed, or its code called exit(); the launcher\'s output says which); the first sign, at +0.300000s: ORD error: START request to SRT: ' +
            'module not running (its mailbox is stale) (Connection refused)']);
        // the later sign told as it was
        expect(both).toContain('+2.500000s ORD  stuck: SRT has not finished release #3 after 200 periods: it is no longer running (it crashed or was killed)');
        // SRT's exit record read: no sign of its end mid-run
        const exited = [CSV_HEADER, '1100000000,w,SRT,module_started,,,0,pid=41 priority=40', '1200000000,w,SRT,module_exit,,,0,status=0 records=2', ''].join('\n');
        expect(renderStory(parseTrace([{ name: 'SRT_1.csv', text: exited }, { name: 'ORD_1.csv', text: ordLog([notRunning]) }])).join('\n')).not.toContain('its records stop here');
    });

    it('tells with ORD\'s end the undo it never served, as of a run that was stopping', () => {
        const lines = story([
            '6000000000,w,BSE,request_received,contract-launch,,0,KILL',
            '6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"',
            '6000000200,w,BSE,supervisor,,,0,function drive stopped',
        ], [
            '6000000050,w,ORD,request_received,contract-launch,,0,KILL',
            '6000000300,w,ORD,module_exit,,,0,status=0 records=3',
        ]);
        expect(lines).toContain('+5.000000s ORD  exited (status=0 records=3); while the run stopped: ORD ended before it served BSE\'s undo: deactivate schema fastLoop (activation #4): ' +
            'fastLoop stayed active to its end (the undo reached ORD\'s mailbox after ORD\'s last read of it)');
    });

    it('says nothing more when ORD served the undo, or when the undo was not sent (its own record tells it)', () => {
        const served = story(['6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"'], [
            '6000000200,w,ORD,scheduler,,,0,deactivate fastLoop (activation #4 from BSE)',
            '6000000300,w,ORD,module_exit,,,0,status=0 records=3',
        ]);
        expect(served).toContain('+5.000000s ORD  exited (status=0 records=3)');
        const notSent = story([
            '6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"',
            '6000000150,w,BSE,error,,,0,"STOP request to ORD: not sent, it has ended (it had already ended; the run is stopping)"',
        ], ['6000000300,w,ORD,module_exit,,,0,status=0 records=3']);
        expect(notSent).toContain('+5.000000s ORD  exited (status=0 records=3)');
        expect(notSent).toContain('+5.000000s BSE  while the run stopped: STOP request to ORD: not sent, it has ended (it had already ended; the run is stopping)');
        // ORD crashed during the run with the undo in its mailbox: told without "while the run stopped"
        const crashed = story(['6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"'],
            ['6000000300,w,ORD,module_exit,,,0,status=3 records=3']);
        expect(crashed.find((l) => l.includes('ORD  exited'))).toMatch(/records=3\); ORD ended before it served BSE's undo: deactivate schema fastLoop \(activation #4\)/);
    });

    // a real run (tutorial, sandbox none): ORD stopped (SIGSTOP) during schemaCommande1's activation, so the
    // undo at the run's end reached its mailbox; the launcher then killed it (SIGTERM, SIGKILL): no exit record
    const killedOrd = [
        '6000000000,w,BSE,request_received,contract-launch,,0,KILL',
        '6000000100,w,BSE,supervisor,ORD,,0,"undo: deactivate schema fastLoop (activation #4, to ORD)"',
        '6000000200,w,BSE,supervisor,,,0,function drive stopped',
    ];
    const ordKilled = ['3000000000,w,ORD,ord_complete,,,0,schema=fastLoop cycle=1 tick_ns=3000000000 response_ns=411719'];

    it('tells at the records\' end an undo ORD\'s log never answered when ORD wrote no exit record (killed), once its supervisor\'s exit shows the run ended', () => {
        const lines = story([...killedOrd, '6000000300,w,BSE,module_exit,,,0,status=0 records=5'], ordKilled);
        const told = lines.filter((l) => l.includes('no answer to'));
        expect(told).toEqual(['+5.000000s ORD  while the run stopped: ORD\'s log ends with no exit record (it was killed or terminated: the launcher\'s output says which) ' +
            'and no answer to BSE\'s undo: deactivate schema fastLoop (activation #4): whether ORD served it before its end is unknown (a module killed loses ' +
            'the records it had not written, unless contract-launch wrote them from its log buffers), fastLoop may have stayed active to its end']);
        // told after the records, before the schema figures
        expect(lines.indexOf(told[0]!)).toBe(lines.findIndex((l) => l.startsWith('schema fastLoop')) - 1);
    });

    it('does not say an undo unserved while the run may still go on (its supervisor not ended after it: it may be in flight)', () => {
        const inFlight = story(killedOrd, ordKilled);
        expect(inFlight.filter((l) => l.includes('no answer to') || l.includes('before it served'))).toEqual([]);
        // another module's end after it (a crash while the run goes on) is not the sender's: the run may go on
        const otherEnded = renderStory(parseTrace([{ name: 'BSE_1.csv', text: bse(killedOrd) }, { name: 'ORD_1.csv', text: ord(ordKilled) },
            { name: 'MSC_1.csv', text: [CSV_HEADER, '6000000300,w,MSC,module_crashed,,,0,signal 11 (SIGSEGV) records=9', ''].join('\n') }]));
        expect(otherEnded.filter((l) => l.includes('no answer to'))).toEqual([]);
        // nor when ORD served it, ORD's log ending without its exit record all the same
        const served = story([...killedOrd, '6000000300,w,BSE,module_exit,,,0,status=0 records=5'],
            [...ordKilled, '6000000150,w,ORD,scheduler,,,0,deactivate fastLoop (activation #4 from BSE)']);
        expect(served.filter((l) => l.includes('no answer to'))).toEqual([]);
        // a StoryTeller fed record by record (a live trace): its lines say nothing of it before endLines
        const teller = new StoryTeller();
        const said = parseTrace([{ name: 'BSE_1.csv', text: bse([...killedOrd, '6000000300,w,BSE,module_exit,,,0,status=0 records=5']) }, { name: 'ORD_1.csv', text: ord(ordKilled) }])
            .map((r) => teller.tell(r)).filter((l): l is string => l !== undefined);
        expect(said.filter((l) => l.includes('no answer to'))).toEqual([]);
        expect(teller.endLines()).toHaveLength(1);
    });
});

describe("a supervisor's requests kept for a full mailbox", () => {
    it('reads the request kept as a word, and the counts and the time of their end as numbers', () => {
        expect((parseRecordLine('SUP.csv', 2, '5100000000,w,SUP,requests_kept,VEL,,0,request=STOP') as KnownRecord).fields).toEqual({ request: 'STOP' });
        expect((parseRecordLine('SUP.csv', 3, '7100000000,w,SUP,requests_kept_end,VEL,,0,sent=4 failed=1 replaced=73 kept_ns=2000000000') as KnownRecord).fields)
            .toEqual({ sent: 4, failed: 1, replaced: 73, kept_ns: 2000000000 });
    });

    it('tells when a receiver\'s full mailbox made it keep requests, and what came of them when that ended (the counts that are 0 left out)', () => {
        const text = [CSV_HEADER,
            '5100000000,w,SUP,requests_kept,VEL,,0,request=STOP',
            '5200000000,w,SUP,setparam_sent,VEL,0,8,in place of 73 earlier values for its port',
            '7100000000,w,SUP,error,,,0,STOP request to VEL: mailbox full',
            '7100000000,w,SUP,requests_kept_end,VEL,,0,sent=4 failed=1 replaced=73 kept_ns=2000000000',
            '8000000000,w,SUP,requests_kept,ARM,,0,request=SETPARAM',
            '8012500000,w,SUP,requests_kept_end,ARM,,0,sent=1 failed=0 replaced=1 kept_ns=12500000',
            '9000000000,w,SUP,requests_kept,GRP,,0,',
            '9000000000,w,SUP,requests_kept_end,GRP,,0,sent=0 failed=0 replaced=0 kept_ns=soon',
            '9100000000,w,SUP,module_exit,,,0,status=0 records=9',
            '',
        ].join('\n');
        expect(renderStory(parseTrace([{ name: 'SUP_1.csv', text }])).slice(0, -1)).toEqual([
            "+0.000000s SUP  VEL's mailbox is full: its STOP request is kept (tried again every 5 ms, for up to 2 s)",
            '+2.000000s SUP  error: STOP request to VEL: mailbox full',
            "+2.000000s SUP  the requests kept for VEL's full mailbox ended after 2 s: 4 sent, 1 failed, 73 values replaced by later ones",
            "+2.900000s SUP  ARM's mailbox is full: its SETPARAM request is kept (tried again every 5 ms, for up to 2 s)",
            "+2.912500s SUP  the requests kept for ARM's full mailbox ended after 12.5 ms: 1 sent, 1 value replaced by a later one",
            // a record without its words (a forged log): told without them
            "+3.900000s SUP  GRP's mailbox is full: its request is kept (tried again every 5 ms, for up to 2 s)",
            "+3.900000s SUP  the requests kept for GRP's full mailbox ended",
            '+4.000000s SUP  exited (status=0 records=9)',
        ]);
    });
});

describe('ORD\'s answer to the undo of an activation it refused', () => {
    it('tells ORD ignoring it after the supervisor\'s undo (what ORD does next), not its other ignored line', () => {
        // the field test's manipulator run (+0.424 s): AGAIN asks ORD for armLoop while ARMON's activation #4 is active
        const recordOf = (module: string) => (ns: number, event: string, peer: string, detail: string) => `${ns},w,${module},${event},${peer},,0,${detail}`;
        const mnp = recordOf('MNP');
        const ord = recordOf('ORD');
        const story = renderStory(parseTrace([
            { name: 'MNP_6-Dec-2026-23h50m00s.csv', text: [CSV_HEADER,
                mnp(1000, 'supervisor', 'ORD', '"activate schema armLoop(mode = OPEN) (activation #4, to ORD)"'),
                mnp(5000, 'sup_rule', '', 'manipulate.AGAIN active cause=started(GRAB)'),
                mnp(5001, 'supervisor', 'ORD', '"activate schema armLoop(mode = CLOSED) (activation #5, to ORD)"'),
                mnp(5200, 'sup_rule', '', 'manipulate.AGAIN inactive cause=ORD:1 value="armLoop"'),
                mnp(5201, 'supervisor', 'ORD', '"undo: deactivate schema armLoop (activation #5, to ORD)"'), ''].join('\n') },
            { name: 'ORD_6-Dec-2026-23h50m00s.csv', text: [CSV_HEADER,
                ord(1100, 'scheduler', '', 'activate armLoop (activation #4 from MNP)'),
                ord(5100, 'scheduler', '', 'conflict: armLoop shares a module with active armLoop (ORD:1)'),
                ord(5300, 'request_received', 'MNP', 'STOP'),
                ord(5301, 'scheduler', '', 'ignored: deactivate armLoop (not this activation)'),
                // expected when a schema is deactivated while its module runs: not told
                ord(6000, 'scheduler', '', 'ignored: ARM finished outside a cycle'), ''].join('\n') },
        ])).slice(0, -1);
        expect(story.slice(-3)).toEqual([
            '+0.000004s MNP  rule manipulate.AGAIN inactive <- ORD:1 = "armLoop"',
            '+0.000004s MNP  undo: deactivate schema armLoop (activation #5, to ORD)',
            '+0.000004s ORD  ignored: deactivate armLoop (not this activation)',
        ]);
    });
});

describe('a rule cause in the words of the model', () => {
    it('writes times as Cactal time literals, an event as its port and value, and says what stop means', () => {
        expect(['elapsed=1000000ns', 'elapsed=250000ns', 'elapsed=1500000000ns', 'elapsed=2000000000ns', 'elapsed=1234ns', 'duration(PAUSE)=100000000ns'].map(readableCause))
            .toEqual(['elapsed=1ms', 'elapsed=250us', 'elapsed=1500ms', 'elapsed=2s', 'elapsed=1234ns', 'duration(PAUSE)=100ms']);
        expect(readableCause('MAA:2 value="disconnected"')).toBe('MAA:2 = "disconnected"');
        expect(readableCause('ORD:0 value="velocityLoop"')).toBe('ORD:0 = "velocityLoop"');
        expect(readableCause('started(FIRST)')).toBe('started(FIRST)');
        expect(readableCause('endof(AUTO)')).toBe('endof(AUTO)');
        expect(readableCause('stop')).toBe('its function stopped');
        // what it does not know stays as logged
        expect(readableCause('elapsed=soon')).toBe('elapsed=soon');
    });
});
