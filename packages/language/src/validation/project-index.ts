/**
 * Project-wide name tables (datatypes, functions, modules + supervisors, schemas), computed once
 * per workspace build from the index and shared by the uniqueness checks. A table holds the names
 * of one project: the project of the document asking (scoping/projects.ts).
 */
import { AstUtils, MultiMap, WorkspaceCache, type AstNode, type AstNodeDescription, type URI } from 'langium';
import type { CactalServices } from '../cactal-module.js';
import { otherLocations } from './locations.js';

export class ProjectNames {
    private readonly cache: WorkspaceCache<string, MultiMap<string, AstNodeDescription>>;
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
        const project = this.projectOf(context);
        return this.cache.get(`${project}\u0000${types.join('|')}`, () => {
            const map = new MultiMap<string, AstNodeDescription>();
            const index = this.services.shared.workspace.IndexManager;
            const projects = this.services.projects.Projects;
            for (const type of types) {
                for (const d of index.allElements(type)) {
                    if (d.type === type && projects.keyOf(d.documentUri) === project) map.add(d.name, d);
                }
            }
            return map;
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
