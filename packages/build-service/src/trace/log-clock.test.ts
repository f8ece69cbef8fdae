import { describe, expect, it } from 'vitest';
import { CSV_HEADER, parseLogFile, parseTrace } from './parse.js';
import { StoryTeller, renderStory } from './story.js';
import { traceFileToLogs } from './jsonl.js';
import { LogClock, monoBeyondInt64, wallTimeMs } from './log-clock.js';
import { isUnknown, type KnownRecord } from './records.js';

const W = (s: number) => `2026-11-24T18:30:${String(15 + s).padStart(2, '0')}.123456Z`;
const ORD = 'ORD_24-Nov-2026-18h30m15s.csv';
const MSA = 'MSA_24-Nov-2026-18h30m15s.csv';
const BASE = 40_000_000_000_000;
const at = (ms: number) => BASE + ms * 1_000_000;

/** A tutorial-like run: ORD completes cycle 0 of schemaCommande1 with no miss. */
function runLogs(msaExtra: string[] = [], ordExtra: string[] = []) {
    return [
        { name: ORD, text: [CSV_HEADER,
            `${at(0)},${W(0)},ORD,module_started,,,0,pid=1 priority=90`,
            `${at(10)},${W(0)},ORD,scheduler,,,0,activate schemaCommande1 (activation #1 from SUP)`,
            `${at(11)},${W(0)},ORD,ord_release,MSA,,0,schema=schemaCommande1 cycle=0 tick_ns=${at(11)} release_ns=${at(11)} release=1`,
            `${at(12)},${W(0)},ORD,ord_complete,,,0,schema=schemaCommande1 cycle=0 tick_ns=${at(11)} response_ns=1000000`,
            ...ordExtra, ''].join('\n') },
        { name: MSA, text: [CSV_HEADER,
            `${at(1)},${W(0)},MSA,module_started,,,0,pid=2 priority=84`,
            `${at(11)},${W(0)},MSA,run_started,ORD,,0,activation=1`,
            `${at(12)},${W(0)},MSA,run_finished,,,0,activation=1 cpu_ns=41000 ACK_FINISHED`,
            ...msaExtra, ''].join('\n') },
    ];
}

const figures = (logs: ReturnType<typeof runLogs>) => {
    const teller = new StoryTeller();
    for (const r of parseTrace(logs)) teller.tell(r);
    return teller.schemaFigures();
};

describe("A: an engine's record kinds are taken from that engine only", () => {
    it("a module's ord_deadline_miss (ContractLog) is its own user record, marked, never ORD's miss", () => {
        const forged = `${at(20)},${W(0)},MSA,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=99 tick_ns=1`;
        const records = parseTrace(runLogs([forged]));
        const r = records.find((x) => !isUnknown(x) && (x as KnownRecord).detail.includes('cycle=99')) as KnownRecord;
        expect(r).toMatchObject({ kind: 'user', module: 'MSA', fields: { event: 'ord_deadline_miss', posingAs: 'ORD' } });
        expect(figures(runLogs([forged]))).toEqual(figures(runLogs()));
        expect(figures(runLogs([forged]))[0]).toMatchObject({ schema: 'schemaCommande1', deadlineMisses: 0 });
        const story = renderStory(records).join('\n');
        expect(story).toContain("MSA's own record under the name of ORD's records: not taken for ORD's");
        expect(story).not.toMatch(/1 deadline miss/);
    });

    it("a module's scheduler line and ORD's supervisor records are no engine facts either", () => {
        const recs = parseTrace(runLogs([`${at(21)},${W(0)},MSA,scheduler,,,0,deadline miss: schemaCommande1 cycle 7 (ORD:0)`], [`${at(13)},${W(0)},ORD,sup_rule,,,0,f.r active cause=elapsed=5ns`]));
        const users = recs.filter((r) => r.kind === 'user') as KnownRecord[];
        expect(users.map((u) => [u.module, u.fields['event'], u.fields['posingAs']])).toEqual([['ORD', 'sup_rule', 'a supervisor'], ['MSA', 'scheduler', 'ORD']]);
        expect(figures(runLogs([`${at(21)},${W(0)},MSA,scheduler,,,0,deadline miss: schemaCommande1 cycle 7 (ORD:0)`]))[0]!.deadlineMisses).toBe(0);
    });
});

describe('B: a time the runtime did not write is no time of the run', () => {
    it('a line appended with an early time, or one past 64 bits, is an unreadable line, said why; the run keeps its time base', () => {
        const early = `1,${W(0)},MSA,user,,,0,EARLY`;
        const late = `18000000000000000000,${W(0)},MSA,user,,,0,LATE`;
        const records = parseTrace(runLogs([early, late]));
        const unknown = records.filter(isUnknown);
        expect(unknown.map((u) => u.reason)).toEqual([
            expect.stringMatching(/^mono_ns goes back in its log, 40000\.0\d+ s before the record before it/),
            expect.stringMatching(/^mono_ns is past a 64-bit time/),
        ]);
        const known = records.filter((r) => !isUnknown(r)) as KnownRecord[];
        expect(known[0]!.monoNs).toBe(String(at(0)));
        const story = renderStory(records);
        expect(story[0]).toMatch(/^\+0\.000000s ORD/);
        expect(story.join('\n')).not.toMatch(/\+18000000000|\+400\d\d\./);
    });

    it("a jump forward that the wall time does not make is unreadable; a genuine pause (both move) is not", () => {
        const jump = `9000000000000000000,${W(0)},MSA,user,,,0,FAR`;
        const recs = parseLogFile({ name: MSA, text: [CSV_HEADER, `${at(1)},${W(0)},MSA,module_started,,,0,pid=2 priority=84`, jump, `${at(3000)},${W(3)},MSA,user,,,0,after a real 3 s pause`, ''].join('\n') });
        expect(recs.map((r) => (isUnknown(r) ? r.reason.slice(0, 40) : r.kind))).toEqual(['module_started', 'mono_ns jumps 8999959999.999 s past the ', 'user']);
    });

    it("a machine suspended mid-run (the wall time moves on, CLOCK_MONOTONIC does not) is no forged time; a wall clock set back during a jump still is", () => {
        const lines = [
            `${at(1)},${W(0)},MSA,module_started,,,0,pid=2 priority=84`,
            // 3 s of run between the two records, and 10 min of sleep the monotonic clock did not count
            `${at(3001)},2026-11-24T18:40:18.123456Z,MSA,user,,,0,after the machine woke up`,
            `${at(6001)},2026-11-24T18:38:21.123456Z,MSA,user,,,0,wall clock set 2 min back`,
        ];
        const recs = parseLogFile({ name: MSA, text: [CSV_HEADER, ...lines, ''].join('\n') });
        expect(recs.map((r) => (isUnknown(r) ? r.reason.slice(0, 60) : r.kind))).toEqual(['module_started', 'user', 'mono_ns jumps 3.000 s past the record before it in its log w']);
    });

    it("an out-of-order line of ORD's log does not become the run's time 0", () => {
        const records = parseTrace(runLogs([], [`900,${W(0)},ORD,scheduler,,,0,activate schemaCommande1 (activation #2 from SUP)`]));
        expect(records.filter(isUnknown)).toHaveLength(1);
        expect((records[0] as KnownRecord).monoNs).toBe(String(at(0)));
    });

    it('the checks themselves', () => {
        expect(monoBeyondInt64('9223372036854775807')).toBe(false);
        expect(monoBeyondInt64('9223372036854775808')).toBe(true);
        expect(monoBeyondInt64('00000000000000000001')).toBe(false);
        expect(monoBeyondInt64('18000000000000000000')).toBe(true);
        expect(wallTimeMs('2026-11-24T18:30:15.123456Z')).toBeCloseTo(Date.UTC(2026, 10, 24, 18, 30, 15) + 123.456, 3);
        expect(wallTimeMs('w')).toBeNaN();
        // two threads of a module logging at once: a step back under 1 ms is no forgery
        const c = new LogClock();
        expect(c.check(5_000_000, '')).toBeUndefined();
        expect(c.check(4_500_000, '')).toBeUndefined();
        expect(c.check(3_000_000, '')).toMatch(/goes back/);
    });

    it('a trace file gets the same checks, per module (its lines are named as problems)', () => {
        const records = parseTrace(runLogs([`1,${W(0)},MSA,user,,,0,EARLY`]));
        const text = records.map((r) => JSON.stringify(r)).join('\n') + '\n';
        // the writer kept the early line as an unknown record: carried, named
        const back = traceFileToLogs('run.jsonl', text);
        expect(back.skipped).toBe(1);
        expect(back.problems[0]).toMatch(/goes back in its log/);
        // a hand-made trace file with the forged line as a record: refused by the same check
        const forged = text.replace(/\{"kind":"unknown"[^\n]*\}/, JSON.stringify({ kind: 'user', monoNs: '1', wallTime: W(0), module: 'MSA', peer: '', port: null, size: 0, detail: 'EARLY', fields: { event: 'user' } }));
        const back2 = traceFileToLogs('run.jsonl', forged);
        expect(back2.unreadable).toBe(1);
        expect(back2.problems[0]).toMatch(/^line \d+: mono_ns goes back in its log/);
    });
});
