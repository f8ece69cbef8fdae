/** A trace file (JSON lines) read back as a run's logs, through the CSV reader's checks (jsonl.ts). */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { CSV_HEADER, TRACE_KINDS, isRule, isUnknown, parseLogFile, parseTrace, recordOfJsonLine, renderStory, traceFileToLogs, traceFileToLogsSteps, type TraceRecord } from './index.js';

/** A run's logs: every kind of the table (its example line, at its own time), in two modules' logs, plus quoting. */
function sampleLogs() {
    const lines = TRACE_KINDS.map((k, i) => {
        const f = k.example.split(',');
        f[0] = String(1_000_000 + i * 1000);
        return f.join(',');
    });
    const quoted = `2000000,2026-12-03T10:00:00.000001Z,MIS,sup_rule,,,0,"mission.AUTO active cause=TEL:1 value=""auto, now"""`;
    const byModule = new Map<string, string[]>();
    for (const l of [...lines, quoted]) {
        const module = l.split(',')[2]!;
        byModule.set(module, [...(byModule.get(module) ?? []), l]);
    }
    return [...byModule].map(([m, l]) => ({ name: `${m}_run.csv`, text: `${CSV_HEADER}\n${l.join('\n')}\n` }));
}

const jsonl = (records: TraceRecord[]) => records.map((r) => JSON.stringify(r)).join('\n') + '\n';

describe('trace files (JSON lines)', () => {
    it('read back as logs, give the records and the story of the logs they were written from', () => {
        const records = parseTrace(sampleLogs());
        expect(records.filter((r) => r.kind === 'unknown')).toEqual([]);
        const back = traceFileToLogs('run.jsonl', jsonl(records));
        expect(back.problems).toEqual([]);
        expect(back.skipped).toBe(0);
        expect(back.files.every((f) => /^[A-Za-z_]\w*_run\.csv$/.test(f.name))).toBe(true);
        expect(parseTrace(back.files)).toEqual(records);
        expect(renderStory(parseTrace(back.files))).toEqual(renderStory(records));
    });

    it('say the file\'s order of the records (the order contract trace tells them in): records of one time keep it, whatever their modules\' names', () => {
        // a simulation's step: every record at one time, its causes first (ORD's conflict before the rule it ends)
        const text = [
            '{"kind":"sim_start","monoNs":"0","module":"SIM","detail":"simulation start: s.scenario"}',
            '{"kind":"supervisor","monoNs":"313000000","module":"MNP","peer":"ORD","detail":"activate schema armLoop() (activation #5, to ORD)"}',
            '{"kind":"scheduler","monoNs":"313000000","module":"ORD","peer":"","detail":"conflict: armLoop shares a module with active armLoop (ORD:1)"}',
            '{"kind":"sup_rule","monoNs":"313000000","module":"MNP","peer":"","detail":"manipulate.AGAIN inactive cause=ORD:1 value=\\"armLoop\\""}',
            'not JSON',
            '{"kind":"scheduler","monoNs":"313000000","module":"ORD","peer":"","detail":"ignored: deactivate armLoop (not this activation)"}',
            '',
        ].join('\n');
        const back = traceFileToLogs('sim.jsonl', text);
        expect(back.files.map((f) => f.name)).toEqual(['MNP_sim.csv', 'ORD_sim.csv']);
        expect([...back.order]).toEqual([0, 1, 0, 1]);
        // the file's records, in its order, from the logs and that order
        const next = back.files.map(() => 0);
        const lines = back.files.map((f) => f.text.split('\n').slice(1));
        expect([...back.order].map((f) => lines[f]![next[f]!++]!.split(',')[3])).toEqual(['supervisor', 'scheduler', 'sup_rule', 'scheduler']);
    });

    it('a record cut at its log\'s end (`cut`) reads back as that log\'s last line, again without its line end', () => {
        const log = `${CSV_HEADER}\n1000,2026-12-03T10:00:00.000001Z,MSC,request_received,ORD,,0,START\n2000,2026-12-03T10:00:00.000002Z,MSC,request_received,ORD,,0,STA`;
        const other = `${CSV_HEADER}\n1500,2026-12-03T10:00:00.000001Z,MSA,request_received,ORD,,0,START\n`;
        const records = parseTrace([{ name: 'MSC_1.csv', text: log }, { name: 'MSA_1.csv', text: other }]);
        expect(records.filter((r) => (r as { cut?: true }).cut)).toHaveLength(1);
        const back = traceFileToLogs('run.jsonl', jsonl(records));
        expect(back.files.find((f) => f.name.startsWith('MSC_'))!.text.endsWith(',STA')).toBe(true);
        expect(back.files.find((f) => f.name.startsWith('MSA_'))!.text.endsWith('START\n')).toBe(true);
        expect(parseTrace(back.files)).toEqual(records);
    });

    it('a simulation\'s sim_start and records the writer kept as unknown are skipped as logs, counted; read one by one, the unknown ones come back', () => {
        const records = parseTrace(sampleLogs());
        const text = JSON.stringify({ kind: 'sim_start', monoNs: '0', wallTime: '', module: 'SIM', peer: '', port: null, size: 0, detail: 'simulation start', fields: {} }) + '\n' +
            JSON.stringify({ kind: 'unknown', file: 'X.csv', line: 3, reason: 'bad', text: 'x' }) + '\n' + jsonl(records);
        const back = traceFileToLogs('sim.jsonl', text);
        // the carried line is named, as `contract trace FILE.jsonl` warns about it
        expect([back.skipped, back.problems]).toEqual([1, ['line 2: a line of X.csv (line 3) that is no record: bad']]);
        expect(parseTrace(back.files)).toEqual(records);
        // one record at a time (contract trace FILE.jsonl), the unknown record comes back as it was, bounded
        expect(recordOfJsonLine('t.jsonl', 2, text.split('\n')[1]!)).toEqual({ kind: 'unknown', file: 'X.csv', line: 3, reason: 'bad', text: 'x' });
        expect(recordOfJsonLine('t.jsonl', 2, JSON.stringify({ kind: 'unknown', file: 'F'.repeat(500), line: -4, reason: 7 }))).toEqual({ kind: 'unknown', file: 'F'.repeat(200), line: 0, reason: '', text: '' });
        expect(recordOfJsonLine('t.jsonl', 1, text.split('\n')[0]!)).toMatchObject({ kind: 'sim_start', module: 'SIM', monoNs: '0', detail: 'simulation start' });
        expect(back.simulation).toBe('');
        // two simulations in one file (two scenarios): each from time 0; the first is kept, the second said left out
        const two = traceFileToLogs('sim.jsonl', text.replace('simulation start', 'simulation start: a.scenario') + text.replace('simulation start', 'simulation start: b.scenario'));
        expect(two.simulation).toBe('a.scenario');
        expect(two.problems).toEqual(['line 2: a line of X.csv (line 3) that is no record: bad', `the file's other simulations, from line ${text.split('\n').length}, left out: one is shown at a time`]);
        expect(parseTrace(two.files)).toEqual(records);
    });

    it('hostile lines are named, never trusted: the derived fields come from the columns again', () => {
        const rule = parseTrace(sampleLogs()).find(isRule)!;
        const lying = { ...rule, causeEvent: { kind: 'stop' }, active: false, fields: { injected: 1 } };
        const lines = [
            JSON.stringify(lying),
            'not json',
            '[1,2]',
            JSON.stringify({ kind: 'sup_rule', monoNs: 12, module: 'MIS', detail: 'x' }),
            JSON.stringify({ ...rule, module: '../../etc' }),
            JSON.stringify({ ...rule, monoNs: '1,2' }),
            JSON.stringify({ ...rule, port: -1 }),
            JSON.stringify({ ...rule, kind: 'no such kind' }),
            'x'.repeat(20_000),
        ];
        const back = traceFileToLogs('../../evil name.jsonl', lines.join('\n') + '\n');
        // every bad line is named, with the CSV reader's own reason for those it refuses (the Monitor
        // names what `contract trace FILE.jsonl` warns about, and counts as many)
        expect(back.problems).toEqual(['line 2: not JSON', 'line 3: not a JSON object', 'line 4: kind, monoNs, module and detail must be strings', 'line 5: bad module name',
            'line 6: mono_ns is not a number', 'line 7: bad port or size', "line 8: unknown event 'no such kind'", 'line 9: longer than 16384 characters']);
        expect(back.unreadable).toBe(8);
        const streamed = lines.map((l, i) => recordOfJsonLine('t.jsonl', i + 1, l)).filter((r) => r && isUnknown(r));
        expect(streamed).toHaveLength(back.unreadable);
        // the log names are plain: no path from the file's name
        expect(back.files.map((f) => f.name)).toEqual([`${rule.module}_evil_name.csv`]);
        const read = parseTrace(back.files);
        // the lying line is the rule as its columns say; the others were named above, not carried into the logs
        expect(read).toEqual([rule]);
        expect(recordOfJsonLine('t.jsonl', 2, 'not json')).toMatchObject({ kind: 'unknown', file: 't.jsonl', line: 2, reason: 'not JSON' });
        expect(recordOfJsonLine('t.jsonl', 3, '  ')).toBeUndefined();
    });

    it('a module\'s own record (ContractLog with an event name of its own) comes back with its name', () => {
        const text = [CSV_HEADER, '2500,w,MAA,gripper_closed,,,0,force=12.5 N', '2600,w,MAA,user,,,0,literally user', ''].join('\n');
        const records = parseLogFile({ name: 'MAA_1.csv', text });
        expect(records).toMatchObject([
            { kind: 'user', module: 'MAA', detail: 'force=12.5 N', fields: { event: 'gripper_closed' } },
            { kind: 'user', detail: 'literally user', fields: { event: 'user' } },
        ]);
        const back = recordOfJsonLine('t.jsonl', 1, JSON.stringify(records[0]));
        expect(back).toEqual(records[0]);
        // `contract trace` tells them (EVENT: DETAIL), none is an unreadable line
        const story = renderStory(parseTrace([{ name: 'MAA_1.csv', text }]));
        expect(story.slice(0, 2)).toEqual(['+0.000000s MAA  gripper_closed: force=12.5 N', '+0.000000s MAA  user: literally user']);
        expect(story.at(-1)).toContain('0 unreadable lines');
    });

    it('any text: no exception, every line a record, a problem or skipped', () => {
        fc.assert(fc.property(fc.array(fc.oneof(fc.string(), fc.json()), { maxLength: 30 }), (lines) => {
            const text = lines.join('\n');
            const back = traceFileToLogs('t.jsonl', text, 1000);
            const records = back.files.reduce((n, f) => n + f.text.split('\n').length - 2, 0);
            const nonEmpty = text.split('\n').filter((l) => l.replace(/\r$/, '').trim() !== '').length;
            expect(records + back.problems.length + back.skipped).toBe(nonEmpty);
            expect(back.unreadable).toBe(back.problems.length);
        }));
    });

    it('in steps (the IDE draws between them): the same logs; every line that is no record counted, past the problems named', () => {
        const good = jsonl(Array.from({ length: 1200 }, (_, i) => ({ kind: 'user', monoNs: String(1000 + i), module: i % 2 ? 'MAA' : 'MSC', detail: `n=${i}`, fields: { event: 'tick' } })) as unknown as TraceRecord[]).split('\n').filter(Boolean);
        const lines = good.flatMap((l, i) => (i % 40 === 0 ? [l, 'not json {'] : [l]));
        const text = lines.join('\n');
        const steps = traceFileToLogsSteps('t.jsonl', text, 100);
        let yields = 0;
        let step = steps.next();
        for (; !step.done; step = steps.next()) yields++;
        expect(yields).toBe(Math.floor(lines.length / 100) + 2); // and once after each log (MAA's, MSC's) is made
        const whole = traceFileToLogs('t.jsonl', text);
        expect(step.value).toEqual(whole);
        expect(whole.unreadable).toBe(30);
        expect(whole.problems).toHaveLength(21); // 20 named, then `10 more line(s) that are no record`
        expect(whole.problems.at(-1)).toBe('10 more line(s) that are no record');
    });
});
