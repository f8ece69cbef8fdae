/** The text report writes every time of a scenario in one unit, so that its time column reads down. */
import { describe, expect, it } from 'vitest';
import { jsonReport, junitReport, reportTimeFormat, textReport, type ScenarioResult } from '../src/index.js';

describe('the text report\'s times', () => {
    it('picks the coarsest unit that writes each time as a whole number', () => {
        expect([0, 3e9, 6e9].map(reportTimeFormat([0, 3e9, 6e9]))).toEqual(['0', '3s', '6s']);
        expect([2.9e9, 3e9, 3.1e9].map(reportTimeFormat([2.9e9, 3e9, 3.1e9]))).toEqual(['2900ms', '3000ms', '3100ms']);
        expect([1e6, 1.5e3].map(reportTimeFormat([1e6, 1.5e3]))).toEqual(['1000000ns', '1500ns']);
        expect([1e6, 2e3].map(reportTimeFormat([1e6, 2e3]))).toEqual(['1000us', '2us']);
        // a time that is not a step's gets decimals in the steps' unit
        expect([300_500_000, 1_000, 1_200_000_000].map(reportTimeFormat([0, 1.2e9]))).toEqual(['300.5ms', '0.001ms', '1200ms']);
    });

    it('a scenario with 3s and 3100ms shows both in ms', () => {
        const step = (timeNs: number, source: string) => ({
            line: 1, source, timeNs, kind: 'event' as const, ok: true,
            record: { line: 1, timeNs, ok: true, verb: 'event', delivered: 1, rules: [], actions: [], log: [] },
        });
        const result = {
            file: 'x.scenario', passed: true, steps: [step(3e9, 'MAA:2 "a"'), step(3.1e9, 'MAA:2 "b"')], failures: [],
            eventsProcessed: 2, endNs: 4e9, ms: 1, harnessMs: 1,
        } as unknown as ScenarioResult;
        const text = textReport([result]);
        expect(text).toContain('  3000ms  MAA:2 "a"');
        expect(text).toContain('  3100ms  MAA:2 "b"');
        expect(text).toContain('4000ms simulated');
    });

    it('what happened before a step (a timer, a deadline miss) is above its line, in the engines\' order; an expectation comes after what happened at its time', () => {
        const rule = (timeNs: number, seq: number, r: string, active: boolean, cause: string) => ({ timeNs, seq, supervisor: 'CEL', function: 'cell', rule: r, active, cause });
        const step = (timeNs: number, kind: 'event' | 'expect', source: string, rules: ReturnType<typeof rule>[], log: Array<{ timeNs: number; seq: number; who: string; line: string }> = []) => ({
            line: 1, source, timeNs, kind, ok: true,
            record: { line: 1, timeNs, ok: true, verb: kind, rules, actions: [], log },
        });
        const result = {
            file: 'cell.scenario', passed: true, failures: [], eventsProcessed: 2, endNs: 1e9, ms: 1, harnessMs: 1,
            steps: [
                step(100e6, 'event', 't=100ms SCN:0 0.3', [rule(100e6, 3, 'SLOW', true, 'SCN:0 value=0.3')]),
                // listed rules first, log after: the log's deadline miss (seq 7) came first
                step(140e6, 'expect', 'expect rule CEL.cell.RECOVER active', [rule(116e6, 8, 'PICK', false, 'ORD:0 value="pickLoop"'), rule(140e6, 10, 'RECOVER', true, 'endof(PICK)')],
                    [{ timeNs: 116e6, seq: 7, who: 'ORD', line: 'deadline miss: pickLoop (ORD:0)' }]),
            ],
        } as unknown as ScenarioResult;
        const lines = textReport([result], { verbose: true }).split('\n').map((l) => l.trim().replace(/\s+/g, ' '));
        const at = (text: string) => lines.findIndex((l) => l.includes(text));
        expect(at('100ms t=100ms SCN:0 0.3')).toBeLessThan(at('+ CEL.cell.SLOW active'));
        expect(at('116ms ORD| deadline miss: pickLoop (ORD:0)')).toBeLessThan(at('116ms - CEL.cell.PICK inactive <- ORD:0 = "pickLoop"'));
        expect(at('- CEL.cell.PICK inactive')).toBeLessThan(at('140ms + CEL.cell.RECOVER active'));
        expect(at('+ CEL.cell.RECOVER active')).toBeLessThan(at('ok 140ms expect rule CEL.cell.RECOVER active'));
        const times = lines.map((l) => /^(?:ok )?(\d+)ms /.exec(l)?.[1]).filter((t): t is string => t !== undefined).map(Number);
        expect(times).toEqual([...times].sort((a, b) => a - b));
    });

    it('--verbose tells a deadline miss as contract trace does: its cycle and the modules not finished or the one a held cycle waits for, from ORD\'s records and lines over the steps', () => {
        const rec = (timeNs: number, seq: number, kind: string, peer: string, detail: string) => ({ timeNs, seq, module: 'ORD', kind, peer, detail });
        const step = (timeNs: number, source: string, records: ReturnType<typeof rec>[], log: Array<{ timeNs: number; seq: number; who: string; line: string }> = []) => ({
            line: 1, source, timeNs, kind: 'event' as const, ok: true,
            record: { line: 1, timeNs, ok: true, verb: 'event', delivered: 1, rules: [], actions: [], log, records },
        });
        const result = {
            file: 'line.scenario', passed: true, failures: [], eventsProcessed: 2, endNs: 1e9, ms: 1, harnessMs: 1,
            steps: [
                // cycle 3 released in the first step: A finishes, B does not
                step(30e6, 't=30ms X:0 1', [
                    rec(30e6, 1, 'ord_release', 'A', 'schema=loop cycle=3 tick_ns=30000000 release_ns=30000000 release=7'),
                    rec(30e6, 2, 'ord_release', 'B', 'schema=loop cycle=3 tick_ns=30000000 release_ns=30000000 release=8'),
                    rec(31e6, 3, 'ord_finished', 'A', 'schema=loop cycle=3 release=7 response_ns=1000000'),
                ]),
                // missed in the next
                step(40e6, 't=40ms X:0 2', [rec(38e6, 5, 'ord_deadline_miss', '', 'schema=loop cycle=3 tick_ns=30000000')],
                    [{ timeNs: 38e6, seq: 4, who: 'ORD', line: 'deadline miss: loop (ORD:0)' }]),
                // activated again while B still runs: the new cycle is held (ORD's line), then missed
                step(60e6, 't=60ms X:0 3', [rec(58e6, 9, 'ord_deadline_miss', '', 'schema=loop cycle=0 tick_ns=50000000')], [
                    { timeNs: 50e6, seq: 6, who: 'ORD', line: 'activate loop (activation #2 from SUP)' },
                    { timeNs: 50e6, seq: 7, who: 'ORD', line: 'cycle of loop held: B still runs a release of an earlier activation' },
                    { timeNs: 58e6, seq: 8, who: 'ORD', line: 'deadline miss: loop cycle 0 (ORD:0)' },
                ]),
            ],
        } as unknown as ScenarioResult;
        const text = textReport([result], { verbose: true });
        expect(text).toMatch(/38ms {4}ORD\| deadline miss \(ORD:0\): loop cycle 3 \(not finished: B\)\n/);
        expect(text).toMatch(/58ms {4}ORD\| deadline miss \(ORD:0\): loop cycle 0 \(held: nothing released, B still runs an earlier release\)\n/);
        expect(text).not.toMatch(/deadline miss: loop (cycle \d+ )?\(ORD:0\)/); // ORD's bare line (both forms): told by the record
        expect(textReport([result])).not.toContain('deadline miss'); // not verbose: the rules say it
        // at the end, each periodic schema's figures, as `contract trace` ends a run's story
        expect(text).toContain('t=60ms X:0 3\n                  schema loop: 0 completed cycles, 2 deadline misses, 0 overruns, 1 held cycle\n  passed:');
        // and as data in the JSON report
        expect(JSON.parse(jsonReport([result])).scenarios[0].schemas).toEqual([
            { schema: 'loop', completedCycles: 0, maxResponseNs: 0, deadlineMisses: 2, overruns: 0, heldCycles: 1, missedTicks: 0, lateReleases: 0 },
        ]);
    });

    it('--verbose folds ORD\'s periodic releases: each module\'s first after an activation, then a count per step', () => {
        const log = (timeNs: number, seq: number, line: string) => ({ timeNs, seq, who: 'ORD', line });
        const cycle = (k: number) => [log(k * 10e6, 3 * k, 'release A (loop)'), log(k * 10e6 + 1e6, 3 * k + 1, 'release B (loop)')];
        const step = (timeNs: number, source: string, lines: ReturnType<typeof log>[]) => ({
            line: 1, source, timeNs, kind: 'event' as const, ok: true,
            record: { line: 1, timeNs, ok: true, verb: 'event', delivered: 1, rules: [], actions: [], log: lines },
        });
        const result = {
            file: 'loop.scenario', passed: true, failures: [], eventsProcessed: 2, endNs: 1e9, ms: 1, harnessMs: 1,
            steps: [
                step(0, 't=0 X:0 1', [log(0, -1, 'activate loop'), ...cycle(0), ...cycle(1), ...cycle(2)]),
                step(100e6, 't=100ms X:0 2', [...cycle(5), ...cycle(6), log(70e6, 100, 'deactivate loop'), log(80e6, 101, 'activate loop'), ...cycle(8)]),
            ],
        } as unknown as ScenarioResult;
        const lines = textReport([result], { verbose: true }).split('\n').map((l) => l.trim().replace(/\s+/g, ' '));
        const releases = lines.filter((l) => / ORD\| (release|…)/.test(l));
        expect(releases).toEqual([
            '0 ORD| release A (loop)', '1ms ORD| release B (loop)',
            "21ms ORD| … 4 more releases of loop (each module's first after an activation is shown)",
            // a new activation shows each module's first release again
            '80ms ORD| release A (loop)', '81ms ORD| release B (loop)',
            "61ms ORD| … 4 more releases of loop (each module's first after an activation is shown)",
        ].sort((x, y) => parseFloat(x) - parseFloat(y)));
        // without --verbose no engine line at all
        expect(textReport([result]).includes('ORD|')).toBe(false);
    });

    it('a string value with a newline stays on its line; junit counts a failed event step as a test, as its testsuite does', () => {
        const failedEvent = {
            line: 2, source: 't=1ms MAZ:0 "q', timeNs: 1e6, kind: 'event' as const, ok: false, message: 'x.scenario:2: event failed: "a\nb\u202ec" is not a value',
            record: { line: 2, timeNs: 1e6, ok: false, verb: 'event', delivered: 0, rules: [], actions: [], log: [] },
        };
        const result = { file: 'x.scenario', passed: false, failures: [failedEvent], eventsProcessed: 1, endNs: 2e6, ms: 1, harnessMs: 1, steps: [failedEvent] } as unknown as ScenarioResult;
        const text = textReport([result]);
        expect(text).toContain('event failed: "a?b?c" is not a value');
        // delivered to nobody because it failed, not for want of a subscriber (field test ft58c, defect 2)
        expect(text).not.toContain('no supervisor is subscribed');
        const ok = { ...failedEvent, ok: true, message: undefined, record: { ...failedEvent.record, ok: true } };
        expect(textReport([{ ...result, passed: true, failures: [], steps: [ok] } as unknown as ScenarioResult])).toContain('(no supervisor is subscribed to this event, no event flow connected to it: nobody received it)');
        const junit = junitReport([result]);
        expect(junit).toMatch(/<testsuites name="contract simulate" tests="1" failures="1">/);
        expect(junit).toMatch(/<testsuite name="x.scenario" tests="1" failures="1"/);
        // a title of megabytes is cut in the test cases' classname (it was repeated whole in each)
        const long = junitReport([{ ...result, title: 'T'.repeat(5_000_000) } as ScenarioResult]);
        expect(long).toContain(`classname="${'T'.repeat(200)}…"`);
        expect(long.length).toBeLessThan(5_000);
    });
});
