/**
 * Differential test: a real run of the tutorial (`contract run --sandbox bwrap`, 5 s, real
 * processes, real MAA/MSC code) and the simulator fed with the same events must take the same
 * supervisor decisions: every `sup_rule` record of the run's CSV trace (read with
 * @contract-studio/build-service/trace), in order, per supervisor, equals the simulator's rule
 * changes with their causes.
 *
 * The events are taken from the run's logs: each `event_posted` record of a module to a
 * supervisor (producer side: every event once, whatever the supervisor was doing), at its time
 * since GLB.mission started. Values: a string event's value is the one a `sup_rule` cause of that
 * event carries; MAA:2 events that changed no rule were "connected" (the only other status the
 * tutorial's MAA script posts); datatype values are not in the logs (`{N bytes}`) and the
 * tutorial's rules test none of them, so they are replayed with the type's default. Supervisors'
 * own notifications (SUP:1) are not replayed: the simulated SUP makes them.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { isRule, parseTrace, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { formatTime, loadScenario, runLoadedScenario, type ScenarioResult } from '../src/index.js';
import { prepared, REPO, TUTORIAL } from './support.js';

const SUPERVISORS = new Set(['SUP', 'GLB']);
let scratch: string;
let records: TraceRecord[];
let runCode: number | null;
let runErr = '';

beforeAll(() => {
    scratch = mkdtempSync(join(tmpdir(), 'contract-sim-diff-'));
    cpSync(TUTORIAL, join(scratch, 'tutorial'), { recursive: true, filter: (src) => !/\/(logs|run)$/.test(src) });
    const run = spawnSync(process.execPath, [join(REPO, 'packages/cli/bin/contract.js'), 'run', 'tutorial', '--sandbox', 'bwrap', '--duration', '5s', '--logs', join(scratch, 'logs'), '--format', 'json'],
        { cwd: scratch, encoding: 'utf8', timeout: 280_000, maxBuffer: 64 * 1024 * 1024 });
    runCode = run.status;
    runErr = `${run.stderr ?? ''}\n${(run.stdout ?? '').slice(-2000)}`;
    const dir = join(scratch, 'logs');
    const files = readdirSync(dir).filter((f) => f.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(dir, name), 'utf8') }));
    records = parseTrace(files);
}, 300_000);
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

const mono = (r: TraceRecord) => ('monoNs' in r ? BigInt(r.monoNs) : 0n);

/** The scenario of the run: its start, the modules' events to supervisors, its end. */
function scenarioOfRun(): { text: string; real: RuleRecord[] } {
    const known = records.filter((r): r is KnownRecord | RuleRecord => r.kind !== 'unknown');
    const started = known.find((r) => r.module === 'GLB' && r.kind === 'supervisor' && r.detail === 'function mission started');
    if (!started) throw new Error('the run has no "function mission started" record of GLB');
    const t0 = mono(started);
    // the launcher's stop (KILL/STOP from contract-launch) ends the comparison
    const stop = known.find((r) => SUPERVISORS.has(r.module) && r.kind === 'request_received' && r.peer === 'contract-launch' && /^(STOP|KILL)/.test(r.detail));
    const end = stop ? mono(stop) : BigInt(Number.MAX_SAFE_INTEGER);
    const real = known.filter(isRule).filter((r) => SUPERVISORS.has(r.module) && mono(r) < end);
    const causes = real.filter((r) => r.causeEvent.kind === 'event');
    const used = new Set<RuleRecord>();
    const seen = new Set<string>();
    const lines = [`until ${formatTime(Number(end - t0))}`, 'start GLB.mission()'];
    for (const r of known) {
        if (r.kind !== 'event_posted' || !SUPERVISORS.has(r.peer) || SUPERVISORS.has(r.module) || r.port === null) continue;
        const t = mono(r);
        if (t < t0 || t >= end) continue;
        const key = `${r.module}:${r.port}@${r.monoNs}`;
        if (seen.has(key)) continue;
        seen.add(key);
        let value = '';
        if (r.module === 'MAA' && r.port === 2) {
            // the first unused cause of MAA:2 within 500 ms of the post carries its value
            const cause = causes.find((c) => !used.has(c) && c.causeEvent.kind === 'event' && c.causeEvent.module === 'MAA' && c.causeEvent.port === 2 && mono(c) >= t && mono(c) - t < 500_000_000n);
            if (cause && cause.causeEvent.kind === 'event') {
                for (const c of causes) if (mono(c) === mono(cause) && c.module === cause.module) used.add(c);
                value = cause.causeEvent.value;
            } else {
                value = '"connected"';
            }
        }
        lines.push(`t=${formatTime(Number(t - t0))} ${r.module}:${r.port} ${value}`.trimEnd());
    }
    return { text: lines.join('\n') + '\n', real };
}

const decision = (sup: string, fn: string, rule: string, active: boolean, cause: string) => `${sup} ${fn}.${rule} ${active ? 'active' : 'inactive'} <- ${cause}`;

describe('simulator vs a real bwrap run of the tutorial', () => {
    let sim: ScenarioResult;
    let real: RuleRecord[];
    let text: string;

    beforeAll(async () => {
        expect(runCode, runErr).toBe(0);
        ({ text, real } = scenarioOfRun());
        const project = await prepared(TUTORIAL);
        const s = loadScenario('run.scenario', 'run.scenario', text, project.index);
        expect(s.diagnostics, text).toEqual([]);
        sim = await runLoadedScenario(project, s);
    }, 120_000);

    it('the run took the report\'s decisions (FIRST, SECOND on "disconnected", the commutation)', () => {
        const told = real.map((r) => decision(r.module, r.function, r.rule, r.active, r.cause));
        expect(told).toContain('SUP action.SECOND active <- MAA:2 value="disconnected"');
        expect(told.length).toBeGreaterThan(5);
    });

    it('every supervisor took the same decisions, in the same order, with the same causes', () => {
        expect(sim.error).toBeUndefined();
        const simulated = sim.steps.flatMap((s) => s.record.rules);
        for (const sup of SUPERVISORS) {
            const want = real.filter((r) => r.module === sup).map((r) => decision(sup, r.function, r.rule, r.active, r.cause));
            const got = simulated.filter((c) => c.supervisor === sup).map((c) => decision(sup, c.function, c.rule, c.active, c.cause));
            expect(got, `${sup}; scenario replayed:\n${text}`).toEqual(want);
        }
    });
});
