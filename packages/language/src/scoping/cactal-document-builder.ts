/**
 * Some diagnostics of a file depend on files it does not link to:
 * - import diagnostics (missing file, cycles, unused imports) depend on the files it imports;
 * - project-wide uniqueness (modules, supervisors, datatypes, functions, schemas) depends on every
 *   file exporting the same name;
 * - the scheduler-configuration checks and the cycle checks depend on the project's facts
 *   (`project-facts.ts`).
 * Langium relinks and revalidates a document only when a file it refers to changes; this builder
 * also revalidates the importers of a changed file, the files that export a name a changed file
 * exported before or exports now, and the files whose project-wide diagnostics depend on a fact a
 * changed file contributed before or contributes now; and every file when a file added or removed,
 * or a `src-gen/` folder made or removed, moved a file into another project (scoping/projects.ts).
 */
import {
    Cancellation, DefaultDocumentBuilder, DocumentState, URI, UriUtils,
    type LangiumDocument
} from 'langium';
import { isModel } from '../generated/ast.js';
import { documentFacts, factsOf, projectDependents, type DocumentFacts } from './project-facts.js';
import type { CactalServices } from '../cactal-module.js';

export class CactalDocumentBuilder extends DefaultDocumentBuilder {
    /** Top-level names exported by the changed and deleted files before the current update. */
    private namesBeforeUpdate = new Set<string>();
    /**
     * Facts of the files changed since the last completed update, as they were before the first of
     * those changes: an update cancelled by the next keystroke must not lose what changed.
     */
    private readonly pendingFacts = new Map<string, DocumentFacts>();
    /**
     * The project of every document as it was before the first of the updates since the last
     * completed one that may have changed the layout: a cancelled one (a second src-gen/ made right
     * after the first, the next keystroke) must not lose the move.
     */
    private pendingProjects: Map<string, string> | undefined;

    override async update(changed: URI[], deleted: URI[], cancelToken = Cancellation.CancellationToken.None): Promise<void> {
        const touchedUris = [...changed, ...deleted].map((u) => u.toString());
        const before = this.documentsAt(touchedUris);
        // a file added or removed may change which project the others are in (projects.ts: a second
        // first-level folder with .contract files splits the opened folder into projects)
        // (a src-gen/ folder made or removed too: the URI of a folder, no document)
        const layoutMayChange = deleted.length > 0 || changed.some((u) => !this.langiumDocuments.hasDocument(u));
        if (layoutMayChange) this.pendingProjects ??= this.lastProjectKeys();
        for (const [uri, doc] of before) if (!this.pendingFacts.has(uri)) this.pendingFacts.set(uri, documentFacts(doc));
        this.namesBeforeUpdate = this.exportedNames(new Set(before.keys()));
        await super.update(changed, deleted, cancelToken);

        const after = this.documentsAt([...touchedUris, ...this.pendingFacts.keys()]);
        const factsBefore = new Map(this.pendingFacts);
        for (const uri of after.keys()) if (!factsBefore.has(uri)) factsBefore.set(uri, documentFacts(undefined));
        const touched = new Set(after.keys());
        const all = this.langiumDocuments.all.toArray();
        const settled = (doc: LangiumDocument) => !touched.has(doc.uri.toString()) && doc.state === DocumentState.Validated;
        // names the changed files export now: files that export them too must show (or drop) the duplicate
        const namesNow = this.exportedNames(touched);
        const projectsBefore = this.pendingProjects;
        const projectsNow = projectsBefore && this.projectKeys();
        const moved = projectsNow !== undefined && [...projectsNow].some(([uri, key]) => projectsBefore!.has(uri) && projectsBefore!.get(uri) !== key);
        const relink = all.filter((doc) => settled(doc) && (moved || this.exportsAny(doc, namesNow)));
        // files whose project-wide diagnostics depend on a fact the changed files contribute: validation only
        const revalidate = [...projectDependents(factsBefore, factsOf(after), all)].filter((doc) => settled(doc) && !relink.includes(doc));
        for (const doc of relink) this.resetToState(doc, DocumentState.ComputedScopes);
        for (const doc of revalidate) this.resetToState(doc, DocumentState.IndexedReferences);
        // from here a cancelled build is resumed by the next update (it rebuilds every document not validated)
        this.pendingFacts.clear();
        this.pendingProjects = undefined;
        if (relink.length + revalidate.length > 0) {
            await this.buildDocuments([...relink, ...revalidate], this.updateBuildOptions, cancelToken);
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

    /**
     * The given URIs (with their document, if the workspace has one) and the workspace's documents
     * under them (a changed or deleted URI may be a folder), by URI string.
     */
    private documentsAt(uris: string[]): Map<string, LangiumDocument | undefined> {
        const found = new Map<string, LangiumDocument | undefined>();
        const others: string[] = [];
        for (const u of uris) {
            const uri = URI.parse(u);
            if (this.langiumDocuments.hasDocument(uri)) found.set(u, this.langiumDocuments.getDocument(uri));
            else {
                found.set(u, undefined);
                others.push(u);
            }
        }
        if (others.length === 0) return found;
        const folders = others.map((u) => (u.endsWith('/') ? u : `${u}/`));
        for (const doc of this.langiumDocuments.all) {
            const uri = doc.uri.toString();
            if (found.has(uri) || folders.some((f) => uri.startsWith(f))) found.set(uri, doc);
        }
        return found;
    }

    /** The project of every document (projects.ts), by URI string. */
    private projectKeys(): Map<string, string> {
        return this.keysBy((projects, uri) => projects.keyOf(uri));
    }

    /** The project every document was last found in (not worked out again: the layout as the last build saw it). */
    private lastProjectKeys(): Map<string, string> {
        return this.keysBy((projects, uri) => projects.lastKeyOf(uri));
    }

    private keysBy(key: (projects: CactalServices['projects']['Projects'], uri: URI) => string | undefined): Map<string, string> {
        const keys = new Map<string, string>();
        for (const doc of this.langiumDocuments.all) {
            if (!this.serviceRegistry.hasServices(doc.uri)) continue;
            const services = this.serviceRegistry.getServices(doc.uri) as Partial<CactalServices>;
            const k = services.projects && key(services.projects.Projects, doc.uri);
            if (k !== undefined) keys.set(doc.uri.toString(), k);
        }
        return keys;
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
