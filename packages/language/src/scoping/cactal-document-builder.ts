/**
 * Some diagnostics of a file depend on files it does not link to:
 * - import diagnostics (missing file, cycles, unused imports) depend on the files it imports;
 * - project-wide uniqueness (modules, supervisors, datatypes, functions, schemas) depends on every
 *   file exporting the same name.
 * Langium relinks and revalidates a document only when a file it refers to changes; this builder
 * also revalidates the importers of a changed file, and the files that export a name a changed
 * file exported before or exports now.
 */
import {
    Cancellation, DefaultDocumentBuilder, DocumentState, UriUtils,
    type LangiumDocument, type URI
} from 'langium';
import { isModel } from '../generated/ast.js';

export class CactalDocumentBuilder extends DefaultDocumentBuilder {
    /** Top-level names exported by the changed and deleted files before the current update. */
    private namesBeforeUpdate = new Set<string>();

    override async update(changed: URI[], deleted: URI[], cancelToken = Cancellation.CancellationToken.None): Promise<void> {
        const touched = new Set([...changed, ...deleted].map((u) => u.toString()));
        this.namesBeforeUpdate = this.exportedNames(touched);
        await super.update(changed, deleted, cancelToken);
        // names the changed files export now: files that export them too must show (or drop) the duplicate
        const namesNow = this.exportedNames(touched);
        const stale = this.langiumDocuments.all
            .filter((doc) => !touched.has(doc.uri.toString()) && doc.state === DocumentState.Validated && this.exportsAny(doc, namesNow))
            .toArray();
        if (stale.length > 0) {
            for (const doc of stale) this.resetToState(doc, DocumentState.ComputedScopes);
            await this.buildDocuments(stale, this.updateBuildOptions, cancelToken);
        }
    }

    protected override shouldRelink(document: LangiumDocument, changedUris: Set<string>): boolean {
        if (super.shouldRelink(document, changedUris)) return true;
        const model = document.parseResult.value;
        if (!isModel(model)) return false;
        const dir = UriUtils.dirname(document.uri);
        if (model.imports.some((imp) => imp.path !== undefined && changedUris.has(UriUtils.resolvePath(dir, imp.path).toString()))) return true;
        return this.exportsAny(document, this.namesBeforeUpdate);
    }

    private exportedNames(uris: Set<string>): Set<string> {
        const names = new Set<string>();
        if (uris.size === 0) return names;
        for (const d of this.indexManager.allElements(undefined, uris)) names.add(d.name);
        return names;
    }

    private exportsAny(document: LangiumDocument, names: Set<string>): boolean {
        if (names.size === 0) return false;
        const model = document.parseResult.value;
        return isModel(model) && model.elements.some((e) => 'name' in e && typeof e.name === 'string' && names.has(e.name));
    }
}
