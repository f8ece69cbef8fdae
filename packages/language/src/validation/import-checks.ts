/** docs/language-reference.md §1: imports (missing file, cycles, unused, duplicates, position) and file content. */
import { AstUtils, URI, UriUtils, WorkspaceCache, type AstNode, type LangiumDocument, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isActivateSchema, isConstant, isDataType, isEnumType, isFunctionPrototype, isModel, isSchedulerConfiguration,
    type CactalAstType, type Import, type Model
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import type { ImportResolver } from '../scoping/import-resolver.js';
import { ImportCodes } from './codes/imports.js';
import { report } from './report.js';

export function importChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const checker = new ImportChecker(services);
    return { Model: (model, accept) => checker.checkModel(model, accept) };
}

function hasSyntaxError(document: LangiumDocument | undefined): boolean {
    return !!document && (document.parseResult.parserErrors.length > 0 || document.parseResult.lexerErrors.length > 0);
}

interface ImportGraph {
    edges: Map<string, string[]>;
    /** file URI -> id of its strongly connected component */
    component: Map<string, number>;
}

class ImportChecker {
    private readonly imports: ImportResolver;
    private readonly graphCache: WorkspaceCache<string, ImportGraph>;
    private readonly outgoingCache: WorkspaceCache<string, Set<string>>;
    private readonly byUriCache: WorkspaceCache<string, Map<string, LangiumDocument>>;

    constructor(private readonly services: CactalServices) {
        this.imports = services.imports.ImportResolver;
        this.graphCache = new WorkspaceCache(services.shared);
        this.outgoingCache = new WorkspaceCache(services.shared);
        this.byUriCache = new WorkspaceCache(services.shared);
    }

    checkModel(model: Model, accept: ValidationAcceptor): void {
        const document = AstUtils.getDocument(model);
        const docs = this.services.shared.workspace.LangiumDocuments;
        const seen = new Map<string, Import>();
        const firstElementOffset = model.elements[0]?.$cstNode?.offset ?? Number.POSITIVE_INFINITY;
        const importUris = model.imports.filter((i) => i.path !== undefined).map((i) => this.imports.resolveImport(i).toString());
        const used = this.usedUris(model, document, importUris);

        for (const imp of model.imports) {
            if (imp.path === undefined) continue;
            const uri = this.imports.resolveImport(imp);
            const key = uri.toString();
            if ((imp.$cstNode?.offset ?? 0) > firstElementOffset) {
                report(accept, ImportCodes['import-not-at-top'], `Imports belong at the top of the file, before any definition: move import "${imp.path}" up.`, { node: imp });
            }
            if (key === document.uri.toString()) {
                report(accept, ImportCodes['import-self'], `This file imports itself; remove import "${imp.path}".`, { node: imp, property: 'path' });
                continue;
            }
            if (seen.has(key)) {
                report(accept, ImportCodes['import-duplicate'], `"${imp.path}" is already imported above; remove this import.`, { node: imp, property: 'path' });
                continue;
            }
            seen.set(key, imp);
            if (!docs.hasDocument(uri)) {
                const suggestion = this.similarFile(document, uri);
                report(accept, ImportCodes['import-missing-file'],
                    `Imported file "${imp.path}" does not exist; paths are relative to the importing file's folder${suggestion ? `. Did you mean "${suggestion}"?` : '.'}`,
                    { node: imp, property: 'path', data: suggestion ? { suggestion } : {} });
                continue;
            }
            // a syntax error here or there: the recovery may have lost the use or the definition (and the quick fix would remove a needed import)
            const unused = !used.has(key) && !hasSyntaxError(document) && !hasSyntaxError(docs.getDocument(uri));
            if (!unused) continue;
            // a cycle of imports each used is two (or more) files using each other's names, which must import each
            // other: nothing to fix. The import of nothing used that closes a cycle is said there, the one to remove.
            const cycle = this.findCycle(document.uri.toString(), key);
            if (cycle) {
                const names = [document.uri.toString(), ...cycle].map((u) => UriUtils.basename(URI.parse(u)));
                report(accept, ImportCodes['import-cycle'],
                    `Import cycle: ${names.join(' -> ')}, and nothing from "${imp.path}" is used in this file: remove this import (imports are not transitive: a file imports only the files whose names it uses).`,
                    { node: imp, property: 'path' });
            }
            report(accept, ImportCodes['import-unused'], `Nothing from "${imp.path}" is used in this file.`, { node: imp, property: 'path', tags: [1] });
        }
        this.checkContent(model, accept);
    }

    /** The import graph of the workspace with its strongly connected components (cached per build). */
    private graph(): ImportGraph {
        return this.graphCache.get('graph', () => {
            const byUri = this.documentsByUri();
            const edges = new Map<string, string[]>();
            for (const [uri, doc] of byUri) {
                const model = doc.parseResult.value;
                const targets = isModel(model) ? [...this.imports.visibleUris(model)].filter((u) => u !== uri && byUri.has(u)) : [];
                edges.set(uri, targets);
            }
            return { edges, component: stronglyConnectedComponents(edges) };
        });
    }

    /** A path of file URIs from `start` back to `origin` (both included) inside their import cycle. */
    private findCycle(origin: string, start: string): string[] | undefined {
        const { edges, component } = this.graph();
        const scc = component.get(origin);
        if (scc === undefined || component.get(start) !== scc) return undefined;
        const previous = new Map<string, string>([[start, start]]);
        const queue = [start];
        while (queue.length) {
            const current = queue.shift()!;
            for (const next of edges.get(current) ?? []) {
                if (component.get(next) !== scc || previous.has(next)) continue;
                previous.set(next, current);
                if (next === origin) {
                    const path = [origin];
                    let cur = origin;
                    while (cur !== start) { cur = previous.get(cur)!; path.unshift(cur); }
                    return path;
                }
                queue.push(next);
            }
        }
        return undefined;
    }

    /** Files the document's references point to (cached per build). */
    private outgoing(document: LangiumDocument): Set<string> {
        return this.outgoingCache.get(document.uri.toString(), () => {
            const out = new Set<string>();
            for (const reference of document.references) {
                const target = (reference as { ref?: AstNode }).ref;
                if (target) out.add(AstUtils.getDocument(target).uri.toString());
            }
            return out;
        });
    }

    /**
     * Files this one uses: those defining what it refers to, those the files of the referred
     * elements themselves refer to (a schema's modules, a module's types), and the scheduler
     * configuration's file when this file activates a periodic schema.
     */
    private usedUris(model: Model, document: LangiumDocument, importUris: string[]): Set<string> {
        const own = document.uri.toString();
        const direct = this.outgoing(document);
        const used = new Set<string>([...direct].filter((u) => u !== own));
        const candidates = importUris.filter((u) => !used.has(u));
        if (candidates.length === 0) return used;
        // second level: what the referred elements' files refer to
        const byUri = this.documentsByUri();
        for (const uri of [...used]) {
            const doc = byUri.get(uri);
            if (doc) for (const second of this.outgoing(doc)) used.add(second);
        }
        if (candidates.some((u) => !used.has(u)) && AstUtils.streamAst(model).some((n) => isActivateSchema(n) && n.schema?.ref?.kind === 'periodic')) {
            for (const uri of candidates) {
                const m = byUri.get(uri)?.parseResult.value;
                if (isModel(m) && m.elements.some(isSchedulerConfiguration)) used.add(uri);
            }
        }
        return used;
    }

    /** A file of the importer's project with the same name as a missing import, as a path relative to the importer. */
    private similarFile(document: LangiumDocument, missing: URI): string | undefined {
        const name = UriUtils.basename(missing);
        for (const [, doc] of this.documentsByUri()) {
            if (doc !== document && UriUtils.basename(doc.uri) === name && this.services.projects.Projects.sameProject(doc.uri, document.uri)) return this.imports.relativeImportPath(document.uri, doc.uri);
        }
        return undefined;
    }

    /** The workspace's documents by URI string (cached per build). */
    private documentsByUri(): Map<string, LangiumDocument> {
        return this.byUriCache.get('all', () => new Map(this.services.shared.workspace.LangiumDocuments.all.map((d) => [d.uri.toString(), d] as const).toArray()));
    }

    /** Types file (datatypes, enumerations, constants, functions) or exactly one module/schema/scheduler configuration/supervisor. */
    private checkContent(model: Model, accept: ValidationAcceptor): void {
        const isTypeDef = (e: AstNode) => isDataType(e) || isFunctionPrototype(e) || isEnumType(e) || isConstant(e);
        const typeDefs = model.elements.filter(isTypeDef);
        const others = model.elements.filter((e) => !isTypeDef(e));
        if (others.length === 0) return;
        const describe = (e: AstNode) => e.$type === 'SchedulerConfiguration' ? 'scheduler configuration' : e.$type.toLowerCase();
        if (typeDefs.length > 0) {
            report(accept, ImportCodes['file-mixed-content'],
                `This file mixes type definitions with a ${describe(others[0]!)}: put datatypes and functions in their own file and import it.`,
                { node: others[0]!, keyword: firstKeyword(others[0]!) });
        }
        for (const extra of others.slice(1)) {
            report(accept, ImportCodes['file-mixed-content'],
                `A file holds exactly one module, schema, scheduler configuration or supervisor: move this ${describe(extra)} to its own file.`,
                { node: extra, keyword: firstKeyword(extra) });
        }
    }
}

/** Tarjan's algorithm (iterative): node -> component id. */
export function stronglyConnectedComponents(edges: Map<string, string[]>): Map<string, number> {
    const index = new Map<string, number>();
    const low = new Map<string, number>();
    const onStack = new Set<string>();
    const stack: string[] = [];
    const component = new Map<string, number>();
    let counter = 0;
    let components = 0;
    for (const root of edges.keys()) {
        if (index.has(root)) continue;
        const work: Array<{ node: string; next: number }> = [{ node: root, next: 0 }];
        index.set(root, counter); low.set(root, counter); counter++;
        stack.push(root); onStack.add(root);
        while (work.length) {
            const frame = work[work.length - 1]!;
            const targets = edges.get(frame.node) ?? [];
            if (frame.next < targets.length) {
                const t = targets[frame.next++]!;
                if (!edges.has(t)) continue;
                if (!index.has(t)) {
                    index.set(t, counter); low.set(t, counter); counter++;
                    stack.push(t); onStack.add(t);
                    work.push({ node: t, next: 0 });
                } else if (onStack.has(t)) {
                    low.set(frame.node, Math.min(low.get(frame.node)!, index.get(t)!));
                }
                continue;
            }
            work.pop();
            if (work.length) {
                const parent = work[work.length - 1]!.node;
                low.set(parent, Math.min(low.get(parent)!, low.get(frame.node)!));
            }
            if (low.get(frame.node) === index.get(frame.node)) {
                let member: string;
                do {
                    member = stack.pop()!;
                    onStack.delete(member);
                    component.set(member, components);
                } while (member !== frame.node);
                components++;
            }
        }
    }
    return component;
}

function firstKeyword(node: AstNode): string {
    switch (node.$type) {
        case 'Module': return 'module';
        case 'Schema': return 'schema';
        case 'SchedulerConfiguration': return 'scheduler';
        case 'Supervisor': return 'supervisor';
        case 'DataType': return 'datatype';
        case 'EnumType': return 'enum';
        case 'Constant': return 'const';
        default: return 'function';
    }
}
