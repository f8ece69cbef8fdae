/** SPEC §2.1: imports (missing file, cycles, unused, duplicates, position) and file content. */
import { AstUtils, UriUtils, type AstNode, type LangiumDocument, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isActivateSchema, isDataType, isFunctionPrototype, isModel, isSchedulerConfiguration,
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

class ImportChecker {
    private readonly imports: ImportResolver;

    constructor(private readonly services: CactalServices) {
        this.imports = services.imports.ImportResolver;
    }

    checkModel(model: Model, accept: ValidationAcceptor): void {
        const document = AstUtils.getDocument(model);
        const docs = this.services.shared.workspace.LangiumDocuments;
        const seen = new Map<string, Import>();
        const firstElementOffset = model.elements[0]?.$cstNode?.offset ?? Number.POSITIVE_INFINITY;
        const used = this.usedUris(model, document);

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
                report(accept, ImportCodes['import-missing-file'],
                    `Imported file "${imp.path}" does not exist (resolved relative to this file: ${UriUtils.relative(UriUtils.dirname(document.uri), uri)}).`,
                    { node: imp, property: 'path' });
                continue;
            }
            const cycle = this.findCycle(document, docs.getDocument(uri)!);
            if (cycle) {
                const names = [document, ...cycle].map((d) => UriUtils.basename(d.uri));
                report(accept, ImportCodes['import-cycle'],
                    `Import cycle: ${names.join(' -> ')}. Imports are not transitive, so no file needs to import a file that imports it back.`,
                    { node: imp, property: 'path' });
            }
            if (!used.has(key)) {
                report(accept, ImportCodes['import-unused'], `Nothing from "${imp.path}" is used in this file.`, { node: imp, property: 'path', tags: [1] });
            }
        }
        this.checkContent(model, accept);
    }

    /** A path of documents from `start` back to `origin` through imports (ending with origin), if any. */
    private findCycle(origin: LangiumDocument, start: LangiumDocument): LangiumDocument[] | undefined {
        const originKey = origin.uri.toString();
        const visited = new Set<string>();
        const docs = this.services.shared.workspace.LangiumDocuments;
        const dfs = (doc: LangiumDocument, path: LangiumDocument[]): LangiumDocument[] | undefined => {
            const key = doc.uri.toString();
            if (key === originKey) return path;
            if (visited.has(key)) return undefined;
            visited.add(key);
            const model = doc.parseResult.value;
            if (!isModel(model)) return undefined;
            for (const imp of model.imports) {
                if (imp.path === undefined) continue;
                const uri = this.imports.resolvePath(doc.uri, imp.path);
                if (!docs.hasDocument(uri)) continue;
                const next = docs.getDocument(uri)!;
                const found = dfs(next, [...path, next]);
                if (found) return found;
            }
            return undefined;
        };
        return dfs(start, [start]);
    }

    /**
     * Files this one uses: those defining what it refers to, those defining what the referred
     * elements themselves refer to (a schema's modules, a module's types), and the scheduler
     * configuration's file when this file activates a periodic schema.
     */
    private usedUris(model: Model, document: LangiumDocument): Set<string> {
        const used = new Set<string>();
        const own = document.uri.toString();
        const referenced = new Set<AstNode>();
        let activatesPeriodic = false;
        for (const node of AstUtils.streamAst(model)) {
            if (isActivateSchema(node) && node.schema?.ref?.kind === 'periodic') activatesPeriodic = true;
            for (const refInfo of AstUtils.streamReferences(node)) {
                const target = (refInfo.reference as { ref?: AstNode }).ref;
                if (!target) continue;
                const targetDoc = AstUtils.getDocument(target);
                if (targetDoc.uri.toString() === own) continue;
                used.add(targetDoc.uri.toString());
                referenced.add(topLevelOf(target));
            }
        }
        for (const element of referenced) {
            for (const node of AstUtils.streamAst(element)) {
                for (const refInfo of AstUtils.streamReferences(node)) {
                    const target = (refInfo.reference as { ref?: AstNode }).ref;
                    if (target) used.add(AstUtils.getDocument(target).uri.toString());
                }
            }
        }
        if (activatesPeriodic) {
            const docs = this.services.shared.workspace.LangiumDocuments;
            for (const imp of model.imports) {
                if (imp.path === undefined) continue;
                const uri = this.imports.resolvePath(document.uri, imp.path);
                const doc = docs.hasDocument(uri) ? docs.getDocument(uri) : undefined;
                const m = doc?.parseResult.value;
                if (isModel(m) && m.elements.some(isSchedulerConfiguration)) used.add(uri.toString());
            }
        }
        return used;
    }

    /** Types file (datatypes + functions) or exactly one module/schema/scheduler configuration/supervisor. */
    private checkContent(model: Model, accept: ValidationAcceptor): void {
        const typeDefs = model.elements.filter((e) => isDataType(e) || isFunctionPrototype(e));
        const others = model.elements.filter((e) => !isDataType(e) && !isFunctionPrototype(e));
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

function topLevelOf(node: AstNode): AstNode {
    let current = node;
    while (current.$container && !isModel(current.$container)) current = current.$container;
    return current;
}

function firstKeyword(node: AstNode): string {
    switch (node.$type) {
        case 'Module': return 'module';
        case 'Schema': return 'schema';
        case 'SchedulerConfiguration': return 'scheduler';
        case 'Supervisor': return 'supervisor';
        case 'DataType': return 'datatype';
        default: return 'function';
    }
}
