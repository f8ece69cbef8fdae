/**
 * Scopes of the names declared inside an element (a supervision function's locals, port variables
 * and parameters, a schema's parameters, a datatype's fields, an enumeration's members, a function's
 * rule labels), made once per element and workspace build rather than once per reference: a
 * 350-line supervisor has hundreds of variable references in one function's rules, and each one
 * described every local and port again (and searched the lazily described list from its start).
 * Dropped with the other workspace caches on every update (the AST nodes are new after a change).
 */
import { WorkspaceCache, stream, StreamScope, type AstNode, type AstNodeDescription, type AstNodeDescriptionProvider, type LangiumSharedCoreServices, type NameProvider, type Scope } from 'langium';

export class MemberScopes {
    private readonly scopes: WorkspaceCache<AstNode, Map<string, Scope>>;
    /** How many member scopes were made since the services started (what a test counts). */
    made = 0;

    constructor(
        shared: LangiumSharedCoreServices,
        private readonly names: NameProvider,
        private readonly descriptions: AstNodeDescriptionProvider
    ) {
        this.scopes = new WorkspaceCache(shared);
    }

    /**
     * The scope of `nodes()` (in their order, then `outer`) declared in `owner`, for the use `role`
     * (one owner can have several: a function's rules see its locals, its locals its parameters).
     * `outer` must be the same for every call with the same owner and role.
     */
    get(owner: AstNode, role: string, nodes: () => AstNode[], outer?: Scope): Scope {
        let byRole = this.scopes.get(owner);
        if (!byRole) {
            byRole = new Map();
            this.scopes.set(owner, byRole);
        }
        let scope = byRole.get(role);
        if (!scope) {
            const described: AstNodeDescription[] = [];
            for (const node of nodes()) {
                const name = this.names.getName(node);
                if (name) described.push(this.descriptions.createDescription(node, name));
            }
            scope = new StreamScope(stream(described), outer);
            byRole.set(role, scope);
            this.made++;
        }
        return scope;
    }
}
