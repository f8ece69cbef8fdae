/**
 * The three outputs of `contract simulate` (docs/simulation.md §3): text like a test runner,
 * JSON (every step's record, for the IDE), JUnit XML (CI reports).
 */
import { ownRunEndText, readableCause, type NamedSchemaFigures } from '@contract-studio/build-service/trace';
import type { ScenarioResult, StepResult, TrimmedRecords } from './run-scenario.js';
import { actionLines } from '../trace/action-lines.js';
import { outputLines } from './output-lines.js';
import { isMissLine, MissTeller, ordWhat, safe } from './schema-story.js';

const UNITS = [['s', 1_000_000_000], ['ms', 1_000_000], ['us', 1_000], ['ns', 1]] as const;

/**
 * One unit for every time of a scenario's report, so that the time column reads down (`2900ms`,
 * `3000ms`, `3100ms`, not `2900ms`, `3s`, `3100ms`): the coarsest unit that writes each of `times`
 * (the steps' times and the end) as a whole number; other times (an ORD release at 300.5 ms) get
 * decimals in that unit. Each stays a valid scenario time literal.
 */
export function reportTimeFormat(times: number[]): (ns: number) => string {
    const [unit, size] = UNITS.find(([, n]) => times.every((t) => t % n === 0)) ?? UNITS[3];
    return (ns) => {
        if (ns === 0) return '0';
        const whole = Math.trunc(ns / size);
        const rest = Math.abs(ns % size);
        if (rest === 0) return `${whole}${unit}`;
        const digits = String(size).length - 1;
        return `${ns < 0 && whole === 0 ? '-' : ''}${whole}.${String(rest).padStart(digits, '0').replace(/0+$/, '')}${unit}`;
    };
}

/** The times that choose a report's unit: its steps' and its end. */
function timesOf(r: ScenarioResult): number[] {
    return [r.endNs, ...r.steps.map((s) => s.timeNs)];
}

/**
 * The verbose report's engine lines, with ORD's periodic releases folded: the first release of each
 * module after each activation of its schema is shown, the later ones of a step are counted on one
 * line at the time of the last (`ORD| … 297 more releases of velocityLoop (each module's first after
 * an activation is shown)`), so a 1 kHz schema does not bury the rule changes.
 */
class ReleaseFolder {
    /** Per schema, the modules whose release was shown since its last activation. */
    private readonly shown = new Map<string, Set<string>>();

    fold(log: ScenarioResult['steps'][number]['record']['log']): Array<{ t: number; seq: number; text: string }> {
        const out: Array<{ t: number; seq: number; text: string }> = [];
        const folded = new Map<string, { n: number; t: number; seq: number }>();
        for (const l of log) {
            const ord = ordWhat(l);
            if (ord.what === 'activate') this.shown.set(String(ord.fields['schema']), new Set());
            if (ord.what === 'release') {
                const module = String(ord.fields['module']), schema = String(ord.fields['schema']);
                let seen = this.shown.get(schema);
                if (!seen) this.shown.set(schema, (seen = new Set()));
                if (seen.has(module)) {
                    const f = folded.get(schema) ?? { n: 0, t: l.timeNs, seq: -1 };
                    folded.set(schema, { n: f.n + 1, t: l.timeNs, seq: l.seq ?? -1 });
                    continue;
                }
                seen.add(module);
            }
            out.push({ t: l.timeNs, seq: l.seq ?? -1, text: `  ${l.who}| ${safe(l.line)}` });
        }
        for (const [schema, f] of folded) {
            out.push({ t: f.t, seq: f.seq, text: `  ORD| … ${f.n} more release${f.n === 1 ? '' : 's'} of ${schema} (each module's first after an activation is shown)` });
        }
        return out;
    }
}

/**
 * Each periodic schema's figures over scenario `r`, from ORD's records and lines of its steps (of a
 * scenario whose records were not all kept, the runner's, told as they came).
 */
function schemaCounts(r: ScenarioResult): NamedSchemaFigures[] {
    if (r.trimmed) return r.trimmed.schemas;
    const teller = new MissTeller();
    for (const s of r.steps) teller.misses(s.record);
    return teller.schemaFigures();
}

/** Lines of one part of the text report (textReportParts). */
const TEXT_LINES_PER_PART = 5_000;

/**
 * The text report in parts whose concatenation is textReport's text (each part whole lines), so
 * that a scenario of many steps is written without the whole report in memory at once.
 */
export function* textReportParts(results: ScenarioResult[], options: { verbose?: boolean } = {}): Generator<string> {
    for (const r of results) yield* textScenarioParts(r, options);
    const failed = results.filter((r) => !r.passed).length;
    yield textSummary(results.length - failed, failed);
}

/** The text report's last line, once every scenario's parts were written. */
export function textSummary(passed: number, failed: number): string {
    return `${passed} passed, ${failed} failed\n`;
}

/**
 * One scenario's part of the text report (textReportParts: every scenario's, then textSummary), in
 * parts of whole lines: a caller that writes each scenario's report once it has run holds one
 * scenario's result at a time.
 */
export function* textScenarioParts(r: ScenarioResult, options: { verbose?: boolean } = {}): Generator<string> {
    let out: string[] = [];
    const formatTime = reportTimeFormat(timesOf(r));
    const releases = new ReleaseFolder();
    const misses = new MissTeller();
    out.push(`${r.file}${r.title ? ` — ${safe(r.title)}` : ''}`);
    let trimmed: StepResult['trimmed'];
    for (const s of r.steps) {
        // where the records kept whole end (RECORD_BOUNDS): said where it happens, told in the NOTE below
        if (s.trimmed && s.trimmed !== trimmed) {
            trimmed = s.trimmed;
            out.push(`  ----  ${trimmed === 'compact' ? 'from here on the steps were kept without their actions, engine lines and records' : 'from here on the steps were kept without their rule changes and output either'} (NOTE below)`);
        }
        const time = formatTime(s.timeNs).padStart(8);
        const mark = s.ok ? (s.kind === 'expect' ? 'ok  ' : '    ') : 'FAIL';
        // what happened since the step before, in the engines' order: what came before this
        // step (a timer, a release) above its line, so that the time column reads down
        const happened: Array<{ t: number; seq: number; text: string }> = s.record.rules.map((c) => ({
            t: c.timeNs, seq: c.seq ?? -1,
            text: `${c.active ? '+' : '-'} ${c.supervisor}.${c.function}.${c.rule} ${c.active ? 'active' : 'inactive'}  <- ${safe(readableCause(c.cause))}`,
        }));
        if (options.verbose) {
            // the actions in a run's words, and what a module or flow hold decided beyond its action line
            for (const l of actionLines(s.record.actions, s.record.records)) happened.push({ t: l.t, seq: l.seq, text: `  ${l.who}: ${safe(l.text)}` });
            // a run a `finish` ended (no STOP, no ack), in the words of `contract trace`
            for (const rec of s.record.records ?? []) {
                const ended = rec.kind === 'run_finished' ? ownRunEndText(rec.detail) : undefined;
                if (ended) happened.push({ t: rec.timeNs, seq: rec.seq ?? -1, text: `  ${safe(rec.module)}| ${ended}` });
            }
            const told = misses.misses(s.record);
            // ORD's bare line of a miss the typed record tells (with its cycle and what it waited for)
            const log = told.length ? s.record.log.filter((l) => !isMissLine(l)) : s.record.log;
            happened.push(...releases.fold(log), ...told);
        }
        const ordered = happened.map((h, i) => ({ ...h, i })).sort((x, y) => x.t - y.t || x.seq - y.seq || x.i - y.i);
        const line = (h: { t: number; text: string }) => `              ${formatTime(h.t).padStart(8)}  ${h.text}`;
        // (an expectation looks at the state after its time: what happened at its time too)
        const before = (h: { t: number }) => h.t < s.timeNs || (h.t === s.timeNs && (s.kind === 'expect' || s.kind === 'end'));
        for (const h of ordered) if (before(h)) out.push(line(h));
        out.push(`  ${mark} ${time}  ${s.kind === 'end' ? `end of the scenario` : safe(s.source)}`);
        for (const h of ordered) if (!before(h)) out.push(line(h));
        // what the user's functions printed (with or without --verbose: docs/simulation.md §2), under the step's own lines
        out.push(...outputLines(s.record.output, ' '.repeat(26)));
        // (an event that failed was delivered to nobody for its own reason, said below: not for want of a subscriber)
        if (s.kind === 'event' && s.ok && s.record.delivered === 0) out.push('                        (no supervisor is subscribed to this event, no event flow connected to it: nobody received it)');
        if (!s.ok && s.message) out.push(`       ${safe(s.message)}`);
        if (out.length >= TEXT_LINES_PER_PART) {
            yield out.join('\n') + '\n';
            out = [];
        }
    }
    // what ORD did of each periodic schema in the whole scenario (the counts `expect deadline misses` and `expect overruns` check)
    if (options.verbose) for (const l of r.trimmed?.schemaLines ?? misses.schemaLines()) out.push(`                  ${safe(l)}`);
    if (r.trimmed) out.push(`  NOTE ${safe(r.trimmed.message)}`);
    if (r.error) out.push(`  ERROR ${safe(r.error)}`);
    const answered = r.steps.filter((s) => s.kind === 'expect').length;
    // a run stopped short (timed out, crashed) says how many expectations it never reached, and how far it got
    const planned = Math.max(r.expectationsPlanned ?? answered, answered);
    const unreached = planned > answered ? ` (${planned - answered} not reached)` : '';
    const simulated = r.error && r.reachedNs < r.endNs ? `${formatTime(r.reachedNs)} of ${formatTime(r.endNs)}` : formatTime(r.endNs);
    out.push(`  ${r.passed ? 'passed' : 'FAILED'}: ${answered - r.failures.filter((f) => f.kind === 'expect').length}/${planned} expectations${unreached}, ${r.failures.length} failure(s); ${simulated} simulated in ${r.ms.toFixed(0)} ms (${r.eventsProcessed} engine inputs)`);
    out.push('');
    yield out.join('\n') + '\n';
}

export function textReport(results: ScenarioResult[], options: { verbose?: boolean } = {}): string {
    return [...textReportParts(results, options)].join('');
}

/** What `--format json` says of the records not kept (the schema figures are the scenario's `schemas`). */
function trimmedJson(t: TrimmedRecords) {
    return { line: t.line, timeNs: t.timeNs, ...(t.bareLine !== undefined ? { bareLine: t.bareLine, bareTimeNs: t.bareTimeNs } : {}), droppedItems: t.droppedItems, message: t.message };
}

/** Steps of one part of the JSON report (jsonReportParts). */
const JSON_STEPS_PER_PART = 2_000;

/**
 * `--format json` in parts whose concatenation is jsonReport's text, so that a scenario of many
 * steps is written without the whole report in memory at once: a scenario's head, then its steps
 * a few thousand at a time.
 */
export function* jsonReportParts(results: ScenarioResult[]): Generator<string> {
    yield JSON_REPORT_HEAD;
    for (const [i, r] of results.entries()) yield* jsonScenarioParts(r, i === 0);
    yield JSON_REPORT_END;
}

/** Characters of a scenario's title kept as its JUnit test cases' classname. */
const JUNIT_NAME_CHARS = 200;

/** What the JSON report begins and ends with, around its scenarios' parts (jsonScenarioParts). */
export const JSON_REPORT_HEAD = '{"scenarios":[';
export const JSON_REPORT_END = ']}\n';

/** One scenario's parts of the JSON report (`first`: the report's first scenario, not preceded by a comma). */
export function* jsonScenarioParts(r: ScenarioResult, first: boolean): Generator<string> {
    const head = JSON.stringify({
        file: r.file, title: r.title, passed: r.passed, error: r.error, endNs: r.endNs, reachedNs: r.reachedNs, expectations: r.expectationsPlanned, ms: Math.round(r.ms), eventsProcessed: r.eventsProcessed,
        ...(r.trimmed ? { trimmed: trimmedJson(r.trimmed) } : {}),
        schemas: schemaCounts(r),
        failures: r.failures.map((f) => ({ line: f.line, source: f.source, timeNs: f.timeNs, message: f.message, expected: f.record.expected, actual: f.record.actual })),
        steps: [],
    });
    // `…,"steps":[]}`: the steps go between its brackets
    yield `${first ? '' : ','}${head.slice(0, -2)}`;
    for (let from = 0; from < r.steps.length; from += JSON_STEPS_PER_PART) {
        const part = r.steps.slice(from, from + JSON_STEPS_PER_PART).map((s) => JSON.stringify({ ...s.record, source: s.source, kind: s.kind }));
        yield `${from ? ',' : ''}${part.join(',')}`;
    }
    yield ']}';
}

export function jsonReport(results: ScenarioResult[]): string {
    return [...jsonReportParts(results)].join('');
}

function xml(s: string): string {
    // XML 1.0 forbids most control characters even escaped
    return s.replace(/[\u0000-\u0008\u000b\u000c\u000e-\u001f]/g, '?').replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
}

export function junitReport(results: ScenarioResult[]): string {
    return junitReportOf(results.map(junitSuite));
}

/**
 * What the JUnit report keeps of a scenario: its testcases (one per expectation and per failed
 * step: an event or start the harness refused) and its figures, not its steps' records: a caller
 * that runs many scenarios keeps this of each until the report's totals are known.
 */
export interface JunitSuite {
    file: string;
    name: string;
    ms: number;
    failures: number;
    error?: string;
    trimmed?: string;
    cases: Array<{ name: string; failure?: { message: string; text: string } }>;
}

export function junitSuite(r: ScenarioResult): JunitSuite {
    const cases = r.steps.filter((s) => s.kind === 'expect' || !s.ok).map((s) => ({
        name: `line ${s.line}: ${s.source}`,
        ...(!s.ok ? { failure: { message: s.message ?? 'failed', text: `expected: ${s.record.expected ?? ''}\nactual: ${s.record.actual ?? s.record.error ?? ''}` } } : {}),
    }));
    // the title names every test case (classname): a title of megabytes was repeated in each
    const name = r.title ?? r.file;
    return { file: r.file, name: name.length > JUNIT_NAME_CHARS ? `${name.slice(0, JUNIT_NAME_CHARS)}…` : name, ms: r.ms, failures: r.failures.length, ...(r.error ? { error: r.error } : {}), ...(r.trimmed ? { trimmed: r.trimmed.message } : {}), cases };
}

/** The JUnit report of the suites (junitSuite of each scenario, in order). */
export function junitReportOf(suites: JunitSuite[]): string {
    const out = ['<?xml version="1.0" encoding="UTF-8"?>'];
    const total = suites.reduce((n, r) => n + r.cases.length + (r.error ? 1 : 0), 0);
    const failures = suites.reduce((n, r) => n + r.failures + (r.error ? 1 : 0), 0);
    out.push(`<testsuites name="contract simulate" tests="${total}" failures="${failures}">`);
    for (const r of suites) {
        out.push(`  <testsuite name="${xml(r.file)}" tests="${r.cases.length + (r.error ? 1 : 0)}" failures="${r.failures + (r.error ? 1 : 0)}" time="${(r.ms / 1000).toFixed(3)}">`);
        for (const c of r.cases) {
            out.push(`    <testcase classname="${xml(r.name)}" name="${xml(c.name)}" time="0">`);
            if (c.failure) out.push(`      <failure message="${xml(c.failure.message)}">${xml(c.failure.text)}</failure>`);
            out.push('    </testcase>');
        }
        if (r.error) out.push(`    <testcase classname="${xml(r.name)}" name="run"><error message="${xml(r.error)}"/></testcase>`);
        if (r.trimmed) out.push(`    <system-out>${xml(r.trimmed)}</system-out>`);
        out.push('  </testsuite>');
    }
    out.push('</testsuites>');
    return out.join('\n') + '\n';
}
