/**
 * Which project a document belongs to, by the rule of `contract generate`, a build and the IDE
 * (conventions' project-root.ts, docs/codegen.md "Where a project is"): names, references and the
 * project-wide checks (duplicates, one scheduler configuration, C-name clashes, ...) look at the
 * documents of the same project only, so a workspace holding several projects (`contract serve
 * examples`, `contract check examples`) shows each one's diagnostics as if it were alone.
 *
 * The opened folders are the workspace folders (a language server) or the DIR `loadWorkspace` was
 * given; a document outside them (a library imported from `../lib`) belongs to the project of a
 * document importing it. Without any opened folder every document is one project.
 */
import { UriUtils, URI, WorkspaceCache, type IndexManager, type LangiumDocument, type LangiumSharedCoreServices } from 'langium';
import { SRC_GEN_DIR, projectRootFinder, type ProjectRoot } from '@contract-studio/conventions';
import { isModel } from '../generated/ast.js';

/** `folder` holds a generated tree (a `src-gen/` folder): the project's root by rule 1. */
export type FolderTreeProbe = (folder: URI) => boolean;

/** The part of the index that the name rules read, as seen from one project. */
export type ProjectIndex = { allElements(type?: string): ReturnType<IndexManager['allElements']> };

/** The key of the one project of a workspace without opened folders. */
const NO_FOLDER = '';

export class CactalProjects {
    private opened: URI[] | undefined;
    private probe: FolderTreeProbe;
    private listed: ((folder: URI) => readonly string[]) | undefined;
    /** Per workspace build: project key by document URI, tree probes by folder, the rule by opened folder. */
    private readonly keys: WorkspaceCache<string, string>;
    private readonly trees: WorkspaceCache<string, boolean>;
    private readonly finders: WorkspaceCache<string, (path: string) => ProjectRoot>;
    /** The last project key found for each document URI (lastKeyOf). */
    private readonly known = new Map<string, string>();

    constructor(private readonly shared: LangiumSharedCoreServices) {
        this.keys = new WorkspaceCache(shared);
        this.trees = new WorkspaceCache(shared);
        this.finders = new WorkspaceCache(shared);
        const fs = shared.workspace.FileSystemProvider;
        this.probe = (folder) => {
            try {
                return fs.statSync(UriUtils.joinPath(folder, SRC_GEN_DIR)).isDirectory;
            } catch {
                return false;
            }
        };
    }

    /**
     * The opened folders (the DIR of `contract check`), instead of the workspace manager's folders;
     * `probe` says which folders hold a generated tree where the file system cannot, and
     * `contractFiles` which `.contract` files an opened folder holds (relative to it) when the
     * workspace's documents may not be all of them yet: the IDE's language worker is told both by
     * the IDE, which lists the tree, before the files are opened one by one.
     */
    configure(options: { openedFolders?: URI[]; probe?: FolderTreeProbe; contractFiles?: (folder: URI) => readonly string[] }): void {
        if (options.openedFolders) this.opened = options.openedFolders;
        if (options.probe) this.probe = options.probe;
        if (options.contractFiles) this.listed = options.contractFiles;
        this.keys.clear();
        this.trees.clear();
        this.finders.clear();
    }

    /** The project of the document at `uri`: its root folder's URI as a string ('' when nothing is opened). */
    keyOf(uri: URI): string {
        const key = uri.toString();
        return this.keys.get(key, () => {
            const project = this.compute(uri, new Set());
            this.known.set(key, project);
            return project;
        });
    }

    /**
     * The project the document at `uri` was last found in (undefined if never asked): kept across
     * workspace builds, unlike keyOf's answers, so an update can compare with the layout as it was
     * before it even when an earlier update that changed it was cancelled (the document builder).
     */
    lastKeyOf(uri: URI): string | undefined {
        return this.known.get(uri.toString());
    }

    /** The root folder of the document's project, if there is one. */
    rootOf(uri: URI): URI | undefined {
        const key = this.keyOf(uri);
        return key === NO_FOLDER ? undefined : URI.parse(key);
    }

    /** Whether the documents at `a` and `b` are of the same project. */
    sameProject(a: URI, b: URI): boolean {
        return a.toString() === b.toString() || this.keyOf(a) === this.keyOf(b);
    }

    /** The workspace's documents of the project of `uri`. */
    documentsOf(uri: URI): LangiumDocument[] {
        const key = this.keyOf(uri);
        return this.shared.workspace.LangiumDocuments.all.filter((d) => this.keyOf(d.uri) === key).toArray();
    }

    /** The index's elements of the project of `uri` only (what a name given there may clash with). */
    indexOf(uri: URI): ProjectIndex {
        const index = this.shared.workspace.IndexManager;
        return { allElements: (type) => index.allElements(type).filter((d) => this.sameProject(d.documentUri, uri)) };
    }

    private openedFolders(): URI[] {
        return this.opened ?? (this.shared.workspace.WorkspaceManager.workspaceFolders ?? []).map((f) => URI.parse(f.uri));
    }

    private compute(uri: URI, seen: Set<string>): string {
        const folders = this.openedFolders();
        if (folders.length === 0) return NO_FOLDER;
        const text = uri.toString();
        const folder = folders
            .filter((f) => text.startsWith(`${f.toString().replace(/\/$/, '')}/`))
            .sort((a, b) => b.toString().length - a.toString().length)[0];
        if (!folder) return this.importerKey(uri, seen) ?? NO_FOLDER;
        const path = decodeURIComponent(text.slice(folder.toString().replace(/\/$/, '').length + 1));
        const { root } = this.finderOf(folder)(path);
        return (root ? UriUtils.joinPath(folder, root) : folder).toString().replace(/\/$/, '');
    }

    /** A document outside the opened folders: the project of the first document (in URI order) importing it. */
    private importerKey(uri: URI, seen: Set<string>): string | undefined {
        const target = uri.toString();
        if (seen.has(target)) return undefined;
        seen.add(target);
        const importers = this.shared.workspace.LangiumDocuments.all
            .filter((d) => {
                const model = d.parseResult?.value;
                if (!isModel(model)) return false;
                const dir = UriUtils.dirname(d.uri);
                return model.imports.some((i) => i.path !== undefined && UriUtils.resolvePath(dir, i.path).toString() === target);
            })
            .map((d) => d.uri)
            .toArray()
            .sort((a, b) => (a.toString() < b.toString() ? -1 : 1));
        for (const importer of importers) {
            const key = this.compute(importer, seen);
            if (key !== NO_FOLDER) return key;
        }
        return undefined;
    }

    private hasTree(folder: URI): boolean {
        return this.trees.get(folder.toString(), () => this.probe(folder));
    }

    /** The rule for the paths of an opened folder, from its `.contract` files (the given list, else its documents). */
    private finderOf(folder: URI): (path: string) => ProjectRoot {
        const base = folder.toString().replace(/\/$/, '');
        return this.finders.get(base, () => {
            const files = this.listed?.(folder) ?? this.shared.workspace.LangiumDocuments.all
                .map((d) => d.uri.toString())
                .filter((u) => u.startsWith(`${base}/`) && u.endsWith('.contract'))
                .map((u) => decodeURIComponent(u.slice(base.length + 1)))
                .toArray();
            return projectRootFinder(files, (f) => this.hasTree(f ? UriUtils.joinPath(folder, f) : folder));
        });
    }
}
