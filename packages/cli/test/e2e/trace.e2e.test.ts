/**
 * The run-time trace of a real run (docs/runtime-api.md "Trace records"): the tutorial runs 5 s
 * in bwrap with `contract run --trace`, then `contract trace` tells it. Every rule change of SUP
 * is told with its cause (FIRST active on elapsed=1ms, then SECOND active on MAA's
 * "disconnected"), and the JSON records are the CSV records, none lost, none reordered.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runFigures } from '../../src/commands/run-schemas.js';
import { readLogs } from './csv-log.js';
import { contract, seededScratchCopy, type CliRun, type Scratch } from './harness.js';

interface JsonRecord {
    kind: string;
    monoNs: string;
    module: string;
    detail: string;
    function?: string;
    rule?: string;
    active?: boolean;
    cause?: string;
}

let scratch: Scratch;
let run: CliRun;
let story: CliRun;
let json: CliRun;
const traceFile = () => join(scratch.root, 'run.jsonl');

beforeAll(async () => {
    scratch = await seededScratchCopy('tutorial');
    run = contract(['run', 'tutorial', '--sandbox', 'bwrap', '--duration', '5s', '--logs', scratch.logs, '--trace', traceFile(), '--format', 'json'], scratch);
    story = contract(['trace', scratch.logs], scratch);
    json = contract(['trace', scratch.logs, '--format', 'json'], scratch);
}, 300_000);
afterAll(() => scratch?.dispose());

/** The CSV records of the logs, each file in its own order (header excluded). */
function csvRecordsByModule(): Map<string, string[]> {
    const out = new Map<string, string[]>();
    for (const r of readLogs(scratch.logs)) out.set(r.module, [...(out.get(r.module) ?? []), `${r.mono} ${r.event} ${r.detail}`]);
    return out;
}

describe('contract trace on a recorded tutorial run (bwrap)', () => {
    it('the run wrote its trace', () => {
        expect(run.code).toBe(0);
        expect(JSON.parse(run.stdout).trace.records).toBeGreaterThan(0);
        // the trace file is the logs' records as JSON lines, whether written live or rewritten at the end
        expect(readFileSync(traceFile(), 'utf8')).toBe(json.stdout);
        // its lines: the records, and the launcher's end lines of the modules (`launcher_line`, no record)
        expect(JSON.parse(run.stdout).trace.records).toBe(json.stdout.trim().split('\n').filter((l) => !l.includes('"kind":"launcher_line"')).length);
    });

    it("gives the schema's figures told on the trace file's check, as a read of the saved logs of their own gives them", async () => {
        const out = JSON.parse(run.stdout) as { logs: string[]; schemas: { schema: string; completedCycles: number }[]; eventHandling: { module: string; handled: number }[] };
        // (schemaCommande2 too when SUP's SECOND came in time to activate it)
        expect(out.schemas.find((s) => s.schema === 'schemaCommande1')?.completedCycles).toBeGreaterThan(0);
        const figures = await runFigures(scratch.logs, out.logs);
        expect(out.schemas).toEqual(figures?.schemas);
        expect(out.eventHandling).toEqual(figures?.eventHandling);
        // MAB's handler of the events MAA:0 =* MAB:0 brings it (its event_handled records)
        expect(out.eventHandling.find((m) => m.module === 'MAB')?.handled).toBeGreaterThan(0);
    });

    it('tells every rule change of SUP with its cause: FIRST on elapsed=1ms, SECOND after MAA\'s "disconnected"', () => {
        expect(story.code).toBe(0);
        const records = json.stdout.trim().split('\n').map((l) => JSON.parse(l) as JsonRecord).filter((r) => (r.kind as string) !== 'launcher_line');
        const changes = records.filter((r) => r.kind === 'sup_rule' && r.module === 'SUP');
        // one sup_rule record per readable `rule F.R active|inactive` line of SUP, in the same order
        const lines = readLogs(scratch.logs).filter((r) => r.module === 'SUP' && r.event === 'supervisor' && /^rule \S+ (in)?active$/.test(r.detail)).map((r) => r.detail);
        expect(changes.map((c) => `rule ${c.function}.${c.rule} ${c.active ? 'active' : 'inactive'}`)).toEqual(lines);
        const told = story.stdout.split('\n').filter((l) => / SUP +rule /.test(l));
        expect(told.length).toBe(changes.length);
        changes.forEach((c, i) => expect(told[i]).toMatch(new RegExp(`rule ${c.function}\\.${c.rule} ${c.active ? 'active' : 'inactive'} +<- \\S`)));
        const first = told.findIndex((l) => /rule action\.FIRST active +<- elapsed=1ms$/.test(l));
        const firstEnds = told.findIndex((l) => /rule action\.FIRST inactive +<- MAA:2 = "disconnected"$/.test(l));
        const second = told.findIndex((l) => /rule action\.SECOND active +<- MAA:2 = "disconnected"$/.test(l));
        expect(first).toBeGreaterThanOrEqual(0);
        expect(firstEnds).toBeGreaterThan(first);
        expect(second).toBeGreaterThan(firstEnds);
        // MAA's TypeC message, field by field (the tutorial's MAA sends "FUFU", type 1, a growing value)
        expect(told.filter((l) => /rule action\.RECEPTION active +<- MAA:0 = \{message="FUFU",messagetype=1,value=\{i=[\d.]+,j=[\d.]+,k=[\d.]+\}\}$/.test(l)).length).toBeGreaterThanOrEqual(1);
    });

    it('tells the schema activations and ORD\'s releases of the run', () => {
        expect(story.stdout).toMatch(/ ORD +activate schemaCommande1 \(activation #\d+ from SUP\)\n/);
        expect(story.stdout).toMatch(/\d+ records: [1-9]\d* module releases, [1-9]\d* completed cycles, /);
    });

    it('gives one JSON record per CSV record, none unknown, in time order, each module\'s in its file order', () => {
        expect(json.code).toBe(0);
        const records = json.stdout.trim().split('\n').map((l) => JSON.parse(l) as JsonRecord).filter((r) => (r.kind as string) !== 'launcher_line');
        const csv = csvRecordsByModule();
        expect(records.length).toBe([...csv.values()].reduce((n, l) => n + l.length, 0));
        expect(records.filter((r) => r.kind === 'unknown')).toEqual([]);
        for (let i = 1; i < records.length; i++) expect(BigInt(records[i]!.monoNs) >= BigInt(records[i - 1]!.monoNs)).toBe(true);
        for (const [module, lines] of csv) {
            expect(records.filter((r) => r.module === module).map((r) => `${r.monoNs} ${r.kind} ${r.detail}`), module).toEqual(lines);
        }
        expect(readFileSync(traceFile(), 'utf8')).toBe(json.stdout);
    });
});
