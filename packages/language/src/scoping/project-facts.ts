/**
 * Project-wide facts: what one file contributes to the diagnostics of files that do not refer to
 * it (docs/language-reference.md §1–6 checks that look at the whole project or follow cycles through several files).
 *
 * | fact | diagnostics of other files that depend on it |
 * |---|---|
 * | `schedulers` (how many scheduler configurations) | `scheduler-missing` (periodic schemas), `scheduler-duplicate` (configurations) |
 * | `scheduledSchemas` (the schemas a configuration lists) | `scheduler-schema-unlisted` (supervisors) |
 * | `activations` (supervisor -> activated supervisors) | `supervisor-activation-cycle` |
 * | `datatypeEdges` (datatype -> field datatypes) | `type-recursive` |
 * | `imports` (import paths) | `import-cycle`, and the file-name suggestion of `import-missing-file` |
 *
 * Duplicate names (`*-name-duplicate`) are handled by the document builder from the index.
 * `projectDependents` compares the facts of the changed files before and after a change and names
 * the other files to revalidate: only when a fact really changed, so an ordinary edit costs nothing.
 */
import { UriUtils, type LangiumDocument } from 'langium';
import {
    isActivateSupervisor, isDataType, isModel, isSchedulerConfiguration, isSchema, isSupervisor,
    type Model
} from '../generated/ast.js';
import { rulesOf, scheduledSchemasOf } from '../model/blocks.js';

/** What one file contributes to project-wide checks (undefined: nothing of that kind). */
export interface DocumentFacts {
    schedulers?: number;
    scheduledSchemas?: string;
    activations?: string;
    datatypeEdges?: string;
    imports: string;
}

const NO_FACTS: DocumentFacts = { imports: '' };

/** The facts of a document (its current AST); a deleted or unparsed document has none. */
export function documentFacts(document: LangiumDocument | undefined): DocumentFacts {
    const model = document?.parseResult?.value;
    if (!isModel(model)) return NO_FACTS;
    return {
        schedulers: model.elements.filter(isSchedulerConfiguration).length || undefined,
        scheduledSchemas: scheduledSchemasFact(model),
        activations: activationsFact(model),
        datatypeEdges: datatypeEdgesFact(model),
        imports: model.imports.map((i) => i.path ?? '').join('\n')
    };
}

function scheduledSchemasFact(model: Model): string | undefined {
    const configs = model.elements.filter(isSchedulerConfiguration);
    if (configs.length === 0) return undefined;
    return configs.map((c) => scheduledSchemasOf(c).map((r) => r.$refText).join(',')).join(';');
}

function activationsFact(model: Model): string | undefined {
    const supervisors = model.elements.filter(isSupervisor);
    if (supervisors.length === 0) return undefined;
    return supervisors.map((s) => {
        // an activation is a rule's action: the rules' actions only, not every node of the conditions
        const targets = s.functions.flatMap((f) => rulesOf(f).flatMap((r) => r.actions.filter(isActivateSupervisor).map((a) => a.supervisor?.$refText ?? '')));
        return `${s.name}>${[...new Set(targets)].sort().join(',')}`;
    }).join(';');
}

function datatypeEdgesFact(model: Model): string | undefined {
    const datatypes = model.elements.filter(isDataType);
    if (datatypes.length === 0) return undefined;
    return datatypes.map((d) => `${d.name}>${d.fields.map((f) => f.type?.datatype?.$refText ?? '').filter((t) => t).join(',')}`).join(';');
}

/** The facts of the given documents, by URI string. */
export function factsOf(documents: Map<string, LangiumDocument | undefined>): Map<string, DocumentFacts> {
    return new Map([...documents].map(([uri, doc]) => [uri, documentFacts(doc)]));
}

/**
 * The documents (other than the changed ones) whose project-wide diagnostics may have changed,
 * given the facts of the changed documents before and after the change.
 */
export function projectDependents(
    before: Map<string, DocumentFacts>,
    after: Map<string, DocumentFacts>,
    all: LangiumDocument[]
): Set<LangiumDocument> {
    const changed = (key: keyof DocumentFacts) => [...before.keys()].some((uri) => before.get(uri)?.[key] !== after.get(uri)?.[key]);
    const others = all.filter((doc) => !before.has(doc.uri.toString()));
    const result = new Set<LangiumDocument>();
    const addWhere = (predicate: (model: Model, doc: LangiumDocument) => boolean) => {
        for (const doc of others) {
            const model = doc.parseResult?.value;
            if (isModel(model) && predicate(model, doc)) result.add(doc);
        }
    };
    if (changed('schedulers')) addWhere((m) => m.elements.some((e) => isSchedulerConfiguration(e) || (isSchema(e) && e.kind === 'periodic')));
    if (changed('scheduledSchemas')) addWhere((m) => m.elements.some(isSupervisor));
    if (changed('activations')) addWhere((m) => m.elements.some(isSupervisor));
    if (changed('datatypeEdges')) addWhere((m) => m.elements.some(isDataType));
    const filesAddedOrDeleted = [...before.keys()].some((uri) => (before.get(uri) === NO_FACTS) !== (after.get(uri) === NO_FACTS));
    if (changed('imports') || filesAddedOrDeleted) {
        // a cycle that is gone: its files reported it; a new cycle: it goes through a changed file
        addWhere((_, doc) => hasDiagnostic(doc, 'import-cycle') || hasDiagnostic(doc, 'import-missing-file'));
        for (const doc of importCycleMembers([...before.keys()], all)) {
            if (!before.has(doc.uri.toString())) result.add(doc);
        }
    }
    return result;
}

function hasDiagnostic(doc: LangiumDocument, code: string): boolean {
    return doc.diagnostics?.some((d) => d.code === code) ?? false;
}

/** Documents on an import cycle through one of `uris`: reachable from it and reaching it. */
function importCycleMembers(uris: string[], all: LangiumDocument[]): LangiumDocument[] {
    const byUri = new Map(all.map((d) => [d.uri.toString(), d]));
    const forward = new Map<string, string[]>();
    const backward = new Map<string, string[]>();
    for (const doc of all) {
        const model = doc.parseResult?.value;
        if (!isModel(model)) continue;
        const from = doc.uri.toString();
        const dir = UriUtils.dirname(doc.uri);
        for (const imp of model.imports) {
            if (imp.path === undefined) continue;
            const to = UriUtils.resolvePath(dir, imp.path).toString();
            if (!byUri.has(to)) continue;
            forward.set(from, [...(forward.get(from) ?? []), to]);
            backward.set(to, [...(backward.get(to) ?? []), from]);
        }
    }
    const members = new Set<string>();
    for (const start of uris) {
        const ahead = reachable(start, forward);
        for (const uri of reachable(start, backward)) if (ahead.has(uri)) members.add(uri);
    }
    return [...members].map((u) => byUri.get(u)!).filter((d) => d !== undefined);
}

function reachable(start: string, edges: Map<string, string[]>): Set<string> {
    const seen = new Set<string>();
    const todo = [...(edges.get(start) ?? [])];
    while (todo.length) {
        const next = todo.pop()!;
        if (seen.has(next)) continue;
        seen.add(next);
        todo.push(...(edges.get(next) ?? []));
    }
    return seen;
}
