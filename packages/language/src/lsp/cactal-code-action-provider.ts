/**
 * Quick fixes (SPEC §2.7) for the diagnostics that carry what the fix needs in their data:
 * - `import-not-imported` (data.importPath): add the import after the file's imports;
 * - `module-name-format` (data.suggestion): rename the module/supervisor to its upper-case form,
 *   in every file that refers to it;
 * - `port-index-duplicate` (data.suggestedIndex): renumber the port to a free index.
 */
import { CstUtils, type AstNode, type LangiumDocument, type LangiumDocuments, type References } from 'langium';
import type { CodeActionProvider } from 'langium/lsp';
import { CodeActionKind, type CodeAction, type CodeActionParams, type Diagnostic } from 'vscode-languageserver-protocol';
import { isModule, isSupervisor, type Model } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { renameEdits } from './rename-edits.js';

type DiagnosticData = { code?: string; importPath?: string; suggestion?: string; suggestedIndex?: number };

export class CactalCodeActionProvider implements CodeActionProvider {
    private readonly references: References;
    private readonly documents: LangiumDocuments;

    constructor(services: CactalServices) {
        this.references = services.references.References;
        this.documents = services.shared.workspace.LangiumDocuments;
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
            } else if (code === 'port-index-duplicate' && typeof data.suggestedIndex === 'number') {
                actions.push({
                    title: `Renumber to :${data.suggestedIndex}`,
                    kind: CodeActionKind.QuickFix,
                    diagnostics: [diagnostic],
                    isPreferred: true,
                    edit: { changes: { [document.textDocument.uri]: [{ range: diagnostic.range, newText: String(data.suggestedIndex) }] } }
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
            edit: renameEdits(this.references, this.documents, node, suggestion)
        };
    }
}
