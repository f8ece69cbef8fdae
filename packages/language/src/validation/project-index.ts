/**
 * Project-wide name tables (datatypes, functions, modules + supervisors, schemas), computed once
 * per workspace build from the index and shared by the uniqueness checks.
 */
import { MultiMap, WorkspaceCache, type AstNodeDescription, type LangiumCoreServices } from 'langium';

export class ProjectNames {
    private readonly cache: WorkspaceCache<string, MultiMap<string, AstNodeDescription>>;

    constructor(private readonly services: LangiumCoreServices) {
        this.cache = new WorkspaceCache(services.shared);
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
