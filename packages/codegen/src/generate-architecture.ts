import { resolve } from 'node:path';
import type { LangiumDocument } from 'langium';
import type { Model } from '@contract-studio/language';
import { generateFiles } from './generators/generate-files.js';
import { architectureFromModels } from './model/from-langium.js';
import type { Architecture } from './model/architecture.js';
import { emptyReport, type GenerationReport } from './writer/report.js';
import { writeTree, type WriteTreeOptions } from './writer/write-tree.js';

/** Anything that carries a Cactal model: a Langium document, a loadWorkspace() document, or a model. */
export type ModelSource = LangiumDocument<Model> | { document: LangiumDocument<Model> } | Model;

function documentOf(s: ModelSource): LangiumDocument<Model> | undefined {
    if ('parseResult' in s) return s;
    if ('document' in s) return s.document;
    return (s as Model).$document as LangiumDocument<Model> | undefined;
}

function modelOf(s: ModelSource): Model {
    const d = documentOf(s);
    return d ? d.parseResult.value : (s as Model);
}

/**
 * Writes the architecture's C tree (docs/codegen.md, "The tree") into `outDir` (the project's
 * src-gen), merging protected regions. The tree depends only on the model and the generator, never on `outDir` or the machine:
 * the runtime is chosen at build time (docs/architecture.md, Seam 3).
 */
export function generateFromArchitecture(arch: Architecture, outDir: string, options: WriteTreeOptions = {}): GenerationReport {
    let files;
    try {
        files = generateFiles(arch);
    } catch (e) {
        const report = emptyReport();
        report.errors.push({ file: '(model)', message: `cannot generate: ${(e as Error).message}` });
        return report;
    }
    try {
        return writeTree(resolve(outDir), files, options);
    } catch (e) {
        const report = emptyReport();
        report.errors.push({ file: '(output)', message: `cannot write ${outDir}: ${(e as Error).message}` });
        return report;
    }
}

/**
 * Seam 4: generates the C tree of a checked Cactal workspace into `outDir`. Refuses (report with
 * errors, nothing written) when a document has parse, link or validation errors. `options`:
 * writeTree's (a build's generation passes `displacedCode: 'refuse'`).
 */
export function generateArchitecture(documents: ModelSource[], outDir: string, options: WriteTreeOptions = {}): GenerationReport {
    const report = emptyReport();
    const sorted = byUri(documents);
    for (const source of sorted) {
        const d = documentOf(source);
        if (!d) continue;
        const problems = [
            ...d.parseResult.lexerErrors.map((e) => ({ line: e.line ?? 0, message: e.message })),
            ...d.parseResult.parserErrors.map((e) => ({ line: e.token.startLine ?? 0, message: e.message })),
            ...(d.diagnostics ?? []).filter((x) => x.severity === 1).map((x) => ({ line: x.range.start.line + 1, message: x.message })),
        ];
        for (const p of problems) report.errors.push({ file: d.uri.fsPath, line: p.line, message: p.message });
    }
    if (report.errors.length > 0) {
        report.errors.unshift({ file: '(model)', message: 'the model has errors: nothing was generated (run `contract check` for details)' });
        return report;
    }
    return generateFromArchitecture(architectureOf(sorted), outDir, options);
}

/** The documents in the order the generator reads them (by URI): the tree never depends on the order they were loaded in. */
function byUri(documents: ModelSource[]): ModelSource[] {
    return [...documents].sort((a, b) => {
        const ua = documentOf(a)?.uri.toString() ?? '';
        const ub = documentOf(b)?.uri.toString() ?? '';
        return ua < ub ? -1 : ua > ub ? 1 : 0;
    });
}

/** The plain architecture model the generator makes of `documents` (checked ones: generateArchitecture refuses errors). */
export function architectureOf(documents: ModelSource[]): Architecture {
    return architectureFromModels(byUri(documents).map(modelOf));
}
