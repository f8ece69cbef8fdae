/**
 * Go to definition: Langium's default for every cross-reference (ports by index included), plus
 * the file an `import "..."` designates.
 */
import { CstUtils, type LangiumDocument } from 'langium';
import { DefaultDefinitionProvider } from 'langium/lsp';
import { LocationLink, type DefinitionParams } from 'vscode-languageserver-protocol';
import { isImport } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import type { ImportResolver } from '../scoping/import-resolver.js';

export class CactalDefinitionProvider extends DefaultDefinitionProvider {
    private readonly imports: ImportResolver;

    constructor(services: CactalServices) {
        super(services);
        this.imports = services.imports.ImportResolver;
    }

    override getDefinition(document: LangiumDocument, params: DefinitionParams): LocationLink[] | undefined {
        const root = document.parseResult.value.$cstNode;
        if (root) {
            const leaf = CstUtils.findLeafNodeAtOffset(root, document.textDocument.offsetAt(params.position));
            if (leaf && isImport(leaf.astNode)) {
                const target = this.imports.importedDocument(leaf.astNode);
                if (!target) return undefined;
                const start = { line: 0, character: 0 };
                return [LocationLink.create(target.uri.toString(), { start, end: start }, { start, end: start }, leaf.range)];
            }
        }
        return super.getDefinition(document, params) as LocationLink[] | undefined;
    }
}
