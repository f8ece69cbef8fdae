import { describe, expect, it } from 'vitest';
import { CSV_HEADER, parseTrace, renderStory, StoryTeller } from './index.js';

const MS = 1_000_000;

/** The records of a run's logs (each log's lines after the CSV header). */
const recordsOf = (logs: Record<string, string[]>) =>
    parseTrace(Object.entries(logs).map(([name, lines]) => ({ name, text: [CSV_HEADER, ...lines, ''].join('\n') })));

/** MAB's handling of one MAA:0 event received at `ms`, `handlingNs` long: its event_received and event_handled records. */
const handled = (ms: number, handlingNs: number, from = 'MAA', fromPort = 0) => [
    `${ms * MS},w,MAB,event_received,${from},0,24,from_port=${fromPort} latency_ns=9000`,
    `${ms * MS + handlingNs},w,MAB,event_handled,${from},0,0,from_port=${fromPort} handling_ns=${handlingNs}`,
];

describe("an asynchronous module's handling of its events (event_handled), told at the story's end", () => {
    // 100 events of 2.4 ms, one of 3.7 ms (the 51st), one of 9.1 ms from another producer (the 80th)
    const lines = Array.from({ length: 100 }, (_, i) => handled(10 + i * 10, i === 50 ? 3_700_000 : i === 79 ? 9_100_000 : 2_400_000, i === 79 ? 'MAC' : 'MAA', i === 79 ? 1 : 0)).flat();
    const logs = { 'SUP_1.csv': [`${1 * MS},w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns`], 'MAB_1.csv': lines };

    it('per module: the events handled, p99 and max of the handling time, the longest with its event and when it was received', () => {
        const story = renderStory(recordsOf(logs));
        expect(story.filter((l) => l.startsWith('MAB '))).toEqual([
            'MAB handled 100 events: handling p99 3.7 ms, max 9.1 ms; the longest, MAC:1 -> MAB:0 received at +0.799000s, 9.1 ms',
        ]);
        // after the flows' lines, before the schemas' and the counts
        expect(story.at(-2)).toMatch(/^MAB handled /);
    });

    it('gives the same as data (contract run --format json: eventHandling)', () => {
        const teller = new StoryTeller();
        for (const r of recordsOf(logs)) teller.tell(r);
        expect(teller.eventHandlingFigures()).toEqual([{
            module: 'MAB', handled: 100, p99HandlingNs: 3_700_000, maxHandlingNs: 9_100_000,
            longest: { from: 'MAC', fromPort: 1, port: 0, receivedMonoNs: String(800 * MS), handlingNs: 9_100_000 },
        }]);
    });

    it('tells nothing of a log with no event_handled (a runtime that wrote none), and takes no forged handling time', () => {
        const old = renderStory(recordsOf({ 'MAB_1.csv': lines.filter((l) => !l.includes('event_handled')) }));
        expect(old.some((l) => l.includes(' handled '))).toBe(false);
        const forged = renderStory(recordsOf({ 'MAB_1.csv': [`${MS},w,MAB,event_handled,MAA,0,0,from_port=0 handling_ns=-5`] }));
        expect(forged.some((l) => l.includes(' handled '))).toBe(false);
    });
});
