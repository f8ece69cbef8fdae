/**
 * A language server given no workspace folder (a client that sends none: Neovim's `root_markers`
 * when no marker is found, an editor opening a lone file) knows only the files it is sent. Then
 * the server reads what they import from disk, as `contract check` does: after each build, every
 * import of a `file:` document that leads to a regular `.contract` file not yet known (at most
 * DEFAULT_MAX_IMPORT_BYTES; a link is followed as the editor's own file system would) is loaded,
 * and so, in turn, are its imports — at most MAX_FOLLOWED files in all. With a workspace folder
 * nothing happens here: the folder's files are the project (docs/editors.md "The root is the
 * project folder").
 */
import { statSync } from 'node:fs';
import { DocumentState, type LangiumDocument, type URI } from 'langium';
import type { LangiumSharedServices } from 'langium/lsp';
import { isModel } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { DEFAULT_MAX_IMPORT_BYTES } from './confined-import.js';

/** Files read from disk for imports, at most, in one server's life (the rest stay `import-missing-file`). */
export const MAX_FOLLOWED = 2000;

/** Whether `uri` is a regular `.contract` file of at most DEFAULT_MAX_IMPORT_BYTES. */
function readableImport(uri: URI): boolean {
    if (uri.scheme !== 'file' || !uri.path.endsWith('.contract')) return false;
    try {
        const st = statSync(uri.fsPath);
        return st.isFile() && st.size <= DEFAULT_MAX_IMPORT_BYTES;
    } catch {
        return false;
    }
}

export function followImportsWithoutFolders(shared: LangiumSharedServices, cactal: CactalServices): void {
    const documents = shared.workspace.LangiumDocuments;
    const builder = shared.workspace.DocumentBuilder;
    let followed = 0;
    let scheduled = false;
    const withoutFolders = () => (shared.workspace.WorkspaceManager.workspaceFolders ?? []).length === 0;

    /** Imports of `docs` that lead to a file not yet loaded, and their importers. */
    const unloaded = (docs: readonly LangiumDocument[]) => {
        const load = new Map<string, URI>();
        const importers = new Map<string, URI>();
        for (const doc of docs) {
            const model = doc.parseResult.value;
            if (doc.uri.scheme !== 'file' || !isModel(model)) continue;
            for (const imp of model.imports) {
                if (imp.path === undefined) continue;
                const target = cactal.imports.ImportResolver.resolveImport(imp);
                const key = target.toString();
                if (documents.hasDocument(target) || load.has(key) || !readableImport(target)) continue;
                load.set(key, target);
                importers.set(doc.uri.toString(), doc.uri);
            }
        }
        return { load: [...load.values()], importers: [...importers.values()] };
    };

    builder.onBuildPhase(DocumentState.Validated, (built) => {
        if (scheduled || followed >= MAX_FOLLOWED || !withoutFolders()) return;
        const { load } = unloaded(built);
        if (!load.length) return;
        scheduled = true;
        // after this build: a new one under the workspace lock, as a change of files is built
        setTimeout(() => {
            void shared.workspace.WorkspaceLock.write(async (token) => {
                scheduled = false;
                const next = unloaded(documents.all.toArray());
                const uris = next.load.slice(0, MAX_FOLLOWED - followed);
                if (!uris.length) return;
                followed += uris.length;
                // the importers again too: their import-missing-file diagnostics go
                await builder.update([...uris, ...next.importers], [], token);
            }).catch(() => { scheduled = false; });
        }, 0);
    });
}
