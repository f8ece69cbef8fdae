/**
 * Rename across files (docs/ide.md "Editor services"): modules, supervisors, datatypes, fields, functions, schemas and
 * their parameters, supervision functions, rule labels, ports' and parameters' variables, locals.
 * The new name is checked first (identifier, keywords, `[A-Z]{3}` for modules and supervisors,
 * clashes); a refused name answers the request with an error message the editor shows.
 */
import { CstUtils, type AstNode, type Grammar, type LangiumDocument, type LangiumDocuments } from 'langium';
import type { CactalProjects } from '../scoping/projects.js';
import { DefaultRenameProvider } from 'langium/lsp';
import { LSPErrorCodes, ResponseError, type Range, type RenameParams, type TextDocumentPositionParams, type WorkspaceEdit } from 'vscode-languageserver-protocol';
import type { CactalServices } from '../cactal-module.js';
import { renameProblem } from './name-rules.js';
import { renameEdits } from './rename-edits.js';

export class CactalRenameProvider extends DefaultRenameProvider {
    private readonly documents: LangiumDocuments;
    private readonly projects: CactalProjects;
    private readonly grammar: Grammar;

    constructor(services: CactalServices) {
        super(services);
        this.documents = services.shared.workspace.LangiumDocuments;
        this.projects = services.projects.Projects;
        this.grammar = services.Grammar;
    }

    override async rename(document: LangiumDocument, params: RenameParams): Promise<WorkspaceEdit | undefined> {
        const target = this.targetAt(document, document.textDocument.offsetAt(params.position));
        if (!target) return undefined;
        if (target.name === params.newName) return { changes: {} };
        const problem = renameProblem(target, params.newName, this.grammar, this.projects.indexOf(document.uri));
        if (problem) throw new ResponseError(LSPErrorCodes.RequestFailed, problem);
        return renameEdits(this.references, this.documents, this.projects, target, params.newName);
    }

    /**
     * The range to rename and the current name. On a port reference written as its index (`MSC:1`)
     * the placeholder is the port's name: renaming there renames the port's variable, not the index.
     */
    override prepareRename(document: LangiumDocument, params: TextDocumentPositionParams): Range | undefined {
        const range = super.prepareRename(document, params) as Range | undefined;
        if (!range) return undefined;
        const target = this.targetAt(document, document.textDocument.offsetAt(params.position));
        if (!target?.name) return undefined;
        if (document.textDocument.getText(range) === target.name) return range;
        return { range, placeholder: target.name } as unknown as Range;
    }

    /** The named element a position designates (its name, or a reference to it). */
    targetAt(document: LangiumDocument, offset: number): (AstNode & { name?: string }) | undefined {
        const root = document.parseResult.value.$cstNode;
        if (!root) return undefined;
        const leaf = CstUtils.findDeclarationNodeAtOffset(root, offset, this.grammarConfig.nameRegexp);
        if (!leaf) return undefined;
        const target = this.references.findDeclarations(leaf)[0] as (AstNode & { name?: string }) | undefined;
        return target && typeof target.name === 'string' ? target : undefined;
    }
}
