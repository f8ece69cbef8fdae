/**
 * Runs one checked scenario in a built harness: writes its steps, reads one record per step,
 * pairs them with the scenario's lines and says which expectations failed and why. The harness
 * is bounded (time, output size); whatever it prints is parsed defensively. What the result keeps
 * of the records is bounded too (RECORD_BOUNDS): past it, the steps are kept without their lists,
 * and the result says from which step (`trimmed`).
 */
import { spawn } from 'node:child_process';
import { dirname } from 'node:path';
import type { NamedSchemaFigures } from '@contract-studio/build-service/trace';
import { formatTime, type ParsedScenario, type Step } from '../scenario/index.js';
import type { ResolvedLocal } from '../scenario/index.js';
import { stepLine, type StepRecord } from './protocol.js';
import type { Confinement } from '../harness/confine.js';
import { MissTeller } from './schema-story.js';

export interface StepResult {
    /** Scenario line (1-based) and its text; line 0 / '' for the end of the scenario. */
    line: number;
    source: string;
    timeNs: number;
    kind: Step['kind'] | 'end';
    ok: boolean;
    /** For a failure: what went wrong, naming the step, the expected and the actual state. */
    message?: string;
    record: StepRecord;
    /**
     * Set on the steps past RECORD_BOUNDS.wholeBytes: `compact`, the record kept without its
     * actions, engine lines, typed records, schemas and locals; `bare`, past compactBytes too,
     * without its rule changes and output either (and its error, expected and actual cut). What
     * was left out is counted in the record's `dropped`.
     */
    trimmed?: 'compact' | 'bare';
}

/** What a scenario's result did not keep of its steps' records (RECORD_BOUNDS), said by each report. */
export interface TrimmedRecords {
    /** The first step kept `compact` (line 0: the end of the scenario), and its time. */
    line: number;
    timeNs: number;
    /** The first step kept `bare`, if any. */
    bareLine?: number;
    bareTimeNs?: number;
    /** Items of the steps' lists left out (also in the steps' `dropped`). */
    droppedItems: number;
    /** Each periodic schema's figures over the whole scenario, told as the records came. */
    schemas: NamedSchemaFigures[];
    /** The same as the verbose report's lines. */
    schemaLines: string[];
    /** What was not kept, from where, in a sentence of the reports. */
    message: string;
}

export interface ScenarioResult {
    file: string;
    title?: string;
    passed: boolean;
    steps: StepResult[];
    failures: StepResult[];
    /** Inputs the engines processed (module events, timers, ORD events, release acks...). */
    eventsProcessed: number;
    /** Virtual end time (the scenario's `until`, or its last step's time). */
    endNs: number;
    /**
     * Virtual time the simulation reached: the last step it answered (endNs when it ended; less
     * when it was stopped: timed out, crashed), and the expectations the scenario has (some may
     * not have been reached).
     */
    reachedNs: number;
    expectationsPlanned: number;
    /** Wall time of the harness run, seen from here (process start and pipes included). */
    ms: number;
    /** The harness's own wall time (its end record). */
    harnessMs: number;
    /** A problem of the run itself (harness crashed, timed out): the scenario failed. */
    error?: string;
    /** Set when the steps' records were not all kept (RECORD_BOUNDS). */
    trimmed?: TrimmedRecords;
}

/**
 * What a scenario's result keeps of its steps' records: the harness writes each step's record as one
 * JSON line, and the result keeps every record whole while they add up to `wholeBytes` of those
 * lines (from the first step on); each later step keeps its verdict, error, expected and actual,
 * rule changes and output while those add up to `compactBytes` more, and only its verdict past
 * that. Whatever the scenario, the records kept stay some tens of MB in memory (a step's record
 * parsed takes about 1.5 times its line); the harness's output itself is bounded at
 * MAX_OUTPUT_BYTES. docs/simulation.md §4 "Bounds".
 */
export interface RecordBounds {
    wholeBytes: number;
    compactBytes: number;
}

/** 48 MiB: what the IDE's answer keeps of a simulation (200,000 items of its steps' lists, web-ide simulate-api.ts) fits in it. */
export const RECORD_BOUNDS: RecordBounds = { wholeBytes: 48 * 1024 * 1024, compactBytes: 16 * 1024 * 1024 };

export interface RunOptions {
    /** Wall-clock limit of one scenario (default 60 s). */
    timeoutMs?: number;
    /** Only failures and the end record (benchmarks): no per-step state. */
    quiet?: boolean;
    /**
     * How the harness runs (harness/confine.ts): it runs the project's C functions. Without one it
     * runs unconfined (tests of the runner itself only: prepareProject always gives one).
     */
    confinement?: Confinement;
    /** What the result keeps of the records (default RECORD_BOUNDS). */
    recordBounds?: RecordBounds;
}

/** The harness's output, all records together: the scenario is stopped past it. */
export const MAX_OUTPUT_BYTES = 512 * 1024 * 1024;
/** A `bare` step's error, expected and actual: the characters kept of each (the harness writes up to 8 KiB). */
const BARE_TEXT_CHARS = 256;
const MIB = 1024 * 1024;
/** The lists a trimmed step no longer has (shared: nothing adds to a step's lists after the run). */
const NONE: never[] = Object.freeze([]) as unknown as never[];

function asRecord(line: string): StepRecord | undefined {
    try {
        const v = JSON.parse(line) as StepRecord;
        if (typeof v !== 'object' || v === null || typeof v.line !== 'number' || typeof v.ok !== 'boolean') return undefined;
        // the lists are lists, whatever was written (the project's C runs in this process and may write on its output)
        if (!Array.isArray(v.rules)) v.rules = [];
        if (!Array.isArray(v.actions)) v.actions = [];
        if (!Array.isArray(v.log)) v.log = [];
        if (!Array.isArray(v.records)) v.records = [];
        return v;
    } catch {
        return undefined;
    }
}

const chars = (s: unknown) => (typeof s === 'string' ? s.length : 0);
const items = (xs: unknown) => (Array.isArray(xs) ? xs.length : 0);

/** About how many bytes what a `compact` step keeps takes. */
function compactSize(r: StepRecord): number {
    return chars(r.output) + chars(r.error) + chars(r.expected) + chars(r.actual) + (r.rules.length ? JSON.stringify(r.rules).length : 0);
}

function cut(s: string | undefined): string | undefined {
    return typeof s !== 'string' || s.length <= BARE_TEXT_CHARS ? s : `${s.slice(0, BARE_TEXT_CHARS)}…`;
}

/** Record `r` as a `compact` or `bare` step keeps it, and how many of its lists' items it leaves out. */
function trimRecord(r: StepRecord, bare: boolean): { record: StepRecord; left: number } {
    const left = r.actions.length + r.log.length + r.records.length + items(r.schemas) + items(r.locals) + (bare ? r.rules.length : 0);
    const dropped = (Number.isSafeInteger(r.dropped) ? r.dropped! : 0) + left;
    // one shape for the many steps (an event's): no property added after (each would take room of its own)
    const kept: StepRecord = {
        line: r.line, timeNs: r.timeNs, verb: r.verb, ok: r.ok, delivered: r.delivered,
        rules: bare || !r.rules.length ? NONE : r.rules, actions: NONE, log: NONE, records: NONE, dropped: dropped || undefined,
    };
    if (r.error !== undefined) kept.error = bare ? cut(r.error) : r.error;
    if (r.expected !== undefined) kept.expected = bare ? cut(r.expected) : r.expected;
    if (r.actual !== undefined) kept.actual = bare ? cut(r.actual) : r.actual;
    if (r.output !== undefined && !bare) kept.output = r.output;
    if (r.end) {
        kept.end = r.end;
        if (r.eventsProcessed !== undefined) kept.eventsProcessed = r.eventsProcessed;
        if (r.wallNs !== undefined) kept.wallNs = r.wallNs;
    }
    return { record: kept, left };
}

/** Counts the step's records in the schemas' figures; a record that cannot be read is not counted. */
function tell(story: MissTeller, r: StepRecord): void {
    try {
        story.count(r);
    } catch {
        // not of the harness's shape: not told
    }
}

function stepName(line: number, timeNs: number): string {
    return line ? `line ${line} (${formatTime(timeNs)})` : `the end of the scenario (${formatTime(timeNs)})`;
}

function trimmedMessage(t: Omit<TrimmedRecords, 'message'>, bounds: RecordBounds): string {
    const mib = (n: number) => `${Math.round((n / MIB) * 10) / 10} MiB`;
    return `the steps' records passed ${mib(bounds.wholeBytes)}: from ${stepName(t.line, t.timeNs)} on, the steps are kept without their actions, engine lines, `
        + `typed records, schemas and locals (${t.droppedItems} items, counted in each step's dropped), so the --verbose lines, the --format json records and the --trace file stop before that step`
        + (t.bareLine !== undefined ? `; from ${stepName(t.bareLine, t.bareTimeNs ?? 0)} on (${mib(bounds.compactBytes)} more), without their rule changes and output either` : '')
        + '; the verdicts, failures and schema figures are the whole scenario\'s';
}

/** Where a run stopped short stood: the last step it answered, and the next one it did not reach. */
function stoppedAt(result: ScenarioResult, lines: Int32Array, times: Float64Array, endNs: number): string {
    const last = result.steps[result.steps.length - 1];
    const done = last ? `it had answered the steps up to line ${last.line} (at ${formatTime(last.timeNs)} of virtual time)` : 'it had answered no step yet';
    const at = last ? lines.indexOf(last.line) : -1;
    const next = at + 1 < lines.length ? `, the next one is line ${lines[at + 1]} at ${formatTime(times[at + 1]!)}` : `, the end of the scenario at ${formatTime(endNs)}`;
    return done + next;
}

/** What a step's record needs of the step: its source line and kind. */
interface StepOfLine {
    source: string;
    kind: Step['kind'];
}

function failureMessage(file: string, step: StepOfLine | undefined, r: StepRecord): string {
    const where = `${file}:${r.line}`;
    const src = step ? ` (${step.source})` : '';
    if (r.verb.startsWith('expect-')) {
        if (r.error) return `${where}: at ${formatTime(r.timeNs)}${src}: ${r.error}`;
        return `${where}: at ${formatTime(r.timeNs)}${src}: expected ${r.expected ?? '?'}, but it is ${r.actual ?? '?'}`;
    }
    return `${where}: at ${formatTime(r.timeNs)}${src}: ${r.verb} failed: ${r.error ?? 'refused'}`;
}

export function runScenario(exe: string, file: string, scenario: ParsedScenario, locals: Map<number, ResolvedLocal>,
    options: RunOptions = {}): Promise<ScenarioResult> {
    const t0 = performance.now();
    const lastNs = scenario.steps.length ? scenario.steps[scenario.steps.length - 1]!.atNs : 0;
    const endNs = Math.max(scenario.untilNs ?? lastNs, lastNs);
    let input = harnessInput(scenario, locals, endNs, options.quiet === true);
    // what the records need of their steps, by line: the parsed steps (about 1 KB each: names, values and
    // their spans) are not held while the scenario runs, nor is anything else of `scenario` (only this
    // function's own code reads it, never the closures below): an 8 MiB scenario's are some 210 MB
    const byLine = new Map<number, StepOfLine>();
    for (const s of scenario.steps) byLine.set(s.span.line, { source: s.source, kind: s.kind });
    const title = scenario.title;
    const bounds = options.recordBounds ?? RECORD_BOUNDS;
    const expectationsPlanned = scenario.steps.reduce((n, s) => n + (s.kind === 'expect' ? 1 : 0), 0);
    // each step's line and time, in order (12 bytes a step): what a run stopped short says it had not reached
    const stepLines = Int32Array.from(scenario.steps, (s) => s.span.line);
    const stepTimes = Float64Array.from(scenario.steps, (s) => s.atNs);

    return new Promise((resolvePromise) => {
        const result: ScenarioResult = { file, title, passed: false, steps: [], failures: [], eventsProcessed: 0, endNs, reachedNs: 0, expectationsPlanned, ms: 0, harnessMs: 0 };
        let child;
        try {
            // the simulator sees its own folder (read-only) and the toolchain's libraries, nothing else
            const argv = options.confinement?.wrap([exe], { cwd: dirname(exe), readOnly: [dirname(exe)] }) ?? [exe];
            child = spawn(argv[0]!, argv.slice(1), { stdio: ['pipe', 'pipe', 'pipe'] });
        } catch (e) {
            result.error = `cannot start the simulator: ${e instanceof Error ? e.message : String(e)}`;
            resolvePromise(result);
            return;
        }
        /** The pieces of the line being read (its bytes: a character split between two reads is whole once joined). */
        let pending: Buffer[] = [];
        let bytes = 0;
        let stderr = '';
        let sawEnd = false;
        /** Bytes of the records kept whole, and of what the `compact` steps keep. */
        let whole = 0;
        let compact = 0;
        /** Once the records are no longer kept whole: what is said of it, and ORD's story told as the records come. */
        let trimmed: (Omit<TrimmedRecords, 'message' | 'schemas' | 'schemaLines'> & { story: MissTeller }) | undefined;
        const timer = setTimeout(() => {
            result.error = `the simulation did not finish within ${(options.timeoutMs ?? 60_000) / 1000} s of wall time: ${stoppedAt(result, stepLines, stepTimes, endNs)} (a user function that never returns, or more virtual time than the simulator goes through in that time: every period of every active periodic schema is simulated)`;
            child.kill('SIGKILL');
        }, options.timeoutMs ?? 60_000);
        const take = (line: string, size: number) => {
            if (!line) return;
            let record = asRecord(line);
            if (!record) return;
            const step = byLine.get(record.line);
            if (record.timeNs > result.reachedNs) result.reachedNs = record.timeNs;
            if (record.end) {
                sawEnd = true;
                result.eventsProcessed = record.eventsProcessed ?? 0;
                result.harnessMs = (record.wallNs ?? 0) / 1e6;
            }
            let trim: StepResult['trimmed'];
            if (!trimmed && whole + size <= bounds.wholeBytes) whole += size;
            else {
                if (!trimmed) {
                    // the schemas' figures can no longer be told from the steps kept: told from here, as the records come
                    const story = new MissTeller();
                    for (const s of result.steps) tell(story, s.record);
                    trimmed = { line: record.line, timeNs: record.timeNs, droppedItems: 0, story };
                }
                tell(trimmed.story, record);
                const kept = compactSize(record);
                const bare = trimmed.bareLine !== undefined || compact + kept > bounds.compactBytes;
                if (bare && trimmed.bareLine === undefined) {
                    trimmed.bareLine = record.line;
                    trimmed.bareTimeNs = record.timeNs;
                }
                if (!bare) compact += kept;
                const t = trimRecord(record, bare);
                record = t.record;
                trimmed.droppedItems += t.left;
                trim = bare ? 'bare' : 'compact';
            }
            const kind = record.end ? 'end' : step?.kind ?? 'end';
            const sr: StepResult = trim ? { line: record.line, source: step?.source ?? '', timeNs: record.timeNs, kind, ok: record.ok, record, trimmed: trim }
                : { line: record.line, source: step?.source ?? '', timeNs: record.timeNs, kind, ok: record.ok, record };
            if (!record.ok) {
                sr.message = failureMessage(file, step, record);
                result.failures.push(sr);
            }
            result.steps.push(sr);
        };
        const takeLine = (piece: Buffer) => {
            const all = pending.length ? Buffer.concat([...pending, piece]) : piece;
            pending = [];
            try {
                take(all.toString('utf8'), all.length);
            } catch {
                // a record not of the harness's shape (its lists' items): skipped, as a line that is no JSON
            }
        };
        child.stdout.on('data', (d: Buffer) => {
            if (bytes > MAX_OUTPUT_BYTES) return;
            bytes += d.length;
            if (bytes > MAX_OUTPUT_BYTES) {
                result.error = `the simulation wrote more than ${MAX_OUTPUT_BYTES} bytes: stopped`;
                child.kill('SIGKILL');
                return;
            }
            let from = 0;
            let nl;
            while ((nl = d.indexOf(10, from)) >= 0) {
                takeLine(d.subarray(from, nl));
                from = nl + 1;
            }
            if (from < d.length) pending.push(d.subarray(from));
        });
        child.stderr.on('data', (d: Buffer) => {
            if (stderr.length < 16 * 1024) stderr += d.toString('utf8');
        });
        child.stdin.on('error', () => { /* the harness ended early: reported below */ });
        child.on('error', (e) => {
            result.error ??= `cannot run the simulator: ${e.message}`;
        });
        child.on('close', (code, signal) => {
            clearTimeout(timer);
            if (pending.length && bytes <= MAX_OUTPUT_BYTES) takeLine(Buffer.alloc(0));
            if (!sawEnd && !result.error) result.error = `the simulator ended before the end of the scenario (${signal ?? `exit ${code}`})${stderr ? `: ${stderr.trim()}` : ''}`;
            if (trimmed) {
                const { story, ...told } = trimmed;
                const t = { ...told, schemas: story.schemaFigures(), schemaLines: story.schemaLines() };
                result.trimmed = { ...t, message: trimmedMessage(t, bounds) };
            }
            result.ms = performance.now() - t0;
            result.passed = !result.error && result.failures.length === 0;
            // the child's streams outlive its close for a while (their handles close later): their
            // listeners, and through them the result, are let go now, not then — else a command that
            // runs a second long scenario at once holds the first one's records meanwhile
            for (const stream of [child.stdout, child.stderr, child.stdin]) stream.removeAllListeners();
            child.removeAllListeners();
            resolvePromise(result);
        });
        child.stdin.end(input);
        input = ''; // the pipe holds what it has not written yet
    });
}

/** The harness's input: one line per step, then the end. */
function harnessInput(scenario: ParsedScenario, locals: Map<number, ResolvedLocal>, endNs: number, quiet: boolean): string {
    const lines: string[] = [];
    if (quiet) lines.push('0\t0\tquiet');
    scenario.steps.forEach((s, i) => lines.push(stepLine(s, i, locals)));
    lines.push(`${endNs}\t0\tend`);
    return lines.join('\n') + '\n';
}
