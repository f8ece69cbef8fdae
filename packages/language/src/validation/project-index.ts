/**
 * Project-wide name tables (datatypes, functions, modules + supervisors, schemas), computed once
 * per workspace build from the index and shared by the uniqueness checks.
 */
import { MultiMap, WorkspaceCache, type AstNode, type AstNodeDescription, type LangiumCoreServices } from 'langium';

export class ProjectNames {
    private readonly cache: WorkspaceCache<string, MultiMap<string, AstNodeDescription>>;
    private readonly nodeCache: WorkspaceCache<string, AstNode[]>;

    constructor(private readonly services: LangiumCoreServices) {
        this.cache = new WorkspaceCache(services.shared);
        this.nodeCache = new WorkspaceCache(services.shared);
    }

    /** The AST nodes of every exported element of type `type` (the index's descriptions, resolved in their documents). */
    nodesOf(type: string): AstNode[] {
        return this.nodeCache.get(type, () => {
            const nodes: AstNode[] = [];
            const documents = this.services.shared.workspace.LangiumDocuments;
            const locator = this.services.workspace.AstNodeLocator;
            for (const d of this.byName([type]).values()) {
                const node = d.node ?? (documents.hasDocument(d.documentUri) ? locator.getAstNode(documents.getDocument(d.documentUri)!.parseResult.value, d.path) : undefined);
                if (node) nodes.push(node);
            }
            return nodes;
        });
    }

    /** Descriptions of every exported element of the given types, grouped by name. */
    byName(types: string[]): MultiMap<string, AstNodeDescription> {
        const key = types.join('|');
        return this.cache.get(key, () => {
            const map = new MultiMap<string, AstNodeDescription>();
            const index = this.services.shared.workspace.IndexManager;
            for (const type of types) {
                for (const d of index.allElements(type)) {
                    if (d.type === type) map.add(d.name, d);
                }
            }
            return map;
        });
    }
}
