/**
 * A small LSP client between Monaco and the Langium server in a Web Worker (JSON-RPC over
 * postMessage, vscode-jsonrpc). It mirrors every Cactal model into the server (didOpen/didChange/
 * didClose), turns published diagnostics into Monaco markers, and registers Monaco providers for
 * completion, hover, definition, references, rename, formatting, code actions and document symbols.
 */
import { monaco } from '../editor/monaco.js';
import { BrowserMessageReader, BrowserMessageWriter, createMessageConnection, type MessageConnection } from 'vscode-jsonrpc/browser.js';
import type * as lsp from 'vscode-languageserver-protocol';
import { Emitter } from '../util/emitter.js';
import { toast } from '../util/toast.js';
import { CACTAL_LANGUAGE_ID } from '../editor/cactal-language.js';
import { SCENARIO_LANGUAGE_ID } from '../editor/scenario-language.js';
import * as conv from './lsp-convert.js';
import type { ArchSchema } from './architecture-model.js';
import type { ProjectLayout } from './project-layout.js';
import LanguageWorker from './language-worker.ts?worker';

/**
 * Symbol kinds of the top-level entities that name generated files and region IDs (docs/codegen.md):
 * modules and supervisors (Class), datatypes (Struct), functions (Function). A schema (Namespace)
 * names none, so its rename carries nothing over — as `contract rename` does.
 */
const NAMES_GENERATED_FILES: readonly number[] = [5, 23, 10, 12];

export const MARKER_OWNER = 'cactal';

export class LspClient {
  private connection!: MessageConnection;
  private worker!: Worker;
  private readonly versions = new Map<string, number>();
  /** Last published diagnostics per URI, as sent (their `data` carries what quick fixes need). */
  private readonly diagnostics = new Map<string, lsp.Diagnostic[]>();
  readonly onDiagnostics = new Emitter<{ uri: string; diagnostics: lsp.Diagnostic[] }>();
  /** window/showMessage from the language server. */
  readonly onMessage = new Emitter<lsp.ShowMessageParams>();
  readonly ready: Promise<void>;
  private resolveReady!: () => void;
  /** Opened documents whose first diagnostics have not arrived yet (= not fully built). */
  private readonly unbuilt = new Set<string>();
  private builtWaiters: Array<() => void> = [];
  /** The projects' layout last given, and whether the worker has it (sent once the connection is up). */
  private layout: { json: string; sent: boolean } | undefined;
  private initialized = false;

  constructor() {
    this.ready = new Promise((r) => (this.resolveReady = r));
  }

  async start(): Promise<void> {
    this.worker = new LanguageWorker();
    this.worker.onerror = (e) => console.error('language worker error', e.message);
    this.connection = createMessageConnection(new BrowserMessageReader(this.worker), new BrowserMessageWriter(this.worker));
    this.connection.onNotification('textDocument/publishDiagnostics', (p: lsp.PublishDiagnosticsParams) => {
      this.markBuilt(p.uri);
      this.diagnostics.set(p.uri, p.diagnostics);
      const model = monaco.editor.getModel(monaco.Uri.parse(p.uri));
      if (model) monaco.editor.setModelMarkers(model, MARKER_OWNER, p.diagnostics.map(conv.toMarker));
      this.onDiagnostics.fire({ uri: p.uri, diagnostics: p.diagnostics });
    });
    this.connection.onRequest('workspace/configuration', (p: lsp.ConfigurationParams) => p.items.map(() => null));
    this.connection.onRequest('client/registerCapability', () => null);
    this.connection.onRequest('window/workDoneProgress/create', () => null);
    this.connection.onNotification('window/logMessage', () => undefined);
    // e.g. why Format did nothing (a syntax error): the server's words, shown as a notice
    this.connection.onNotification('window/showMessage', (p: lsp.ShowMessageParams) => this.onMessage.fire(p));
    this.connection.listen();
    const init = await this.connection.sendRequest<lsp.InitializeResult>('initialize', {
      processId: null,
      rootUri: 'file:///workspace',
      workspaceFolders: [{ uri: 'file:///workspace', name: 'workspace' }],
      capabilities: {
        textDocument: {
          synchronization: { didSave: false },
          publishDiagnostics: { relatedInformation: true },
          completion: { completionItem: { snippetSupport: true } },
          hover: { contentFormat: ['markdown', 'plaintext'] },
          documentSymbol: { hierarchicalDocumentSymbolSupport: true },
          rename: { prepareSupport: true },
          codeAction: { codeActionLiteralSupport: { codeActionKind: { valueSet: ['quickfix', 'refactor', 'source'] } } },
          semanticTokens: { requests: { full: true }, tokenTypes: [], tokenModifiers: [], formats: ['relative'] },
        },
        workspace: { workspaceFolders: true, configuration: true, workspaceEdit: { documentChanges: true } },
      },
    } satisfies lsp.InitializeParams);
    this.connection.sendNotification('initialized', {});
    // before the first document: its project is known when it is first checked
    this.initialized = true;
    this.sendLayout();
    this.trackModels();
    this.registerProviders();
    const legend = init.capabilities.semanticTokensProvider?.legend;
    if (legend) this.registerSemanticTokens(legend);
    this.resolveReady();
  }

  /** Models the server sees: Cactal files, and scenario files (opened as tabs only). */
  private isCactal(model: monaco.editor.ITextModel): boolean {
    const id = model.getLanguageId();
    return (id === CACTAL_LANGUAGE_ID || id === SCENARIO_LANGUAGE_ID) && model.uri.scheme === 'file';
  }

  private trackModels(): void {
    const open = (model: monaco.editor.ITextModel) => {
      if (!this.isCactal(model)) return;
      const uri = model.uri.toString();
      this.versions.set(uri, 1);
      this.unbuilt.add(uri);
      void this.connection.sendNotification('textDocument/didOpen', {
        textDocument: { uri, languageId: model.getLanguageId(), version: 1, text: model.getValue() },
      } satisfies lsp.DidOpenTextDocumentParams);
      model.onDidChangeContent(() => {
        const version = (this.versions.get(uri) ?? 1) + 1;
        this.versions.set(uri, version);
        void this.connection.sendNotification('textDocument/didChange', {
          textDocument: { uri, version },
          contentChanges: [{ text: model.getValue() }],
        } satisfies lsp.DidChangeTextDocumentParams);
      });
    };
    monaco.editor.getModels().forEach(open);
    monaco.editor.onDidCreateModel(open);
    monaco.editor.onWillDisposeModel((model) => {
      if (!this.isCactal(model)) return;
      const uri = model.uri.toString();
      this.versions.delete(uri);
      this.diagnostics.delete(uri);
      this.markBuilt(uri);
      void this.connection.sendNotification('textDocument/didClose', { textDocument: { uri } });
      // Models are disposed when their file is deleted or moved: the server must forget the document
      // (Langium keeps closed documents otherwise, and would rebuild them from a file system it has not).
      void this.connection.sendNotification('workspace/didChangeWatchedFiles', { changes: [{ uri, type: 3 }] } satisfies lsp.DidChangeWatchedFilesParams);
      this.onDiagnostics.fire({ uri, diagnostics: [] });
    });
  }

  private markBuilt(uri: string): void {
    if (!this.unbuilt.delete(uri) || this.unbuilt.size) return;
    const waiters = this.builtWaiters;
    this.builtWaiters = [];
    waiters.forEach((w) => w());
  }

  /**
   * Resolves once every opened document has been built and validated at least once (its first
   * diagnostics arrived), so cross-file requests (rename, references) see the whole workspace.
   */
  workspaceBuilt(maxWaitMs = 15_000): Promise<void> {
    if (!this.unbuilt.size) return Promise.resolve();
    return new Promise((r) => {
      this.builtWaiters.push(r);
      setTimeout(() => {
        if (this.unbuilt.size) console.warn(`language server: no diagnostics yet for ${[...this.unbuilt].join(', ')}`);
        r();
      }, maxWaitMs);
    });
  }

  /**
   * Resolves once the server has validated every document opened so far, with whatever they
   * import, and every diagnostic of that validation has arrived (the worker's `cactal/validated`):
   * a document's first diagnostics may come from a build made before the files it imports were
   * opened (on 1,231 files: 75 errors for 12 s, then 1). No time cap; a worker that died: at once.
   */
  async workspaceValidated(): Promise<void> {
    await this.connection.sendRequest('cactal/validated', {}).catch(() => undefined);
  }

  request<R>(method: string, params: unknown): Promise<R> {
    // models that are not workspace files (the conflict view's side-by-side copies) are not in the worker
    const uri = (params as { textDocument?: { uri?: unknown } } | undefined)?.textDocument?.uri;
    if (typeof uri === 'string' && !uri.startsWith('file:')) return Promise.resolve(null as R);
    return this.connection.sendRequest(method, params) as Promise<R>;
  }

  documentSymbols(uri: string): Promise<lsp.DocumentSymbol[] | null> {
    return this.request('textDocument/documentSymbol', { textDocument: { uri } });
  }

  /**
   * The workspace's projects (the folders holding a src-gen/, the .contract files): the worker
   * checks names and project-wide rules per project (docs/codegen.md "Where a project is"). Sent
   * when it changed; the worker then checks every document again.
   */
  setProjectLayout(layout: ProjectLayout): void {
    const json = JSON.stringify(layout);
    if (this.layout?.json === json) return;
    this.layout = { json, sent: false };
    this.sendLayout();
  }

  private sendLayout(): void {
    if (!this.layout || this.layout.sent || !this.initialized) return;
    this.layout.sent = true;
    void this.connection.sendNotification('cactal/projectLayout', JSON.parse(this.layout.json) as ProjectLayout);
  }

  /** Re-validates every document (after files were added or removed). */
  revalidateAll(): void {
    void this.connection.sendNotification('cactal/revalidateAll', {});
  }

  architecture(): Promise<ArchSchema[]> {
    return this.request('cactal/architecture', {});
  }

  private registerProviders(): void {
    const id = CACTAL_LANGUAGE_ID;
    const doc = (model: monaco.editor.ITextModel) => ({ textDocument: { uri: model.uri.toString() } });
    const at = (model: monaco.editor.ITextModel, position: monaco.Position) => ({ ...doc(model), position: conv.toPosition(position) });

    for (const languageId of [id, SCENARIO_LANGUAGE_ID]) this.registerCompletionAndHover(languageId);
    monaco.languages.registerDefinitionProvider(id, {
      provideDefinition: async (model, position) => conv.toLocations(await this.request('textDocument/definition', at(model, position))),
    });
    monaco.languages.registerReferenceProvider(id, {
      provideReferences: async (model, position, context) => {
        await this.workspaceBuilt();
        return conv.toLocations(await this.request('textDocument/references', { ...at(model, position), context }));
      },
    });
    monaco.languages.registerRenameProvider(id, {
      provideRenameEdits: async (model, position, newName) => {
        await this.workspaceBuilt();
        const oldName = model.getWordAtPosition(position)?.word ?? '';
        // Before the edits apply: is this a top-level entity (module, supervisor, datatype, function)?
        const defs = await this.request<lsp.Definition | lsp.LocationLink[] | null>('textDocument/definition', at(model, position)).catch(() => null);
        const targetUri = conv.toLocations(defs)[0]?.uri.toString() ?? model.uri.toString();
        const symbols = (await this.documentSymbols(targetUri).catch(() => null)) ?? [];
        const topLevel = symbols.some((s) => s.name === oldName && NAMES_GENERATED_FILES.includes(s.kind));
        const target = renamedSymbol(symbols, oldName, conv.toLocations(defs)[0]?.range.startLineNumber);
        let r: lsp.WorkspaceEdit | null;
        try {
          r = await this.request<lsp.WorkspaceEdit | null>('textDocument/rename', { ...at(model, position), newName });
        } catch (e) {
          // a name the rename rules refuse: said where the user looks (Monaco only logged it to the console)
          const reason = (e as Error).message || 'the rename was refused';
          toast('warning', `Rename refused: ${reason}`);
          return { edits: [], rejectReason: reason };
        }
        const edit = conv.toWorkspaceEdit(r);
        if (edit.edits.length) this.onRename.fire({ oldName, newName, topLevel, ...target, files: textsAfter(edit) });
        return edit;
      },
      resolveRenameLocation: async (model, position) => {
        const word = model.getWordAtPosition(position);
        if (!word) return { rejectReason: 'Nothing to rename here', range: new monaco.Range(1, 1, 1, 1), text: '' };
        const r = await this.request<lsp.PrepareRenameResult | null>('textDocument/prepareRename', at(model, position)).catch(() => undefined);
        if (r === null) return { rejectReason: 'This element cannot be renamed', range: new monaco.Range(1, 1, 1, 1), text: '' };
        const range = new monaco.Range(position.lineNumber, word.startColumn, position.lineNumber, word.endColumn);
        if (r && 'range' in r) return { range: conv.toRange(r.range), text: r.placeholder };
        if (r && 'start' in r) return { range: conv.toRange(r), text: model.getValueInRange(conv.toRange(r)) };
        return { range, text: word.word };
      },
    });
    monaco.languages.registerDocumentFormattingEditProvider(id, {
      provideDocumentFormattingEdits: async (model, options) => {
        const r = await this.request<lsp.TextEdit[] | null>('textDocument/formatting', { ...doc(model), options });
        return (r ?? []).map((e) => ({ range: conv.toRange(e.range), text: e.newText }));
      },
    });
    monaco.languages.registerCodeActionProvider(id, {
      provideCodeActions: async (model, range, context) => {
        const touches = (d: lsp.Diagnostic) => {
          const r = conv.toRange(d.range);
          return monaco.Range.areIntersectingOrTouching(r, range);
        };
        const diagnostics = (this.diagnostics.get(model.uri.toString()) ?? []).filter(touches);
        const r = await this.request<Array<lsp.CodeAction | lsp.Command> | null>('textDocument/codeAction', {
          ...doc(model),
          range: { start: conv.toPosition(range.getStartPosition()), end: conv.toPosition(range.getEndPosition()) },
          context: { diagnostics, only: undefined },
        });
        const actions = (r ?? []).filter((a): a is lsp.CodeAction => 'title' in a && !('command' in a && typeof a.command === 'string'));
        return {
          actions: actions.map((a) => ({
            title: a.title,
            kind: a.kind,
            isPreferred: a.isPreferred,
            diagnostics: a.diagnostics?.map(conv.toMarker),
            edit: a.edit ? conv.toWorkspaceEdit(a.edit) : undefined,
          })),
          dispose: () => undefined,
        };
      },
    });
    monaco.languages.registerDocumentSymbolProvider(id, {
      provideDocumentSymbols: async (model) => {
        const r = (await this.documentSymbols(model.uri.toString())) ?? [];
        const map = (s: lsp.DocumentSymbol): monaco.languages.DocumentSymbol => ({
          name: s.name,
          detail: s.detail ?? '',
          kind: (s.kind - 1) as monaco.languages.SymbolKind,
          tags: [],
          range: conv.toRange(s.range),
          selectionRange: conv.toRange(s.selectionRange),
          children: s.children?.map(map),
        });
        return r.map(map);
      },
    });
  }

  /** Completion and hover: the only editor services of scenario files besides diagnostics. */
  private registerCompletionAndHover(id: string): void {
    const doc = (model: monaco.editor.ITextModel) => ({ textDocument: { uri: model.uri.toString() } });
    const at = (model: monaco.editor.ITextModel, position: monaco.Position) => ({ ...doc(model), position: conv.toPosition(position) });
    monaco.languages.registerCompletionItemProvider(id, {
      triggerCharacters: [':', '.', ' '],
      provideCompletionItems: async (model, position) => {
        const r = await this.request<lsp.CompletionList | lsp.CompletionItem[] | null>('textDocument/completion', at(model, position));
        const word = model.getWordUntilPosition(position);
        const fallback = new monaco.Range(position.lineNumber, word.startColumn, position.lineNumber, word.endColumn);
        const items = Array.isArray(r) ? r : (r?.items ?? []);
        return { suggestions: items.map((i) => conv.toCompletion(i, fallback)), incomplete: !Array.isArray(r) && !!r?.isIncomplete };
      },
    });
    monaco.languages.registerHoverProvider(id, {
      provideHover: async (model, position) => {
        const r = await this.request<lsp.Hover | null>('textDocument/hover', at(model, position));
        return r ? { contents: conv.toMarkdown(r.contents), range: r.range ? conv.toRange(r.range) : undefined } : null;
      },
    });
  }

  /** Semantic highlighting from the server (modules, ports, labels... coloured by meaning). */
  private registerSemanticTokens(legend: lsp.SemanticTokensLegend): void {
    monaco.languages.registerDocumentSemanticTokensProvider(CACTAL_LANGUAGE_ID, {
      getLegend: () => legend,
      provideDocumentSemanticTokens: async (model) => {
        const r = await this.request<lsp.SemanticTokens | null>('textDocument/semanticTokens/full', { textDocument: { uri: model.uri.toString() } });
        return r ? { data: new Uint32Array(r.data), resultId: r.resultId } : null;
      },
      releaseDocumentSemanticTokens: () => undefined,
    });
  }

  /** Fired when a rename was computed (the IDE carries generated files over). */
  /**
   * A rename applied: `topLevel` for an entity that names generated files; `kind` and `owner` when
   * the user code of the generated C uses the name (a module's port or parameter: its module; a
   * datatype; a function), for the carry-over (app/rename-carryover.ts).
   */
  readonly onRename = new Emitter<RenameEvent>();
}

export interface RenameEvent {
  oldName: string;
  newName: string;
  topLevel: boolean;
  kind?: RenamedKind;
  owner?: string;
  /** A renamed enumeration's members: its C constants (`Mode_AUTO`) in the user code follow it. */
  members?: string[];
  /**
   * Each file the rename edits, with its text before and once edited (the server writes them,
   * journaled; refused, the editor's rename is taken back: app/rename-undo.ts).
   */
  files: Array<{ uri: string; before: string; text: string }>;
}

/** The text of each open model `edit` changes, as it is and as it will be once edited (computed on the models as they are, before the edit applies). */
function textsAfter(edit: monaco.languages.WorkspaceEdit): Array<{ uri: string; before: string; text: string }> {
  const byUri = new Map<string, monaco.languages.IWorkspaceTextEdit[]>();
  for (const e of edit.edits) if ('textEdit' in e) byUri.set(e.resource.toString(), [...(byUri.get(e.resource.toString()) ?? []), e]);
  const files: Array<{ uri: string; before: string; text: string }> = [];
  for (const [uri, edits] of byUri) {
    const model = monaco.editor.getModel(monaco.Uri.parse(uri));
    if (!model) continue;
    const before = model.getValue();
    let text = before;
    // from the last edit back: the offsets of those before stay right
    const at = edits.map((e) => ({ start: model.getOffsetAt({ lineNumber: e.textEdit.range.startLineNumber, column: e.textEdit.range.startColumn }), end: model.getOffsetAt({ lineNumber: e.textEdit.range.endLineNumber, column: e.textEdit.range.endColumn }), text: e.textEdit.text }));
    for (const e of at.sort((a, b) => b.start - a.start)) text = text.slice(0, e.start) + e.text + text.slice(e.end);
    files.push({ uri, before, text });
  }
  return files;
}

/** What a rename renamed, as POST /api/rename-entity names it (its carry-over into src-gen and the `.scenario` files). */
export type RenamedKind = 'module' | 'supervisor' | 'schema' | 'supervision function' | 'port' | 'parameter' | 'datatype' | 'enumeration' | 'function'
  | 'enumeration member' | 'rule label' | 'local' | 'function parameter';

/** LSP SymbolKind numbers of the Cactal document symbols (language cactal-document-symbol-provider.ts). */
const SYMBOL = { Namespace: 3, Class: 5, Method: 6, Property: 7, Enum: 10, Function: 12, Variable: 13, Key: 20, EnumMember: 22, Struct: 23, Event: 24, TypeParameter: 26 } as const;

/**
 * What a rename renames, from the document symbols of its definition's file: a module or a
 * supervisor (Class, told apart by its detail), a schema (Namespace), a datatype, an enumeration
 * (with its members) or a function at top level; a member of an enumeration, the enumeration named; a port (Event, Variable) or parameter (Property) of a module or
 * supervisor, a supervision function (Method) of a supervisor, the owner named; a rule label (Key),
 * local (Variable) or parameter (TypeParameter) of a supervision function, owned by `SUP.function`. `line` (1-based) is
 * the definition's line, to tell apart two ports of one name in two modules of a file. Nothing for
 * other names (schemas' parameters, fields...).
 */
function renamedSymbol(symbols: lsp.DocumentSymbol[], name: string, line: number | undefined): Pick<RenameEvent, 'kind' | 'owner' | 'members'> {
  const at = (s: lsp.DocumentSymbol) => line === undefined || (s.range.start.line + 1 <= line && line <= s.range.end.line + 1);
  for (const top of symbols) {
    if (top.name === name && at(top)) {
      if (top.kind === SYMBOL.Struct) return { kind: 'datatype' };
      if (top.kind === SYMBOL.Enum) return { kind: 'enumeration', members: (top.children ?? []).map((m) => m.name) };
      if (top.kind === SYMBOL.Function) return { kind: 'function' };
      if (top.kind === SYMBOL.Namespace) return { kind: 'schema' };
      // a port's line is inside its module's range: the module itself only when the line is its own
      if (top.kind === SYMBOL.Class && (line === undefined || top.selectionRange.start.line + 1 === line)) {
        return { kind: top.detail === 'supervisor' ? 'supervisor' : 'module' };
      }
    }
    if (top.kind === SYMBOL.Enum && at(top) && (top.children ?? []).some((m) => m.name === name && m.kind === SYMBOL.EnumMember)) {
      return { kind: 'enumeration member', owner: top.name };
    }
    if (top.kind !== SYMBOL.Class || !at(top)) continue;
    for (const child of top.children ?? []) {
      if (child.name !== name || !at(child)) continue;
      if (child.kind === SYMBOL.Event || child.kind === SYMBOL.Variable) return { kind: 'port', owner: top.name };
      if (child.kind === SYMBOL.Property) return { kind: 'parameter', owner: top.name };
      if (child.kind === SYMBOL.Method) return { kind: 'supervision function', owner: top.name };
    }
    // a supervision function's rule labels, locals and parameters: owned by SUP.function
    for (const fn of top.children ?? []) {
      if (fn.kind !== SYMBOL.Method || !at(fn)) continue;
      const inner = (fn.children ?? []).find((c) => c.name === name && at(c));
      const owner = `${top.name}.${fn.name}`;
      if (inner?.kind === SYMBOL.Key) return { kind: 'rule label', owner };
      if (inner?.kind === SYMBOL.Variable) return { kind: 'local', owner };
      if (inner?.kind === SYMBOL.TypeParameter) return { kind: 'function parameter', owner };
    }
  }
  return {};
}
