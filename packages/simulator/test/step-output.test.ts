/**
 * What the user's functions print during a step (a compute function's printf) is in the text
 * report under that step, with or without --verbose, each line marked `output|` (docs/simulation.md
 * §2 "Their output is shown with the step"); being the project's C, it is made safe for a terminal
 * (escape sequences, CR, bidi overrides written `\uXXXX`) and bounded (long lines cut, lines per step).
 */
import { describe, expect, it } from 'vitest';
import { OUTPUT_BOUNDS, outputLines, textReport, type ScenarioResult } from '../src/index.js';

const step = (timeNs: number, kind: 'event' | 'expect', source: string, output?: string) => ({
    line: 1, source, timeNs, kind, ok: true,
    record: {
        line: 1, timeNs, ok: true, verb: kind, delivered: 1, actions: [], log: [],
        rules: kind === 'event' ? [{ timeNs, seq: 1, supervisor: 'CEL', function: 'run', rule: 'PICKING', active: true, cause: 'CAM:0 value=1' }] : [],
        ...(output === undefined ? {} : { output }),
    },
});

function report(output: string, verbose = false): string[] {
    const result = {
        file: 'cell.scenario', passed: true, failures: [], eventsProcessed: 2, endNs: 2e9, ms: 1, harnessMs: 1,
        steps: [step(1e9, 'event', 't=1s CAM:0 1', output), step(2e9, 'expect', 'expect rule CEL.run.PICKING active')],
    } as unknown as ScenarioResult;
    return textReport([result], { verbose }).split('\n');
}

describe('the text report shows what the user\'s functions printed, under its step', () => {
    it('each printed line under the step\'s line and its rule changes, before the next step, marked as output; verbose or not', () => {
        for (const verbose of [false, true]) {
            const lines = report('countPick: pick #1 started\ncountPick: done\n', verbose);
            const at = (text: string) => lines.findIndex((l) => l.includes(text));
            expect(at('t=1s CAM:0 1')).toBeLessThan(at('+ CEL.run.PICKING active'));
            expect(at('+ CEL.run.PICKING active')).toBeLessThan(at('output| countPick: pick #1 started'));
            expect(at('output| countPick: pick #1 started') + 1).toBe(at('output| countPick: done'));
            expect(at('output| countPick: done')).toBeLessThan(at('expect rule CEL.run.PICKING active'));
            // its own line end opens no empty output line
            expect(lines.filter((l) => l.includes('output|'))).toHaveLength(2);
        }
    });

    it('a step that printed nothing has no output line', () => {
        expect(report('').some((l) => l.includes('output|'))).toBe(false);
    });

    it('escape sequences, CR, C1 and bidi overrides are written \\uXXXX: nothing reaches the terminal raw', () => {
        const hostile = '\x1b]0;pwned\x07\x1b[2Jcleared\rover\x9b31m\u202eevil\u2028x\tok\r\n';
        const lines = report(hostile).filter((l) => l.includes('output|'));
        expect(lines).toEqual([`${' '.repeat(26)}output| \\u001b]0;pwned\\u0007\\u001b[2Jcleared\\u000dover\\u009b31m\\u202eevil\\u2028x\tok`]);
        expect(lines.join('\n')).not.toMatch(/[\x00-\x08\x0b-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e]/);
    });

    it('a very long line is cut, many lines are counted: bounded whatever the function printed', () => {
        const long = 'x'.repeat(100_000);
        const cut = report(`${long}\n`).filter((l) => l.includes('output|'));
        expect(cut).toHaveLength(1);
        expect(cut[0]).toContain(`[… ${100_000 - OUTPUT_BOUNDS.lineChars} characters cut]`);
        expect(cut[0]!.length).toBeLessThan(OUTPUT_BOUNDS.lineChars + 80);
        const many = Array.from({ length: 500 }, (_, i) => `line ${i}`).join('\n');
        const shown = report(many).filter((l) => l.includes('output|'));
        expect(shown).toHaveLength(OUTPUT_BOUNDS.linesPerStep + 1);
        expect(shown.at(-1)).toContain(`… ${500 - OUTPUT_BOUNDS.linesPerStep} more lines (--format json has the step's whole output)`);
        // a cut never splits a character in two
        const emoji = outputLines('😀'.repeat(200), '', { lineChars: 5, linesPerStep: 1 })[0]!;
        expect(emoji).toBe('output| 😀😀 [… 396 characters cut]');
    });
});
