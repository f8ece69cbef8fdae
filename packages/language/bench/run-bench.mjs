#!/usr/bin/env node
// Language benchmark: full workspace build (parse + link + validate) of the synthetic architecture,
// the incremental rebuild after a one-character change in one module file, and three editor requests
// on the built workspace: format every file, hover on a periodic schema (timing analysis), rename a
// module referenced by its schema and the scheduler configuration; and the check of a `.scenario`
// naming every module, schema and rule against that workspace; and the stdio language server's
// latency on a field-sized project with a 350-line supervisor (large-supervisor-latency.mjs).
// Writes bench/parts/language.json (repository root). Needs `npm run build -w packages/language`.
import { mkdtempSync, readFileSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { URI } from 'langium';
import { isModule, isSchema, isSupervisor, rulesOf } from '../dist/index.js';
import { loadWorkspace } from '../dist/node/index.js';
import { scenarioDiagnostics } from '../dist/lsp/scenario/scenario-diagnostics.js';
import { writeSyntheticArchitecture } from './synthetic-architecture.js';
import { measureLargeSupervisorLatency } from './large-supervisor-latency.mjs';

const FULL_RUNS = 3;
const SCENARIO_RUNS = 21;
const EDIT_RUNS = 7;
const FORMAT_RUNS = 3;
const HOVER_RUNS = 21;
const RENAME_RUNS = 5;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

/**
 * Median wall time (ms) of `runs` calls of `request`, each one the first request after a workspace
 * update (an empty `DocumentBuilder.update`, untimed, clears the per-build caches as an edit does);
 * `check` validates the first answer.
 */
async function timeRequest(builder, runs, request, check) {
    const times = [];
    for (let i = 0; i < runs; i++) {
        await builder.update([], []);
        const t0 = performance.now();
        const answer = await request();
        times.push(performance.now() - t0);
        if (i === 0) check(answer);
    }
    return Math.round(median(times) * 100) / 100;
}

function fail(message) {
    throw new Error(`language bench: ${message}`);
}

/** Format all files, hover on a periodic schema's name, rename a synchronous module (median ms, after an update each). */
async function measureEditorRequests(workspace) {
    const documents = workspace.services.shared.workspace.LangiumDocuments;
    const lsp = workspace.services.lsp;
    const builder = workspace.services.shared.workspace.DocumentBuilder;
    const docOf = (file) => documents.getDocument(URI.file(workspace.documents.find((d) => d.file === file).path));
    const all = workspace.documents.map((d) => documents.getDocument(URI.file(d.path)));
    const at = (doc, needle, delta) => {
        const offset = doc.textDocument.getText().indexOf(needle);
        if (offset < 0) fail(`'${needle}' not in ${doc.uri.path}`);
        return { textDocument: { uri: doc.uri.toString() }, position: doc.textDocument.positionAt(offset + delta) };
    };
    const formatOptions = { tabSize: 4, insertSpaces: true };
    const format_all = await timeRequest(builder, FORMAT_RUNS,
        () => all.map((doc) => lsp.Formatter.formatDocument(doc, { textDocument: { uri: doc.uri.toString() }, options: formatOptions })),
        (answers) => { if (answers.length !== all.length || !answers.every(Array.isArray)) fail('formatting did not answer for every file'); });
    const schema = docOf('schemas/periodic0.contract');
    const hover = await timeRequest(builder, HOVER_RUNS,
        () => lsp.HoverProvider.getHoverContent(schema, at(schema, 'periodic schema periodic0', 'periodic schema '.length + 2)),
        (answer) => { if (!JSON.stringify(answer ?? '').includes('utilisation')) fail(`hover on periodic0 shows no timing: ${JSON.stringify(answer)}`); });
    const module = docOf('modules/AAA.contract');
    const rename = await timeRequest(builder, RENAME_RUNS,
        () => lsp.RenameProvider.rename(module, { ...at(module, 'module AAA', 'module '.length + 1), newName: 'ZZZ' }),
        (answer) => {
            const files = Object.keys(answer?.changes ?? {}).length + (answer?.documentChanges?.length ?? 0);
            if (files < 3) fail(`renaming AAA changed ${files} files (expected its module, schema and scheduler files)`);
        });
    return { 'lsp.format_all_ms': format_all, 'lsp.hover_ms': hover, 'lsp.rename_ms': rename };
}

/**
 * A `.scenario` that names every module, schema and rule of the workspace checked against it, as
 * the language server does on each keystroke in a scenario (docs/simulation.md "Editing scenarios"):
 * parse + model checks + LSP conversion, median ms.
 */
function measureScenarioCheck(workspace) {
    const models = workspace.documents.map((d) => d.model);
    const lines = [];
    for (const m of models) {
        for (const e of m.elements) {
            if (isModule(e)) lines.push(`expect module ${e.name} running`);
            else if (isSchema(e)) lines.push(`expect schema ${e.name} active`);
            else if (isSupervisor(e)) for (const f of e.functions) for (const r of rulesOf(f)) lines.push(`expect rule ${e.name}.${f.name}.${r.name} active`);
        }
    }
    const text = lines.join('\n');
    const times = [];
    for (let i = 0; i < SCENARIO_RUNS; i++) {
        const t0 = performance.now();
        const diagnostics = scenarioDiagnostics(text, { models });
        times.push(performance.now() - t0);
        if (diagnostics.length) fail(`the generated scenario has ${diagnostics.length} diagnostics, first: ${diagnostics[0].message}`);
    }
    return { 'lsp.scenario_check_ms': Math.round(median(times) * 100) / 100, 'lsp.scenario_lines': lines.length };
}

const dir = mkdtempSync(join(tmpdir(), 'cactal-bench-'));
try {
    const files = writeSyntheticArchitecture(dir);
    const fullTimes = [];
    const fullCpu = [];
    let workspace;
    for (let i = 0; i < FULL_RUNS; i++) {
        const t0 = performance.now();
        const c0 = process.cpuUsage();
        workspace = await loadWorkspace(dir);
        fullTimes.push(performance.now() - t0);
        const c = process.cpuUsage(c0);
        fullCpu.push((c.user + c.system) / 1000);
    }
    // 1,000 modules are more processes than one run starts (architecture-too-many-processes,
    // docs/language-reference.md §7): the one error the benchmark's workspace is meant to have
    const errors = workspace.diagnostics.filter((d) => d.severity === 'error' && d.code !== 'architecture-too-many-processes');
    if (errors.length) {
        console.error(`synthetic architecture has ${errors.length} errors, first: ${JSON.stringify(errors[0])}`);
        process.exit(1);
    }
    const warnings = workspace.diagnostics.filter((d) => d.severity === 'warning').length;

    const lsp = await measureEditorRequests(workspace);
    const scenario = measureScenarioCheck(workspace);
    const largeSupervisor = await measureLargeSupervisorLatency();

    // incremental: one character of one module file (C=10us <-> C=20us), rebuilt through the DocumentBuilder
    const target = workspace.documents.find((d) => d.file.startsWith('modules/'));
    const original = readFileSync(target.path, 'utf8');
    const builder = workspace.services.shared.workspace.DocumentBuilder;
    const editTimes = [];
    const editCpu = [];
    for (let i = 0; i < EDIT_RUNS; i++) {
        writeFileSync(target.path, i % 2 === 0 ? original.replace('C=10us', 'C=20us') : original);
        const t0 = performance.now();
        const c0 = process.cpuUsage();
        await builder.update([URI.file(target.path)], []);
        editTimes.push(performance.now() - t0);
        const c = process.cpuUsage(c0);
        editCpu.push((c.user + c.system) / 1000);
    }
    const after = workspace.services.shared.workspace.LangiumDocuments.getDocument(URI.file(target.path));
    const editErrors = (after?.diagnostics ?? []).filter((d) => d.severity === 1).length;

    const result = {
        'lsp.workspace_build_ms': Math.round(median(fullTimes)),
        'lsp.workspace_build_first_ms': Math.round(fullTimes[0]),
        'lsp.incremental_edit_ms': Math.round(median(editTimes) * 10) / 10,
        // CPU time of the process (user + system, all threads): tells contention apart from cost on a shared machine
        'lsp.workspace_build_cpu_ms': Math.round(median(fullCpu)),
        'lsp.incremental_edit_cpu_ms': Math.round(median(editCpu) * 10) / 10,
        ...lsp,
        ...scenario,
        ...largeSupervisor,
        'lsp.workspace_files': files,
        'lsp.workspace_errors': errors.length + editErrors,
        'lsp.workspace_warnings': warnings
    };
    const partsDir = fileURLToPath(new URL('../../../bench/parts/', import.meta.url));
    mkdirSync(partsDir, { recursive: true });
    writeFileSync(join(partsDir, 'language.json'), JSON.stringify(result, null, 2) + '\n');
    console.log(JSON.stringify(result));
} finally {
    rmSync(dir, { recursive: true, force: true });
}
