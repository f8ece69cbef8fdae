import { describe, expect, it } from 'vitest';
import { safe } from '../src/runner/schema-story.js';
import fc from 'fast-check';
import { parseScenario } from '../src/scenario/index.js';

describe('parseScenario', () => {
    it('reads every directive with its time and position', () => {
        const p = parseScenario([
            'scenario the story',
            'until 5s',
            'start SUP.action(consigne = {1.0, 2, 3e1})',
            'expect at 1ms rule SUP.action.FIRST active  # comment',
            't=300ms MAA:2 connection_status = "disc#onnected"',
            't=1s ORD:0 "schemaCommande1"',
            'exec MSC 1.5s once',
            't=2s crash MSC',
            'finish MAA',
            'expect local SUP.action.temp_consigne == {1.0, 2.0, 3.0}',
            'expect local failure_data == {"x", -3}',
            'expect schema schemaCommande1 inactive',
            'expect function SUP.action stopped',
            'expect module MAA running',
            't=3s stop SUP.action',
        ].join('\n'));
        expect(p.diagnostics).toEqual([]);
        expect(p.title).toBe('the story');
        expect(p.untilNs).toBe(5e9);
        expect(p.steps.map((s) => [s.kind, s.atNs, s.span.line])).toEqual([
            ['start', 0, 3], ['expect', 1e6, 4], ['event', 3e8, 5], ['event', 1e9, 6], ['exec', 1e9, 7], ['crash', 2e9, 8], ['finish', 2e9, 9],
            ['expect', 2e9, 10], ['expect', 2e9, 11], ['expect', 2e9, 12], ['expect', 2e9, 13], ['expect', 2e9, 14], ['stop', 3e9, 15],
        ]);
        const ev = p.steps[2]!;
        expect(ev.kind === 'event' && ev.portName?.text).toBe('connection_status');
        expect(ev.kind === 'event' && ev.value).toMatchObject({ kind: 'string', value: 'disc#onnected', span: { line: 5, column: 35 } });
        const start = p.steps[0]!;
        expect(start.kind === 'start' && start.args[0]!.value).toMatchObject({ kind: 'struct', elements: [{ kind: 'real' }, { kind: 'int' }, { kind: 'real', value: 30 }] });
        expect(p.steps[4]).toMatchObject({ kind: 'exec', execNs: 1.5e9, once: true });
        expect(p.steps[6]).toMatchObject({ kind: 'finish', module: { text: 'MAA', span: { line: 9, column: 8 } } });
        expect(p.steps[8]).toMatchObject({ kind: 'expect', expectation: { kind: 'local', local: { text: 'failure_data' } } });
        expect(p.steps[8]!.kind === 'expect' && p.steps[8]!.expectation.kind === 'local' && p.steps[8]!.expectation.supervisor).toBeUndefined();
    });

    it('reads expect deadline misses S == N and expect overruns S == N; a count is a whole number', () => {
        const p = parseScenario(['t=1s expect deadline misses velocityLoop == 1', 'expect overruns velocityLoop == 0',
            'expect deadline velocityLoop == 1', 'expect overruns velocityLoop 1', 'expect overruns velocityLoop == 1.5', 'expect overruns velocityLoop == -1',
            'expect deadline misses velocityLoop == 2000000000', 'expect overrun velocityLoop == 1'].join('\n'));
        expect(p.steps.map((s) => s.kind === 'expect' && s.expectation)).toMatchObject([
            { kind: 'count', what: 'deadline misses', schema: { text: 'velocityLoop', span: { line: 1, column: 29 } }, count: 1 },
            { kind: 'count', what: 'overruns', schema: { text: 'velocityLoop' }, count: 0 },
        ]);
        expect(p.diagnostics.map((d) => `${d.line}:${d.column} ${d.message}`)).toEqual([
            "3:17 expected 'misses' after 'deadline' (expect deadline misses SCHEMA == N)",
            "4:30 expected '==' after the schema's name (expect overruns velocityLoop == N)",
            '5:33 expected a count (a whole number, 0 to 1000000000) after \'==\'',
            '6:33 expected a count (a whole number, 0 to 1000000000) after \'==\'',
            '7:40 expected a count (a whole number, 0 to 1000000000) after \'==\'',
            "8:8 expected what to expect: rule, schema, function, module, local, deadline, overruns, found 'overrun'. Did you mean 'overruns'?",
        ]);
    });

    it('reads finish M, finish M after TIME and finish M after TIME once', () => {
        const p = parseScenario(['finish MAB', 'finish MAB after 150ms', 't=1s finish MAB after 0 once', 'finish MAB now', 'finish MAB after'].join('\n'));
        expect(p.steps.map((s) => s.kind === 'finish' && [s.module.text, s.afterNs, s.once])).toEqual([['MAB', undefined, undefined], ['MAB', 150e6, false], ['MAB', 0, true]]);
        expect(p.diagnostics.map((d) => `${d.line} ${d.message}`)).toEqual([
            "4 unexpected 'now' after the module (or 'after TIME' for each of its runs)",
            expect.stringMatching(/^5 expected how long each of its runs lasts/),
        ]);
    });

    it('reads bool values (true, false) alone and inside structured values; truer is no value', () => {
        const p = parseScenario(['t=1ms OBS:1 scan = {{0.3, 5.0}, true}', 't=2ms X:0 false'].join('\n'));
        expect(p.diagnostics).toEqual([]);
        const scan = p.steps[0]!;
        expect(scan.kind === 'event' && scan.value).toMatchObject({ kind: 'struct', elements: [{ kind: 'struct' }, { kind: 'bool', value: true, text: 'true' }] });
        const flag = p.steps[1]!;
        expect(flag.kind === 'event' && flag.value).toMatchObject({ kind: 'bool', value: false });
        const bad = parseScenario('t=1ms X:0 truer');
        expect(bad.diagnostics.map((d) => d.message)).toEqual([expect.stringContaining("expected a value (integer, real, \"string\", true, false, Enum.MEMBER or {structured, value}), found 'truer'")]);
    });

    it('reports what is wrong, where, and what was expected', () => {
        const p = parseScenario([
            't=1s start SUP.action(',
            't=1s stop SUP.action',
            't=500ms MAA:2 "x"',
            'expect at 2x rule A.b.C active',
            'expect rule A.b.C maybe',
            'frobnicate',
            't=3s MAA:2 "unterminated',
        ].join('\n'));
        expect(p.diagnostics.map((d) => [d.line, d.column, d.code])).toEqual([
            [1, 23, 'scenario-syntax'], [3, 3, 'scenario-time-order'], [4, 11, 'scenario-syntax'], [5, 19, 'scenario-syntax'], [6, 1, 'scenario-syntax'], [7, 12, 'scenario-syntax'],
        ]);
        expect(p.diagnostics[1]!.message).toContain("500ms is before the previous step's 1s");
        expect(p.diagnostics[2]!.message).toContain('a time such as 300ms');
        expect(p.diagnostics[3]!.message).toContain("expected 'active' or 'inactive'");
        expect(p.diagnostics[4]!.message).toContain('unknown directive');
    });

    it('a second title or end, and a time finer than a nanosecond, are errors (they were taken silently: the last header won, the time was rounded)', () => {
        const p = parseScenario(['scenario a', 'scenario b', 'until 1s', 'until 2s', 't=0.5ns stop SUP.action', 't=1.0000000006ms stop SUP.action', 'exec CTL 0.7ns', 't=2.5us stop SUP.action', 't=0.500000000s stop SUP.action'].join('\n'));
        expect(p.diagnostics.map((d) => [d.line, d.column, d.message])).toEqual([
            [2, 1, "a second 'scenario' line: a scenario has one title ('a' already)"],
            [4, 1, "a second 'until' line: a scenario has one end (1s already)"],
            [5, 3, '0.5ns is not a whole number of nanoseconds (the virtual clock\'s step): no fraction of a nanosecond'],
            [6, 3, '1.0000000006ms is not a whole number of nanoseconds (the virtual clock\'s step): at most 6 decimals in ms'],
            [7, 10, '0.7ns is not a whole number of nanoseconds (the virtual clock\'s step): no fraction of a nanosecond'],
        ]);
        expect(p.title).toBe('a');
        expect(p.untilNs).toBe(1e9);
        expect(p.steps.map((s) => s.atNs)).toEqual([2500, 0.5e9]);
    });

    it('a lone CR ends a line, as editors read it (a CR-only file was one line, quoted \'\' at its first CR); a tab in an echoed line stays a tab', () => {
        const p = parseScenario('start SUP.action()\rt=1ms stop SUP.action\r\nt=2ms start SUP.action()\n');
        expect(p.diagnostics).toEqual([]);
        expect(p.steps.map((s) => [s.span.line, s.kind])).toEqual([[1, 'start'], [2, 'stop'], [3, 'start']]);
        expect(safe('start\tSUP.action()')).toBe('start\tSUP.action()');
        expect(safe('a\nb\rc\u001bd')).toBe('a?b?c?d');
    });

    it('offers the word a misspelt one was meant to be', () => {
        const p = parseScenario([
            'exepct rule SUP.action.FIRST active',
            'expect rule SUP.action.FIRST actve',
            'expect rlue SUP.action.FIRST active',
            'expect function SUP.action runing',
            'strat SUP.action()',
            'expect rule SUP.action.FIRST maybe',
        ].join('\n'));
        expect(p.diagnostics.map((d) => d.message)).toEqual([
            expect.stringMatching(/^unknown directive 'exepct': .*\. Did you mean 'expect'\?$/),
            expect.stringMatching(/^expected 'active' or 'inactive', found 'actve'\. Did you mean 'active'\?$/),
            expect.stringMatching(/^expected what to expect: .*, found 'rlue'\. Did you mean 'rule'\?$/),
            expect.stringMatching(/^expected 'running' or 'stopped', found 'runing'\. Did you mean 'running'\?$/),
            expect.stringMatching(/^unknown directive 'strat': .*\. Did you mean 'start'\?$/),
            "expected 'active' or 'inactive', found 'maybe'",
        ]);
    });

    it('a step other than expect written with `at TIME` says how to time it', () => {
        const p = parseScenario(['crash SCN at 10ms', 'stop SUP.action at 2s', 't=3s crash MAA at 4s', 'crash SCN now'].join('\n'));
        expect(p.diagnostics.map((d) => d.message)).toEqual([
            "unexpected 'at' after the module (only 'expect' takes 'at TIME': write 't=10ms crash SCN')",
            expect.stringMatching(/^unexpected 'at' after .* \(only 'expect' takes 'at TIME': write 't=2s stop SUP\.action'\)$/),
            "unexpected 'at' after the module (only 'expect' takes 'at TIME')",
            "unexpected 'now' after the module",
        ]);
    });

    it('lists 200 problems, then says how many more; a long word is quoted cut', () => {
        const p = parseScenario(Array.from({ length: 1000 }, (_, i) => `frobnicate${i}`).join('\n'));
        expect(p.diagnostics).toHaveLength(201);
        expect(p.diagnostics[200]!.message).toBe('800 more problem(s) not listed: the first 200 are');
        const long = parseScenario(`${'x'.repeat(10_000)} 1`);
        expect(long.diagnostics[0]!.message.length).toBeLessThanOrEqual(301);
        expect(long.diagnostics[0]!.message.endsWith('…')).toBe(true);
    });

    it('a string reads the language\'s escapes, and refuses a raw control character', () => {
        const ok = parseScenario('t=1ms MAA:2 "a\\nb\\\\c\\"d\\x"');
        // `\x` is read as `x`, with a warning (no such escape: seldom what was meant)
        expect(ok.diagnostics.map((d) => [d.severity, d.code])).toEqual([['warning', 'scenario-unknown-escape']]);
        expect((ok.steps[0] as unknown as { value: { value: string } }).value.value).toBe('a\nb\\c"dx');
        const raw = parseScenario('t=1ms MAA:2 "a\u0000b\u001b[2J"');
        expect(raw.diagnostics.map((d) => d.message)).toEqual([expect.stringContaining('a string holds no raw control character')]);
    });

    it('never throws, whatever the text', () => {
        fc.assert(fc.property(fc.string({ unit: 'binary', maxLength: 300 }), (text) => {
            const p = parseScenario(text);
            for (const d of p.diagnostics) expect(d.line).toBeGreaterThanOrEqual(1);
        }), { numRuns: 500 });
        const alphabet = fc.constantFrom('t=', '1s', 'expect', ' ', 'rule', 'A.b.C', ':', '{', '}', '"', ',', 'MAA:2', '\n', 'start', '(', ')', '=', '#', '.');
        fc.assert(fc.property(fc.array(alphabet, { maxLength: 60 }), (parts) => {
            parseScenario(parts.join(''));
        }), { numRuns: 1000 });
    });
});
