/** The text report writes every time of a scenario in one unit, so that its time column reads down. */
import { describe, expect, it } from 'vitest';
import { reportTimeFormat, textReport, type ScenarioResult } from '../src/index.js';

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
});
