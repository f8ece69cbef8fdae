import { describe, expect, it } from 'vitest';
import { CSV_HEADER, parseRecordLine, parseTrace, renderStory, type KnownRecord } from './index.js';

/** The story of a run's logs: each log's records (without their line ends) after the CSV header. */
const storyOf = (logs: Record<string, string[]>): string[] =>
    renderStory(parseTrace(Object.entries(logs).map(([name, lines]) => ({ name, text: [CSV_HEADER, ...lines, ''].join('\n') }))));

const MS = 1_000_000;

/** LFR's record of one CAM:0 event at `ms` with its value (a CSV field: quotes doubled) and the rule changes it made. */
const received = (ms: number, value: string, rules: number) =>
    `${ms * MS},w,LFR,event_received,CAM,0,256,"from_port=0 latency_ns=40000 rules=${rules} value=${value.replace(/"/g, '""')}"`;

describe('a supervisor\'s events told with their values', () => {
    const lfr = [
        `${1 * MS},w,LFR,sup_rule,,,0,drive.FOLLOW active cause=started(LINK)`,
        received(100, '"lsot"', 0),
        received(200, '"lsot"', 0),
        received(300, '"found"', 0),
        received(400, '"lsot"', 0),
        `${500 * MS},w,LFR,sup_rule,,,0,"drive.FOLLOW inactive cause=CAM:0 value=""stop"""`,
        received(500, '"stop"', 1),
    ];

    it('tells the first event of each value that changed no rule, then counts them per flow with their values', () => {
        const story = storyOf({ 'LFR_1.csv': lfr });
        const told = story.filter((l) => l.includes('changed no rule'));
        expect(told).toEqual([
            '+0.099000s LFR  received CAM:0 = "lsot": it changed no rule (no active rule waited for this value); later ones are counted at the end',
            '+0.299000s LFR  received CAM:0 = "found": it changed no rule (no active rule waited for this value); later ones are counted at the end',
            'LFR got CAM:0 ×4 that changed no rule: "lsot" ×3, "found" ×1',
            expect.stringContaining(', 4 events that changed no rule, '),
        ]);
        // the event that changed a rule is counted as a delivery only
        expect(story.at(-1)).toContain('5 event deliveries');
    });

    it('gives the value and the rule changes as fields (--format json), a value with spaces whole', () => {
        const k = parseRecordLine('LFR_1.csv', 1, received(100, '"lost it"', 0)) as KnownRecord;
        expect(k.fields).toMatchObject({ from_port: 0, latency_ns: 40000, rules: 0, value: '"lost it"' });
    });

    it('tells nothing for a module\'s event_received (no value) nor for an older supervisor log', () => {
        const story = storyOf({ 'LFR_1.csv': [`${100 * MS},w,LFR,event_received,CAM,0,256,from_port=0 latency_ns=40000`] });
        expect(story.filter((l) => l.includes('changed no rule'))).toEqual([]);
    });
});

describe('changes of producer on an input data port', () => {
    const change = (ms: number, producer: string, was: string) =>
        `${ms * MS},w,MOT,producer_changed,${producer},0,16,was ${was}: a new producer (a schema switch)`;
    const interleave = (ms: number, producer: string, was: string) =>
        `${ms * MS},w,MOT,producer_changed,${producer},0,16,was ${was}: interleaved: ${was} and ${producer} both feed this port (each gave a single value between two of the other\'s within 1 s): an input data port has one producer`;

    it('tells a schema switch as a plain line, once per port and pair, and counts the changes', () => {
        const story = storyOf({ 'MOT_1.csv': [change(100, 'SRC', 'CTL'), change(700, 'CTL', 'SRC'), change(3100, 'SRC', 'CTL')] });
        expect(story.filter((l) => l.includes('MOT:0'))).toEqual([
            '+0.000000s MOT  input MOT:0 now fed by SRC (was CTL): a schema switch; later changes are counted at the end',
            'input MOT:0 changed producer 3 times (CTL, SRC)',
        ]);
        expect(story.some((l) => l.includes('warning'))).toBe(false);
    });

    it('tells two producers interleaving as a warning, once per port, and counts the interleaves', () => {
        const story = storyOf({ 'MOT_1.csv': [change(100, 'SRC', 'CTL'), change(120, 'CTL', 'SRC'), interleave(140, 'SRC', 'CTL'), interleave(160, 'CTL', 'SRC')] });
        expect(story.filter((l) => l.includes('MOT:0'))).toEqual([
            '+0.000000s MOT  input MOT:0 now fed by SRC (was CTL): a schema switch; later changes are counted at the end',
            '+0.040000s MOT  warning: input MOT:0 is fed by CTL and SRC at once (their values interleave): an input data port has one producer; later changes are counted at the end',
            'input MOT:0 changed producer 4 times (CTL, SRC), 2 of them interleaved (two producers at once: a wiring fault)',
        ]);
        expect(story.at(-1)).toContain(', 2 interleaved producer changes, ');
    });
});
