/**
 * Quick fixes (docs/ide.md "Editor services") for the diagnostics that carry what the fix needs in their data:
 * - `import-not-imported` (data.importPath): add the import after the file's imports;
 * - `module-name-format` (data.suggestion): rename the module/supervisor to its upper-case form,
 *   in every file that refers to it;
 * - `port-index-duplicate` (data.suggestedIndex): renumber the port to a free index;
 * - `supervisor-action-separator` (data.insertAt, the end of the action before): insert the missing ';';
 * - `supervisor-elapsed-once` (data.suggestion): `elapsed=t` -> `duration(R)=t`;
 * - `identifier-c-reserved`, `identifier-generated-clash` (data.suggestion): rename the element everywhere to a name the
 *   generated C does not take (the suggestion, or the next free `<name>_N` if the rename rules refuse it);
 * - a syntax error saying `Did you mean 'synchronous'?` on a misspelt keyword (the squiggled word is a near miss of it):
 *   replace the word by the keyword.
 */
import { CstUtils, type AstNode, type Grammar, type LangiumDocument, type LangiumDocuments, type References } from 'langium';
import type { CactalProjects } from '../scoping/projects.js';
import type { CodeActionProvider } from 'langium/lsp';
import { CodeActionKind, type CodeAction, type CodeActionParams, type Diagnostic } from 'vscode-languageserver-protocol';
import { isModule, isSupervisor, type Model } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { suggestName } from '../validation/c-names/reserved-names.js';
import { renameProblem } from './name-rules.js';
import { renameEdits } from './rename-edits.js';
import { keywordTypoFix } from './keyword-typo-fix.js';

type DiagnosticData = { code?: string; importPath?: string; suggestion?: string; suggestedIndex?: number; insertAt?: { line?: unknown; character?: unknown } };

export class CactalCodeActionProvider implements CodeActionProvider {
    private readonly references: References;
    private readonly documents: LangiumDocuments;
    private readonly grammar: Grammar;
    private readonly projects: CactalProjects;

    constructor(services: CactalServices) {
        this.references = services.references.References;
        this.documents = services.shared.workspace.LangiumDocuments;
        this.grammar = services.Grammar;
        this.projects = services.projects.Projects;
    }

    getCodeActions(document: LangiumDocument, params: CodeActionParams): CodeAction[] {
        const actions: CodeAction[] = [];
        const importsAdded = new Set<string>();
        for (const diagnostic of params.context.diagnostics) {
            const data = (diagnostic.data ?? {}) as DiagnosticData;
            const code = String(diagnostic.code ?? data.code ?? '');
            if (code === 'import-not-imported' && data.importPath && !importsAdded.has(data.importPath)) {
                importsAdded.add(data.importPath);
                const action = this.addImport(document, diagnostic, data.importPath);
                if (action) actions.push(action);
            } else if (code === 'module-name-format' && data.suggestion) {
                const action = this.upperCaseName(document, diagnostic, data.suggestion);
                if (action) actions.push(action);
            } else if ((code === 'identifier-c-reserved' || code === 'identifier-generated-clash') && data.suggestion) {
                const action = this.renameReserved(document, diagnostic, data.suggestion);
                if (action) actions.push(action);
            } else if (code === 'port-index-duplicate' && typeof data.suggestedIndex === 'number') {
                actions.push({
                    title: `Renumber to :${data.suggestedIndex}`,
                    kind: CodeActionKind.QuickFix,
                    diagnostics: [diagnostic],
                    isPreferred: true,
                    edit: { changes: { [document.textDocument.uri]: [{ range: diagnostic.range, newText: String(data.suggestedIndex) }] } }
                });
            } else if (code === 'supervisor-elapsed-once' && data.suggestion) {
                actions.push({
                    title: `Use ${data.suggestion} (ends it ${data.suggestion.replace(/^.*=/, '')} after each activation)`,
                    kind: CodeActionKind.QuickFix,
                    diagnostics: [diagnostic],
                    isPreferred: true,
                    edit: { changes: { [document.textDocument.uri]: [{ range: diagnostic.range, newText: data.suggestion }] } }
                });
            } else if (code === 'parsing-error') {
                const action = keywordTypoFix(document, diagnostic);
                if (action) actions.push(action);
            } else if (code === 'supervisor-action-separator' && Number.isInteger(data.insertAt?.line) && Number.isInteger(data.insertAt?.character)) {
                const at = { line: data.insertAt!.line as number, character: data.insertAt!.character as number };
                actions.push({
                    title: "Insert ';'",
                    kind: CodeActionKind.QuickFix,
                    diagnostics: [diagnostic],
                    isPreferred: true,
                    edit: { changes: { [document.textDocument.uri]: [{ range: { start: at, end: at }, newText: ';' }] } }
                });
            }
        }
        return actions;
    }

    private addImport(document: LangiumDocument, diagnostic: Diagnostic, importPath: string): CodeAction | undefined {
        const model = document.parseResult.value as Model;
        if (model.imports.some((i) => i.path === importPath)) return undefined;
        const last = model.imports.at(-1)?.$cstNode;
        const position = last ? { line: last.range.end.line + 1, character: 0 } : { line: 0, character: 0 };
        const lineCount = document.textDocument.lineCount;
        const atEnd = last !== undefined && position.line >= lineCount;
        const text = `import "${importPath}";\n`;
        return {
            title: `Add import "${importPath}"`,
            kind: CodeActionKind.QuickFix,
            diagnostics: [diagnostic],
            isPreferred: true,
            edit: {
                changes: {
                    [document.textDocument.uri]: [atEnd
                        ? { range: { start: last!.range.end, end: last!.range.end }, newText: '\n' + text.trimEnd() }
                        : { range: { start: position, end: position }, newText: text }]
                }
            }
        };
    }

    private renameReserved(document: LangiumDocument, diagnostic: Diagnostic, suggestion: string): CodeAction | undefined {
        const node = this.namedNodeAt(document, diagnostic);
        if (!node?.name) return undefined;
        const free = (candidate: string) => renameProblem(node, candidate, this.grammar, this.projects.indexOf(document.uri)) === undefined;
        const newName = free(suggestion) ? suggestion : suggestName(node.name, free);
        if (!free(newName)) return undefined;
        return {
            title: `Rename '${node.name}' to '${newName}'`,
            kind: CodeActionKind.QuickFix,
            diagnostics: [diagnostic],
            isPreferred: true,
            edit: renameEdits(this.references, this.documents, this.projects, node, newName)
        };
    }

    /** The named element whose name the diagnostic covers. */
    private namedNodeAt(document: LangiumDocument, diagnostic: Diagnostic): (AstNode & { name?: string }) | undefined {
        const root = document.parseResult.value.$cstNode;
        if (!root) return undefined;
        const leaf = CstUtils.findLeafNodeAtOffset(root, document.textDocument.offsetAt(diagnostic.range.start));
        const node = leaf?.astNode as (AstNode & { name?: string }) | undefined;
        return node && typeof node.name === 'string' ? node : undefined;
    }

    private upperCaseName(document: LangiumDocument, diagnostic: Diagnostic, suggestion: string): CodeAction | undefined {
        const root = document.parseResult.value.$cstNode;
        if (!root) return undefined;
        const leaf = CstUtils.findLeafNodeAtOffset(root, document.textDocument.offsetAt(diagnostic.range.start));
        const node: AstNode | undefined = leaf?.astNode;
        if (!isModule(node) && !isSupervisor(node)) return undefined;
        return {
            title: `Rename '${node.name}' to '${suggestion}'`,
            kind: CodeActionKind.QuickFix,
            diagnostics: [diagnostic],
            isPreferred: true,
            edit: renameEdits(this.references, this.documents, this.projects, node, suggestion)
        };
    }
}
