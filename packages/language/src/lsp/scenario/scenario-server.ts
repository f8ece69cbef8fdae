/**
 * `.scenario` files in the Cactal language server (docs/simulation.md "Editing scenarios"), for
 * the stdio server (`contract-language-server`) and the web IDE's worker alike:
 * - diagnostics: on open/change of a scenario, and after every workspace build (a `.contract`
 *   changed), the scenario is parsed and checked against its project (`scenario-project.ts`) with
 *   the simulator's own code, and published;
 * - completion and hover for scenario URIs; every other request about a scenario gets an empty
 *   answer instead of Langium's "no services for this file".
 * Call `addScenarioSupport(shared)` before `startLanguageServer(shared)`: it routes the request
 * handlers Langium registers then.
 */
import { DocumentState, type LangiumSharedCoreServices } from 'langium';
import type { LangiumSharedServices } from 'langium/lsp';
import type { Connection } from 'vscode-languageserver';
import type { CompletionParams, Diagnostic, HoverParams } from 'vscode-languageserver-protocol';
import { scenarioCompletion } from './scenario-completion.js';
import { scenarioDiagnostics } from './scenario-diagnostics.js';
import { scenarioHover } from './scenario-hover.js';
import { scenarioNames } from './scenario-names.js';
import { isScenarioUri, scenarioProject } from './scenario-project.js';

type Handler = (params: unknown, ...rest: unknown[]) => unknown;
type Registrar = (handler: Handler) => unknown;

/** Requests about a document that have no meaning for a scenario: answered with `null`. */
const EMPTY_FOR_SCENARIOS = [
    'onDocumentSymbol', 'onDefinition', 'onReferences', 'onCodeAction', 'onFoldingRanges', 'onDocumentHighlight',
    'onDocumentFormatting', 'onDocumentRangeFormatting', 'onDocumentOnTypeFormatting', 'onRenameRequest', 'onPrepareRename',
    'onSignatureHelp', 'onCodeLens', 'onDocumentLinks', 'onTypeDefinition', 'onImplementation', 'onDeclaration', 'onSelectionRanges',
] as const;

function uriOf(params: unknown): string | undefined {
    const doc = (params as { textDocument?: { uri?: unknown } } | null)?.textDocument;
    return typeof doc?.uri === 'string' ? doc.uri : undefined;
}

/** Wraps `target[method]` so the handler registered through it answers scenario URIs with `answer`. */
function route(target: object, method: string, answer: (params: unknown) => unknown): void {
    const original = (target as Record<string, unknown>)[method];
    if (typeof original !== 'function') return;
    const register = (original as Registrar).bind(target);
    (target as Record<string, unknown>)[method] = (handler: Handler) =>
        register((params: unknown, ...rest: unknown[]) => (isScenarioUri(uriOf(params)) ? answer(params) : handler(params, ...rest)));
}

export class ScenarioSupport {
    /** Version of each scenario text the last check started for (a newer change makes it stale). */
    private readonly pending = new Map<string, number>();

    constructor(private readonly shared: LangiumSharedServices, private readonly connection: Connection) {}

    private names(uri: string) {
        return scenarioNames(scenarioProject(this.shared.workspace.LangiumDocuments, uri).models);
    }

    /** Runs `action` once the workspace is loaded and no build is writing the documents. */
    private whenBuilt<T>(action: () => T): Promise<T> {
        const ws = (this.shared as LangiumSharedCoreServices).workspace;
        return ws.WorkspaceManager.ready.then(() => ws.WorkspaceLock.read(action));
    }

    /** Diagnostics of one scenario, unless a newer version of it arrived meanwhile. */
    check(uri: string): void {
        const doc = this.shared.workspace.TextDocuments.get(uri);
        if (!doc) return;
        const version = doc.version;
        this.pending.set(uri, version);
        void this.whenBuilt(() => {
            const current = this.shared.workspace.TextDocuments.get(uri);
            if (!current || this.pending.get(uri) !== version || current.version !== version) return;
            const diagnostics: Diagnostic[] = scenarioDiagnostics(current.getText(), scenarioProject(this.shared.workspace.LangiumDocuments, uri));
            void this.connection.sendDiagnostics({ uri, version, diagnostics });
        }).catch((e) => console.error(`scenario check of ${uri} failed`, e));
    }

    forget(uri: string): void {
        this.pending.delete(uri);
    }

    checkAllOpen(): void {
        for (const doc of this.shared.workspace.TextDocuments.all()) if (isScenarioUri(doc.uri)) this.check(doc.uri);
    }

    completion(params: CompletionParams) {
        return this.whenBuilt(() => {
            const doc = this.shared.workspace.TextDocuments.get(params.textDocument.uri);
            return doc ? { isIncomplete: false, items: scenarioCompletion(doc.getText(), params.position, this.names(doc.uri)) } : null;
        });
    }

    hover(params: HoverParams) {
        return this.whenBuilt(() => {
            const doc = this.shared.workspace.TextDocuments.get(params.textDocument.uri);
            return doc ? scenarioHover(doc.getText(), params.position, this.names(doc.uri)) : null;
        });
    }
}

export function addScenarioSupport(shared: LangiumSharedServices): ScenarioSupport | undefined {
    const connection = shared.lsp.Connection;
    if (!connection) return undefined;
    const support = new ScenarioSupport(shared, connection);
    route(connection, 'onCompletion', (p) => support.completion(p as CompletionParams));
    route(connection, 'onHover', (p) => support.hover(p as HoverParams));
    for (const method of EMPTY_FOR_SCENARIOS) route(connection, method, () => null);
    route(connection.languages.semanticTokens, 'on', () => ({ data: [] }));
    route(connection.languages.semanticTokens, 'onDelta', () => ({ data: [] }));
    route(connection.languages.inlayHint, 'on', () => null);

    const documents = shared.workspace.TextDocuments;
    documents.onDidChangeContent((e) => {
        if (isScenarioUri(e.document.uri)) support.check(e.document.uri);
    });
    documents.onDidClose((e) => {
        if (!isScenarioUri(e.document.uri)) return;
        support.forget(e.document.uri);
        void connection.sendDiagnostics({ uri: e.document.uri, diagnostics: [] });
    });
    // A .contract file changed (or the workspace was first built): the names may have changed.
    shared.workspace.DocumentBuilder.onBuildPhase(DocumentState.Validated, () => support.checkAllOpen());
    return support;
}
