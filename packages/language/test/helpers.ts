/** Test helpers: build an in-memory Cactal workspace (EmptyFileSystem) and read its diagnostics. */
import { EmptyFileSystem, URI, type LangiumDocument } from 'langium';
import { createCactalServices, type CactalServices } from '../src/cactal-module.js';
import type { Model } from '../src/generated/ast.js';

export interface Built {
    services: CactalServices;
    docs: Map<string, LangiumDocument<Model>>;
    /** `file:line:col severity code message` lines, sorted (1-based). */
    lines: string[];
    diagnostics: Array<{ file: string; line: number; severity: string; code: string; message: string; data?: unknown }>;
}

const SEVERITY = ['', 'error', 'warning', 'info', 'hint'];

export function uriOf(file: string): URI {
    return URI.parse(`file:///ws/${file}`);
}

/** Parses, links and validates the given files (name -> content). */
export async function build(files: Record<string, string>, services?: CactalServices): Promise<Built> {
    const cactal = services ?? createCactalServices(EmptyFileSystem).Cactal;
    const shared = cactal.shared;
    // reusing services: drop the previous workspace first
    const previous = shared.workspace.LangiumDocuments.all.map((d) => d.uri).toArray();
    if (previous.length) await shared.workspace.DocumentBuilder.update([], previous);
    const docs = new Map<string, LangiumDocument<Model>>();
    for (const [file, text] of Object.entries(files)) {
        const doc = shared.workspace.LangiumDocumentFactory.fromString<Model>(text, uriOf(file));
        shared.workspace.LangiumDocuments.addDocument(doc);
        docs.set(file, doc);
    }
    await shared.workspace.DocumentBuilder.build([...docs.values()], { validation: true });
    const diagnostics = [...docs.entries()].flatMap(([file, doc]) => (doc.diagnostics ?? []).map((d) => ({
        file,
        line: d.range.start.line + 1,
        col: d.range.start.character + 1,
        severity: SEVERITY[d.severity ?? 1]!,
        code: String(d.code ?? (d.data as { code?: string } | undefined)?.code ?? ''),
        message: d.message,
        data: d.data
    })));
    const lines = diagnostics.map((d) => `${d.file}:${d.line}:${d.col} ${d.severity} ${d.code} ${d.message}`).sort();
    return { services: cactal, docs, lines, diagnostics };
}

/** Codes of the diagnostics of a build (with duplicates). */
export function codes(built: Built): string[] {
    return built.diagnostics.map((d) => d.code);
}

/** Parses one text; returns the model and the lexer/parser error messages. */
let parserServices: CactalServices | undefined;
export function parse(text: string): { model: Model; errors: string[] } {
    parserServices ??= createCactalServices(EmptyFileSystem).Cactal;
    const result = parserServices.parser.LangiumParser.parse<Model>(text);
    return { model: result.value, errors: [...result.lexerErrors.map((e) => e.message), ...result.parserErrors.map((e) => e.message)] };
}

/** The tutorial's datatype file, reused by many tests. */
export const TYPES = `
datatype TypeA {float i = 0.0, float j =0.0, float k=0.0};
datatype TypeB {TypeA coord = {1.0,1.0,1.0}, int frfrrrf=1};
datatype TypeC {string message, int messagetype=0, TypeA value };
datatype TypeD {string dataname, int datavalue};
function bool testit(string arg1, TypeA arg2);
function void doit(string argfirst, float argsecond);
`;
