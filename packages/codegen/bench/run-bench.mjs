#!/usr/bin/env node
// Codegen benchmark: Generate All of the 1,000-module synthetic architecture (the language package's
// generator: 200 schemas x 5 modules, 20 supervisors), then a regeneration of the unchanged model.
// Writes bench/parts/codegen.json (repository root). Needs `npm run build` of language and codegen.
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadWorkspace } from '@contract-studio/language/node';
import { writeSyntheticArchitecture } from '@contract-studio/language/bench';
import { generateArchitecture } from '../dist/index.js';

const RUNS = 3;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const root = fileURLToPath(new URL('../../../', import.meta.url));

const dir = mkdtempSync(join(tmpdir(), 'codegen-bench-'));
try {
    writeSyntheticArchitecture(dir);
    const workspace = await loadWorkspace(dir);
    const errors = workspace.diagnostics.filter((d) => d.severity === 'error');
    if (errors.length) throw new Error(`synthetic architecture has ${errors.length} errors, first: ${JSON.stringify(errors[0])}`);
    const modules = workspace.documents.filter((d) => d.model.elements.some((e) => e.$type === 'Module')).length;

    const generateTimes = [];
    let out;
    let report;
    for (let i = 0; i < RUNS; i++) {
        out = join(dir, `src-gen-${i}`);
        const t0 = performance.now();
        report = generateArchitecture(workspace.documents, out);
        generateTimes.push(performance.now() - t0);
        if (report.errors.length) throw new Error(`generation failed: ${JSON.stringify(report.errors[0])}`);
    }
    const files = report.created.length;
    const noopTimes = [];
    let written = 0;
    for (let i = 0; i < RUNS; i++) {
        const t0 = performance.now();
        const again = generateArchitecture(workspace.documents, out);
        noopTimes.push(performance.now() - t0);
        written = Math.max(written, again.filesWritten);
    }
    const result = {
        'codegen.modules': modules,
        'codegen.files': files,
        'codegen.generate_ms': Math.round(median(generateTimes)),
        'codegen.regenerate_noop_ms': Math.round(median(noopTimes)),
        'codegen.regenerate_noop_files_written': written,
    };
    mkdirSync(join(root, 'bench', 'parts'), { recursive: true });
    writeFileSync(join(root, 'bench', 'parts', 'codegen.json'), JSON.stringify(result, null, 2) + '\n');
    console.log(JSON.stringify(result));
} finally {
    rmSync(dir, { recursive: true, force: true });
}
