/**
 * What the parsed steps of a large scenario hold (an 8 MiB scenario has some 200,000 steps, all
 * kept while its expectations are checked): each step of a kind shares V8's hidden class of that
 * kind. A step copied with a spread (`{ ...body, atNs, span, source }`) got a hidden class of its
 * own once a few kinds had been seen: some 330 bytes a step, and the parse took four times as long.
 */
import { setFlagsFromString } from 'node:v8';
import { describe, expect, it } from 'vitest';
import { parseScenario } from '../src/scenario/parse.js';

setFlagsFromString('--allow-natives-syntax');
/** Whether V8 gives two objects one hidden class (compiled after the flag: `%` is V8's own syntax). */
const haveSameMap = new Function('a', 'b', 'return %HaveSameMap(a, b)') as (a: object, b: object) => boolean;

const KINDS = [
    (t: number) => `t=${t}us TEL:0 joystick = {0.3, 0.1}`,
    () => 'expect local DRV.teleop.cmd == {0.3, 0.1}',
    (t: number) => `t=${t}us TEL:1 request = "auto"`,
    () => 'expect rule MIS.mission.TELEOP inactive',
    () => 'start SUP.f(a = 1)',
    () => 'stop SUP.f',
    () => 'crash M',
    () => 'exec M 1ms once',
];

describe('the parsed steps of a large scenario', () => {
    it('share one hidden class per kind of line, whatever kinds came before', () => {
        const lines = Array.from({ length: 800 }, (_, i) => KINDS[i % KINDS.length]!(10 + i * 10));
        const { steps, diagnostics } = parseScenario(lines.join('\n'));
        expect(diagnostics).toEqual([]);
        expect(steps).toHaveLength(800);
        const ownClass = steps.filter((step, i) => !haveSameMap(step, steps[i % KINDS.length]!)).map((s) => s.span.line);
        expect(ownClass).toEqual([]);
    });
});
