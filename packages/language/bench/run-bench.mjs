#!/usr/bin/env node
// Language benchmark: full workspace build (parse + link + validate) of the synthetic architecture
// and the incremental rebuild after a one-character change in one module file.
// Writes bench/parts/language.json (repository root). Needs `npm run build -w packages/language`.
import { mkdtempSync, readFileSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { URI } from 'langium';
import { loadWorkspace } from '../dist/node/index.js';
import { writeSyntheticArchitecture } from './synthetic-architecture.js';

const FULL_RUNS = 3;
const EDIT_RUNS = 7;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

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
    const errors = workspace.diagnostics.filter((d) => d.severity === 'error');
    if (errors.length) {
        console.error(`synthetic architecture has ${errors.length} errors, first: ${JSON.stringify(errors[0])}`);
        process.exit(1);
    }
    const warnings = workspace.diagnostics.filter((d) => d.severity === 'warning').length;

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
