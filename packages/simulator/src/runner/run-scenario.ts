/**
 * Runs one checked scenario in a built harness: writes its steps, reads one record per step,
 * pairs them with the scenario's lines and says which expectations failed and why. The harness
 * is bounded (time, output size); whatever it prints is parsed defensively.
 */
import { spawn } from 'node:child_process';
import { dirname } from 'node:path';
import { formatTime, type ParsedScenario, type Step } from '../scenario/index.js';
import type { ResolvedLocal } from '../scenario/index.js';
import { stepLine, type StepRecord } from './protocol.js';
import type { Confinement } from '../harness/confine.js';

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
}

export interface ScenarioResult {
    file: string;
    title?: string;
    passed: boolean;
    steps: StepResult[];
    failures: StepResult[];
    /** Inputs the engines processed (module events, timers, ORD events, release acks...). */
    eventsProcessed: number;
    /** Virtual end time. */
    endNs: number;
    /** Wall time of the harness run, seen from here (process start and pipes included). */
    ms: number;
    /** The harness's own wall time (its end record). */
    harnessMs: number;
    /** A problem of the run itself (harness crashed, timed out): the scenario failed. */
    error?: string;
}

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
}

const MAX_OUTPUT_BYTES = 512 * 1024 * 1024;

function asRecord(line: string): StepRecord | undefined {
    try {
        const v = JSON.parse(line) as StepRecord;
        if (typeof v !== 'object' || v === null || typeof v.line !== 'number' || typeof v.ok !== 'boolean') return undefined;
        v.rules ??= [];
        v.actions ??= [];
        v.log ??= [];
        v.records ??= [];
        return v;
    } catch {
        return undefined;
    }
}

function failureMessage(file: string, step: Step | undefined, r: StepRecord): string {
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
    const lines: string[] = [];
    if (options.quiet) lines.push('0\t0\tquiet');
    scenario.steps.forEach((s, i) => lines.push(stepLine(s, i, locals)));
    lines.push(`${endNs}\t0\tend`);
    const byLine = new Map<number, Step>();
    for (const s of scenario.steps) byLine.set(s.span.line, s);

    return new Promise((resolvePromise) => {
        const result: ScenarioResult = { file, title: scenario.title, passed: false, steps: [], failures: [], eventsProcessed: 0, endNs, ms: 0, harnessMs: 0 };
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
        let pending = '';
        let bytes = 0;
        let stderr = '';
        let sawEnd = false;
        const timer = setTimeout(() => {
            result.error = `the simulation did not finish within ${(options.timeoutMs ?? 60_000) / 1000} s (a user function that never returns?)`;
            child.kill('SIGKILL');
        }, options.timeoutMs ?? 60_000);
        const take = (line: string) => {
            if (!line) return;
            const record = asRecord(line);
            if (!record) return;
            const step = byLine.get(record.line);
            const sr: StepResult = {
                line: record.line, source: step?.source ?? '', timeNs: record.timeNs, kind: record.end ? 'end' : step?.kind ?? 'end', ok: record.ok, record,
            };
            if (record.end) {
                sawEnd = true;
                result.eventsProcessed = record.eventsProcessed ?? 0;
                result.harnessMs = (record.wallNs ?? 0) / 1e6;
            }
            if (!record.ok) {
                sr.message = failureMessage(file, step, record);
                result.failures.push(sr);
            }
            result.steps.push(sr);
        };
        child.stdout.on('data', (d: Buffer) => {
            bytes += d.length;
            if (bytes > MAX_OUTPUT_BYTES) {
                result.error = `the simulation wrote more than ${MAX_OUTPUT_BYTES} bytes: stopped`;
                child.kill('SIGKILL');
                return;
            }
            pending += d.toString('utf8');
            let nl;
            while ((nl = pending.indexOf('\n')) >= 0) {
                take(pending.slice(0, nl));
                pending = pending.slice(nl + 1);
            }
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
            take(pending);
            if (!sawEnd && !result.error) result.error = `the simulator ended before the end of the scenario (${signal ?? `exit ${code}`})${stderr ? `: ${stderr.trim()}` : ''}`;
            result.ms = performance.now() - t0;
            result.passed = !result.error && result.failures.length === 0;
            resolvePromise(result);
        });
        child.stdin.end(lines.join('\n') + '\n');
    });
}
