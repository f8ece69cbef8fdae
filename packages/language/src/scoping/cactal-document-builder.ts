/**
 * Import diagnostics of a file depend on the files it imports (missing file, cycles, unused
 * imports), not only on what it links to. Langium relinks and revalidates a document when a file
 * it refers to changes; this builder also does it when a file it imports changes, is created or
 * is deleted.
 */
import { DefaultDocumentBuilder, UriUtils, type LangiumDocument } from 'langium';
import { isModel } from '../generated/ast.js';

export class CactalDocumentBuilder extends DefaultDocumentBuilder {
    protected override shouldRelink(document: LangiumDocument, changedUris: Set<string>): boolean {
        if (super.shouldRelink(document, changedUris)) return true;
        const model = document.parseResult.value;
        if (!isModel(model)) return false;
        const dir = UriUtils.dirname(document.uri);
        return model.imports.some((imp) => imp.path !== undefined && changedUris.has(UriUtils.resolvePath(dir, imp.path).toString()));
    }
}
