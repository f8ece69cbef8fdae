/**
 * Imports: `import "relative/path.contract";` resolves relative to the importing file. A name is
 * visible in a file when it is defined there or in a file it imports directly (not transitively).
 */
import { AstUtils, UriUtils, type AstNode, type LangiumDocument, type LangiumSharedCoreServices, type URI } from 'langium';
import type { LangiumCoreServices } from 'langium';
import { isModel, type Import, type Model } from '../generated/ast.js';

export class ImportResolver {
    private readonly visibleCache = new WeakMap<Model, Set<string>>();
    private readonly shared: LangiumSharedCoreServices;

    constructor(services: LangiumCoreServices) {
        this.shared = services.shared;
    }

    /** The URI an import designates (whether or not the file exists). */
    resolveImport(imp: Import): URI {
        const document = AstUtils.getDocument(imp);
        return this.resolvePath(document.uri, imp.path ?? '');
    }

    /** `path` resolved relative to the directory of `from`. */
    resolvePath(from: URI, path: string): URI {
        return UriUtils.resolvePath(UriUtils.dirname(from), path);
    }

    /** The document an import designates, if it is part of the workspace. */
    importedDocument(imp: Import): LangiumDocument | undefined {
        const uri = this.resolveImport(imp);
        const documents = this.shared.workspace.LangiumDocuments;
        return documents.hasDocument(uri) ? documents.getDocument(uri) : undefined;
    }

    /** URIs (as strings) whose top-level names are visible from `node`'s file: itself and its direct imports. */
    visibleUris(node: AstNode): Set<string> {
        const model = AstUtils.findRootNode(node);
        if (!isModel(model)) return new Set([AstUtils.getDocument(node).uri.toString()]);
        let visible = this.visibleCache.get(model);
        if (!visible) {
            const document = AstUtils.getDocument(model);
            visible = new Set([document.uri.toString()]);
            for (const imp of model.imports) {
                if (imp.path) visible.add(this.resolvePath(document.uri, imp.path).toString());
            }
            this.visibleCache.set(model, visible);
        }
        return visible;
    }

    /** A relative import path from the file `from` to the file `to` (for the "add import" quick fix). */
    relativeImportPath(from: URI, to: URI): string {
        const rel = UriUtils.relative(UriUtils.dirname(from), to);
        return rel;
    }
}
