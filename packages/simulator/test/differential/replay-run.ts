/**
 * The machinery of the differential tests (differential*.bwrap.test.ts): run an example for real
 * (`contract run --sandbox bwrap`: real processes, the real module code), turn its CSV trace into a
 * scenario (the events the supervisors got, at their times since the start function started), run
 * that scenario in the simulator, and put both sides' supervisor decisions (`sup_rule`) in one
 * comparable form.
 *
 * What is replayed, and how its values are found:
 * - every `event_posted` record of a module to a supervisor (producer side: each event once, at the
 *   time it was posted, whatever the supervisor then did with it); a supervisor's own notifications
 *   are not replayed (the simulated supervisor makes them);
 * - every deadline miss of the real ORD (`ord_deadline_miss`, `ORD:0 "schema"`) and conflict
 *   (`scheduler` "conflict: S shares ... (ORD:1)", `ORD:1 "S"`): they depend on the machine's timing,
 *   so the simulated ORD (whose virtual modules are never late) cannot make them by itself;
 * - a value: the CSV has none for an event (only its size), but a rule change it caused names it
 *   (`cause=OBS:0 value=0.35`): each cause goes to the latest post of that port before it (within 5 ms: a
 *   post is logged once sent, its receiver may have logged first). Datatype
 *   values are logged as `{N bytes}` and events that changed no rule name no value: those take the
 *   example's `fallback` (a value the test explains), else the type's default.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { isRule, parseTrace, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { formatTime, type RuleChange } from '../../src/index.js';
import { REPO } from '../support.js';

export interface RealRun {
    records: TraceRecord[];
    code: number | null;
    /** stderr and the end of stdout, for the assertion message. */
    output: string;
    cleanUp(): void;
}

/** Runs a copy of `project` (without its logs) for `duration` in bwrap and reads its CSV trace. */
export function runForReal(project: string, duration: string): RealRun {
    const scratch = mkdtempSync(join(tmpdir(), 'contract-sim-diff-'));
    const name = basename(project);
    cpSync(project, join(scratch, name), { recursive: true, filter: (src) => !/\/(logs|run)$/.test(src) });
    const run = spawnSync(process.execPath, [join(REPO, 'packages/cli/bin/contract.js'), 'run', name, '--sandbox', 'bwrap', '--duration', duration, '--logs', join(scratch, 'logs'), '--format', 'json'],
        { cwd: scratch, encoding: 'utf8', timeout: 280_000, maxBuffer: 64 * 1024 * 1024 });
    const dir = join(scratch, 'logs');
    let files: { name: string; text: string }[] = [];
    try {
        files = readdirSync(dir).filter((f) => f.endsWith('.csv')).map((f) => ({ name: f, text: readFileSync(join(dir, f), 'utf8') }));
    } catch {
        /* no logs: the status says why */
    }
    return {
        records: parseTrace(files),
        code: run.status,
        output: `${run.stderr ?? ''}\n${(run.stdout ?? '').slice(-2000)}`,
        cleanUp: () => rmSync(scratch, { recursive: true, force: true }),
    };
}

export interface ReplayPlan {
    /** The supervisors of the project. */
    supervisors: ReadonlySet<string>;
    /** The function the launcher starts, as a scenario `start` takes it (`GLB.mission()`). */
    start: string;
    /** The value of an event whose value the logs do not give (undefined: the port type's default). */
    fallback?: (module: string, port: number) => string | undefined;
}

export interface RunScenario {
    /** The scenario text: `until`, `start`, then one line per replayed event. */
    text: string;
    /** The run's `sup_rule` records of the supervisors, up to the launcher's stop. */
    real: RuleRecord[];
    /** How many replayed events of each source (`OBS:0`, `ORD:0`...), for the test's own checks. */
    counts: Map<string, number>;
}

const mono = (r: KnownRecord | RuleRecord): bigint => BigInt(r.monoNs);
const LOGGED_DATATYPE = /^\{\d+ bytes\}$/;
/** How much later than its receiver a producer may log a post (measured: ~0.1 ms; far below the examples' event periods). */
const POST_LOGGED_LATE = 5_000_000n;

interface Post {
    t: bigint;
    source: string;
    value?: string;
}

/** The scenario of a real run (see the header for what is replayed). */
export function scenarioOfRun(records: TraceRecord[], plan: ReplayPlan): RunScenario {
    const known = records.filter((r): r is KnownRecord | RuleRecord => r.kind !== 'unknown');
    const [startSup, startFn] = plan.start.replace(/\(.*$/, '').split('.');
    const started = known.find((r) => r.module === startSup && r.kind === 'supervisor' && r.detail === `function ${startFn} started`);
    if (!started) throw new Error(`the run has no "function ${startFn} started" record of ${startSup}`);
    const t0 = mono(started);
    // the launcher's stop (KILL/STOP from contract-launch) ends the comparison
    const stop = known.find((r) => plan.supervisors.has(r.module) && r.kind === 'request_received' && r.peer === 'contract-launch' && /^(STOP|KILL)/.test(r.detail));
    const end = stop ? mono(stop) : BigInt(Number.MAX_SAFE_INTEGER);
    const real = known.filter(isRule).filter((r) => plan.supervisors.has(r.module) && mono(r) < end);

    const posts: Post[] = [];
    const seen = new Set<string>();
    for (const r of known) {
        const t = mono(r);
        if (t < t0 || t >= end) continue;
        if (r.kind === 'event_posted' && plan.supervisors.has(r.peer) && !plan.supervisors.has(r.module) && r.port !== null) {
            const key = `${r.module}:${r.port}@${r.monoNs}`;
            if (seen.has(key)) continue;
            seen.add(key);
            posts.push({ t, source: `${r.module}:${r.port}` });
        } else if (r.module === 'ORD' && r.kind === 'ord_deadline_miss') {
            posts.push({ t, source: 'ORD:0', value: JSON.stringify(String(r.fields.schema)) });
        } else if (r.module === 'ORD' && r.kind === 'scheduler') {
            const conflict = /^conflict: (\S+) shares .*\(ORD:1\)$/.exec(r.detail);
            if (conflict) posts.push({ t, source: 'ORD:1', value: JSON.stringify(conflict[1]) });
        }
    }
    posts.sort((a, b) => (a.t < b.t ? -1 : a.t > b.t ? 1 : 0));
    // each rule change caused by an event names its value: the latest post of that port before it
    // (give or take POST_LOGGED_LATE: the producer logs a post once sent, after its receiver may
    // already have logged what it decided)
    for (const r of real) {
        const c = r.causeEvent;
        if (c.kind !== 'event' || LOGGED_DATATYPE.test(c.value)) continue;
        const source = `${c.module}:${c.port}`;
        let post: Post | undefined;
        for (const p of posts) {
            if (p.t > mono(r) + POST_LOGGED_LATE) break;
            if (p.source === source) post = p;
        }
        if (post && post.value === undefined) post.value = c.value;
    }

    const counts = new Map<string, number>();
    const lines = [`until ${formatTime(Number(end - t0))}`, `start ${plan.start}`];
    for (const p of posts) {
        counts.set(p.source, (counts.get(p.source) ?? 0) + 1);
        const [module, port] = p.source.split(':');
        const value = p.value ?? plan.fallback?.(module!, Number(port)) ?? '';
        lines.push(`t=${formatTime(Number(p.t - t0))} ${p.source} ${value}`.trimEnd());
    }
    return { text: lines.join('\n') + '\n', real, counts };
}

/** One decision, as both sides write it: `SUP action.SECOND active <- MAA:2 value="disconnected"`. */
export const decision = (sup: string, fn: string, rule: string, active: boolean, cause: string): string => `${sup} ${fn}.${rule} ${active ? 'active' : 'inactive'} <- ${cause}`;

export const realDecisions = (real: RuleRecord[], sup: string): string[] =>
    real.filter((r) => r.module === sup).map((r) => decision(sup, r.function, r.rule, r.active, r.cause));

export const simulatedDecisions = (changes: RuleChange[], sup: string): string[] =>
    changes.filter((c) => c.supervisor === sup).map((c) => decision(sup, c.function, c.rule, c.active, c.cause));
