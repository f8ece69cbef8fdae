/**
 * What a scenario's result keeps of the harness's records is bounded (run-scenario.ts
 * RECORD_BOUNDS, docs/simulation.md §4 "Bounds"): the records are kept whole up to 48 MiB, then
 * each step keeps its verdict, rule changes and output (16 MiB more), then its verdict alone; every
 * report says from which line, and what it still gives is the whole scenario's (verdicts, failures,
 * schema figures) or a prefix of the unbounded run's (records, trace). A scenario of 100,000 events
 * used to keep every parsed record (2.4 GB of memory for 150 MB of records).
 */
import { join } from 'node:path';
import { beforeAll, describe, expect, it } from 'vitest';
import {
    jsonReport, junitReport, loadScenario, RECORD_BOUNDS, runLoadedScenario, textReport, textReportParts,
    type PreparedProject, type RecordBounds, type ScenarioResult,
} from '../src/index.js';
import { stepsToTrace, traceStepOf } from '../src/trace/steps-to-trace.js';
import { prepared, ROBOT } from './support.js';

let project: PreparedProject;

beforeAll(async () => {
    project = await prepared(ROBOT);
}, 240_000);

/**
 * `events` joystick events 1 ms apart in teleoperation (each: DRV.teleop.FOLLOW active then
 * inactive, the 100 Hz velocity loop's releases, the locals), an expectation of the joystick's
 * value every 250 events; `tail` after them.
 */
function scenario(events: number, tail: string[] = []): string {
    const lines = ['scenario many joystick events', 'start MIS.mission()'];
    for (let i = 0; i < events; i++) {
        lines.push(`t=${10 + i}ms TEL:0 joystick = {0.3, 0.1}`);
        if (i % 250 === 249) lines.push('expect local DRV.teleop.cmd == {0.3, 0.1}');
    }
    return [...lines, ...tail].join('\n') + '\n';
}

async function run(text: string, recordBounds?: RecordBounds): Promise<ScenarioResult> {
    const s = loadScenario(join(ROBOT, 'scenarios', 'many.scenario'), 'many.scenario', text, project.index);
    expect(s.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
    const r = await runLoadedScenario(project, s, recordBounds ? { recordBounds } : {});
    expect(r.error).toBeUndefined();
    return r;
}

const items = (r: ScenarioResult['steps'][number]['record']) =>
    r.actions.length + r.log.length + r.records.length + (r.schemas?.length ?? 0) + (r.locals?.length ?? 0);

/** The JSON report as it was written before it came in parts: one JSON.stringify of everything. */
function wholeJson(results: ScenarioResult[]): string {
    return JSON.stringify({
        scenarios: results.map((r) => ({
            file: r.file, title: r.title, passed: r.passed, error: r.error, endNs: r.endNs, reachedNs: r.reachedNs, expectations: r.expectationsPlanned, ms: Math.round(r.ms), eventsProcessed: r.eventsProcessed,
            ...(r.trimmed ? { trimmed: JSON.parse(jsonReport([r])).scenarios[0].trimmed } : {}),
            schemas: JSON.parse(jsonReport([r])).scenarios[0].schemas,
            failures: r.failures.map((f) => ({ line: f.line, source: f.source, timeNs: f.timeNs, message: f.message, expected: f.record.expected, actual: f.record.actual })),
            steps: r.steps.map((s) => ({ ...s.record, source: s.source, kind: s.kind })),
        })),
    }) + '\n';
}

describe('the records a scenario keeps', () => {
    it('past 48 MiB of records, the steps are kept without their lists, and every report says from which line', async () => {
        // about 1.5 KB of records per event: 40,000 events make some 60 MB
        expect(RECORD_BOUNDS.wholeBytes).toBe(48 * 1024 * 1024);
        const r = await run(scenario(40_000));
        expect(r.passed).toBe(true);
        expect(r.steps).toHaveLength(40_000 + 40_000 / 250 + 2); // start, events, expectations, end
        const t = r.trimmed!;
        expect(t).toBeDefined();
        const first = r.steps.findIndex((s) => s.trimmed);
        expect(r.steps[first]!.line).toBe(t.line);
        expect(r.steps.slice(first).every((s) => s.trimmed === 'compact')).toBe(true);
        expect(t.bareLine).toBeUndefined();
        // the records kept whole: up to the bound, not far below it
        const whole = r.steps.slice(0, first).reduce((n, s) => n + JSON.stringify(s.record).length, 0);
        expect(whole).toBeLessThanOrEqual(RECORD_BOUNDS.wholeBytes);
        expect(whole).toBeGreaterThan(RECORD_BOUNDS.wholeBytes * 0.95);
        // later steps: their rule changes (what the text report shows), their lists counted in `dropped`
        const later = r.steps[first + 10]!;
        expect(later.record.rules.map((c) => `${c.rule} ${c.active}`)).toEqual(['FOLLOW true', 'FOLLOW false']);
        expect(later.record.locals).toBeUndefined();
        expect(later.record.records).toEqual([]);
        expect(later.record.dropped).toBeGreaterThan(0);
        expect(t.droppedItems).toBe(r.steps.slice(first).reduce((n, s) => n + (s.record.dropped ?? 0), 0));
        // the schema figures are the whole scenario's: 40 s of the 100 Hz velocity loop
        expect(t.schemas.find((f) => f.schema === 'velocityLoop')!.completedCycles).toBeGreaterThan(3_900);

        const text = textReport([r]).split('\n');
        const note = text.findIndex((l) => l.startsWith('  NOTE '));
        expect(text[note]).toContain(`the steps' records passed 48 MiB: from line ${t.line} (`);
        expect(text[note]).toContain('the --format json records and the --trace file stop before that step');
        const marker = text.findIndex((l) => l.startsWith('  ----  '));
        expect(text[marker + 1]).toContain(r.steps[first]!.source);
        expect(text.at(-2)).toBe('1 passed, 0 failed');
        // written in parts of whole lines, the same text
        const parts = [...textReportParts([r])];
        expect(parts.length).toBeGreaterThan(1);
        expect(parts.every((p) => p.endsWith('\n'))).toBe(true);

        const json = JSON.parse(jsonReport([r]));
        expect(json.scenarios[0].trimmed).toMatchObject({ line: t.line, timeNs: t.timeNs, droppedItems: t.droppedItems });
        expect(json.scenarios[0].trimmed.message).toBe(t.message);
        expect(json.scenarios[0].steps).toHaveLength(r.steps.length);
        expect(json.scenarios[0].steps[first - 1].locals.length).toBeGreaterThan(0);
        expect(json.scenarios[0].steps[first].locals).toBeUndefined();
        expect(junitReport([r])).toContain("<system-out>the steps' records passed 48 MiB");

        // the trace ends before the first step not kept whole
        const trace = stepsToTrace(r.steps.map(traceStepOf));
        expect(Number((trace.at(-1) as { monoNs: string }).monoNs)).toBeLessThanOrEqual(r.steps[first - 1]!.timeNs);
    });

    it('what is kept is the unbounded run\'s: the same verdicts, failures, schema figures; the records and the trace up to the first step trimmed', async () => {
        // a deadline miss and a failed expectation late in the scenario, where only verdicts are kept
        const text = scenario(2_000, ['exec VEL 15ms once', 'expect at 2100ms deadline misses velocityLoop == 1', 'expect rule MIS.mission.AUTO active']);
        const full = await run(text, { wholeBytes: Infinity, compactBytes: Infinity });
        const r = await run(text, { wholeBytes: 256 * 1024, compactBytes: 32 * 1024 });
        expect(full.trimmed).toBeUndefined();
        const t = r.trimmed!;
        expect(t.bareLine).toBeDefined();
        const first = r.steps.findIndex((s) => s.trimmed);
        const bare = r.steps.findIndex((s) => s.trimmed === 'bare');
        expect(first).toBeGreaterThan(10);
        expect(bare).toBeGreaterThan(first + 10);
        expect(r.steps[bare]!.line).toBe(t.bareLine);

        expect(r.passed).toBe(false);
        expect(r.failures.map((f) => [f.line, f.message])).toEqual(full.failures.map((f) => [f.line, f.message]));
        expect(r.failures.map((f) => f.trimmed)).toEqual(['bare']);
        expect(r.steps.map((s) => [s.line, s.kind, s.ok, s.timeNs])).toEqual(full.steps.map((s) => [s.line, s.kind, s.ok, s.timeNs]));
        r.steps.forEach((s, i) => {
            const f = full.steps[i]!;
            if (!s.trimmed) expect(s.record).toEqual(f.record);
            else {
                expect(s.record.rules).toEqual(s.trimmed === 'compact' ? f.record.rules : []);
                expect(s.record.output).toBe(s.trimmed === 'compact' ? f.record.output : undefined);
                expect(s.record.dropped ?? 0).toBe((f.record.dropped ?? 0) + items(f.record) + (s.trimmed === 'bare' ? f.record.rules.length : 0));
            }
        });

        // the figures over the whole scenario, not over the steps kept
        const figures = JSON.parse(jsonReport([full])).scenarios[0].schemas;
        expect(figures.find((f: { schema: string }) => f.schema === 'velocityLoop')).toMatchObject({ deadlineMisses: 1, overruns: 1 });
        expect(JSON.parse(jsonReport([r])).scenarios[0].schemas).toEqual(figures);
        const schemaLines = (x: ScenarioResult) => textReport([x], { verbose: true }).split('\n').filter((l) => /^ {18}schema /.test(l));
        expect(schemaLines(r)).toEqual(schemaLines(full));
        expect(schemaLines(r).length).toBeGreaterThan(0);

        // the trace: the unbounded run's, up to the first step trimmed
        expect(stepsToTrace(r.steps.map(traceStepOf), 'many.scenario')).toEqual(stepsToTrace(full.steps.slice(0, first).map(traceStepOf), 'many.scenario'));
        // the text report: the unbounded run's up to that step, where it says so
        const lines = textReport([r], { verbose: true }).split('\n');
        const marker = lines.findIndex((l) => l.startsWith('  ----  '));
        expect(lines.slice(0, marker)).toEqual(textReport([full], { verbose: true }).split('\n').slice(0, marker));
        expect(lines.filter((l) => l.startsWith('  ----  '))).toHaveLength(2);
        // JUnit: the same test cases
        const cases = (x: ScenarioResult) => junitReport([x]).split('\n').filter((l) => l.includes('<testcase') || l.includes('<failure'));
        expect(cases(r)).toEqual(cases(full));
        // the JSON report, written in parts, is the one JSON text it was
        expect(jsonReport([full, r])).toBe(wholeJson([full, r]));
    });
});
