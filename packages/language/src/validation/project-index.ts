/**
 * Project-wide name tables (datatypes, functions, modules + supervisors, schemas), computed once
 * per workspace build from the index and shared by the uniqueness checks. A table holds the names
 * of one project: the project of the document asking (scoping/projects.ts).
 */
import { AstUtils, MultiMap, WorkspaceCache, type AstNode, type AstNodeDescription, type URI } from 'langium';
import type { CactalServices } from '../cactal-module.js';
import { otherLocations } from './locations.js';

export class ProjectNames {
    private readonly cache: WorkspaceCache<string, Map<string, MultiMap<string, AstNodeDescription>>>;
    private readonly nodeCache: WorkspaceCache<string, AstNode[]>;

    constructor(private readonly services: CactalServices) {
        this.cache = new WorkspaceCache(services.shared);
        this.nodeCache = new WorkspaceCache(services.shared);
    }

    /** The AST nodes of every exported element of type `type` in the project of `context`. */
    nodesOf(type: string, context: AstNode): AstNode[] {
        const project = this.projectOf(context);
        return this.nodeCache.get(`${project}\u0000${type}`, () => {
            const nodes: AstNode[] = [];
            const documents = this.services.shared.workspace.LangiumDocuments;
            const locator = this.services.workspace.AstNodeLocator;
            for (const d of this.byName([type], context).values()) {
                const node = d.node ?? (documents.hasDocument(d.documentUri) ? locator.getAstNode(documents.getDocument(d.documentUri)!.parseResult.value, d.path) : undefined);
                if (node) nodes.push(node);
            }
            return nodes;
        });
    }

    /** Descriptions of every exported element of the given types in the project of `context`, grouped by name. */
    byName(types: string[], context: AstNode): MultiMap<string, AstNodeDescription> {
        const tables = this.byProject(types);
        const project = this.projectOf(context);
        let table = tables.get(project);
        // kept, empty: the same table for the whole build (identifier-checks.ts keys its caches with it)
        if (!table) tables.set(project, table = new MultiMap());
        return table;
    }

    /** The tables of `types` of every project, made in one pass over the index. */
    private byProject(types: string[]): Map<string, MultiMap<string, AstNodeDescription>> {
        return this.cache.get(types.join('|'), () => {
            const tables = new Map<string, MultiMap<string, AstNodeDescription>>();
            const index = this.services.shared.workspace.IndexManager;
            const projects = this.services.projects.Projects;
            for (const type of types) {
                for (const d of index.allElements(type)) {
                    if (d.type !== type) continue;
                    const project = projects.keyOf(d.documentUri);
                    let table = tables.get(project);
                    if (!table) tables.set(project, table = new MultiMap());
                    table.add(d.name, d);
                }
            }
            return tables;
        });
    }

    /** Where the other occurrences of `node`'s name are, for its message (locations.ts). */
    otherLocations(node: AstNode, occurrences: URI[]): string {
        return otherLocations(this.services.projects.Projects, AstUtils.getDocument(node).uri, occurrences);
    }

    private projectOf(context: AstNode): string {
        return this.services.projects.Projects.keyOf(AstUtils.getDocument(context).uri);
    }
}
