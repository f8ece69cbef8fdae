/**
 * Scoping of every Cactal cross-reference (docs/language-reference.md §1–6):
 * - top-level names (types, functions, modules, supervisors, schemas): the file and its direct imports;
 * - ports by index in the context of their owner, kind and direction (`MSC:1 -> MSD:2`);
 * - members: schema parameters, supervision functions and their parameters, rule labels;
 * - variables by context (schema parameters in a schema; parameters, locals and the supervisor's
 *   port variables in a supervision function) and field paths by the type of the path so far.
 */
import {
    AstUtils, DefaultScopeProvider, EMPTY_SCOPE, MultiMapScope, WorkspaceCache, stream,
    type AstNode, type AstNodeDescription, type ReferenceInfo, type Scope, type Stream
} from 'langium';
import {
    isActivateSchema, isActivateSupervisor, isDataCommunication, isEventCommunication, isFieldSegment,
    isFunctionArgumentAssignment, isLocalBlock, isModule, isModuleEvent, isModuleInstance, isNotify,
    isParameterize, isParameterSetting, isSchema, isSchemaArgument, isSubscribe, isSupervisionFunction,
    isSupervisor, isVariableRef, isEnumType, isDurationEvent, isEndofEvent, isStartedEvent, isFunctionParameter,
    type Module, type Port, type Supervisor
} from '../generated/ast.js';
import { localsOf, parametersOf, rulesOf } from '../model/blocks.js';
import { portsOfKind, type PortDirection, type PortKind } from '../model/ports.js';
import { typeOfPathPrefix } from '../model/types.js';
import type { CactalServices } from '../cactal-module.js';
import type { ImportResolver } from './import-resolver.js';
import { MemberScopes } from './member-scopes.js';

/**
 * Scope of ports (or parameters) named by their index. Descriptions are created only for what is
 * asked: linking needs one element, completion all of them.
 */
class IndexScope implements Scope {
    constructor(
        private readonly nodes: Array<AstNode & { index: number }>,
        private readonly describe: (node: AstNode, name: string) => AstNodeDescription
    ) {}

    getElement(name: string): AstNodeDescription | undefined {
        const node = this.nodes.find((n) => typeof n.index === 'number' && String(n.index) === name);
        return node ? this.describe(node, name) : undefined;
    }

    getElements(name: string): Stream<AstNodeDescription> {
        return stream(this.nodes.filter((n) => typeof n.index === 'number' && String(n.index) === name)).map((n) => this.describe(n, name));
    }

    getAllElements(): Stream<AstNodeDescription> {
        return stream(this.nodes.filter((n) => typeof n.index === 'number')).map((n) => this.describe(n, String(n.index)));
    }
}

export class CactalScopeProvider extends DefaultScopeProvider {
    private readonly imports: ImportResolver;
    /** Visible top-level scope per (document, reference type), rebuilt after every workspace change. */
    private readonly visibleScopes: WorkspaceCache<string, Scope>;
    /** Scopes of the names declared in an element, made once per element and build (member-scopes.ts). */
    readonly memberScopes: MemberScopes;

    constructor(services: CactalServices) {
        super(services);
        this.imports = services.imports.ImportResolver;
        this.visibleScopes = new WorkspaceCache(services.shared);
        this.memberScopes = new MemberScopes(services.shared, this.nameProvider, this.descriptions);
    }

    override getScope(context: ReferenceInfo): Scope {
        const { container, property } = context;

        if (isFieldSegment(container)) return this.fieldScope(container);
        if (isVariableRef(container)) return this.variableScope(container, this.visibleScope(context));

        // ports by index
        if (isParameterSetting(container)) {
            const owner = container.$container;
            const module = isModuleInstance(owner) || isParameterize(owner) ? owner.module?.ref : undefined;
            return isModule(module) ? this.indexScope(parametersOf(module)) : EMPTY_SCOPE;
        }
        if (isDataCommunication(container)) {
            return property === 'sourcePort'
                ? this.portScope(container.source?.ref, 'data', 'out')
                : property === 'targetPort' ? this.portScope(container.target?.ref, 'data', 'in') : this.visibleScope(context);
        }
        if (isEventCommunication(container)) {
            return property === 'sourcePort'
                ? this.portScope(container.source?.ref, 'event', 'out')
                : property === 'targetPort' ? this.portScope(container.target?.ref, 'event', 'in') : this.visibleScope(context);
        }
        if (isModuleEvent(container) && property === 'port') return this.portScope(container.source?.ref, 'event', 'out');
        if (isSubscribe(container)) {
            if (property === 'sourcePort') return this.portScope(container.source?.ref, 'event', 'out');
            if (property === 'targetPort') return this.portScope(AstUtils.getContainerOfType(container, isSupervisor), 'event', 'in');
        }
        if (isNotify(container) && property === 'port') {
            return this.portScope(AstUtils.getContainerOfType(container, isSupervisor), 'event', 'out');
        }

        // members
        if (isSchemaArgument(container)) {
            const schema = isActivateSchema(container.$container) ? container.$container.schema?.ref : undefined;
            return schema ? this.memberScopes.get(schema, 'parameters', () => schema.parameters) : EMPTY_SCOPE;
        }
        if (isActivateSupervisor(container) && property === 'function') {
            const sup = container.supervisor?.ref;
            return sup ? this.memberScopes.get(sup, 'functions', () => sup.functions) : EMPTY_SCOPE;
        }
        if (isFunctionArgumentAssignment(container)) {
            const fn = isActivateSupervisor(container.$container) ? container.$container.function?.ref : undefined;
            return fn ? this.memberScopes.get(fn, 'parameters', () => fn.parameters) : EMPTY_SCOPE;
        }
        if (isStartedEvent(container) || isEndofEvent(container) || isDurationEvent(container)) {
            const fn = AstUtils.getContainerOfType(container, isSupervisionFunction);
            return fn ? this.memberScopes.get(fn, 'labels', () => rulesOf(fn)) : EMPTY_SCOPE;
        }

        // top-level names through imports
        return this.visibleScope(context);
    }

    /** Top-level elements of the reference's type defined in the file or its direct imports. */
    visibleScope(context: ReferenceInfo): Scope {
        const type = this.reflection.getReferenceType(context);
        const document = AstUtils.getDocument(context.container);
        const key = `${document.uri.toString()}\u0000${type}`;
        return this.visibleScopes.get(key, () => {
            const uris = this.imports.visibleUris(context.container);
            return new MultiMapScope(this.visibleElements(type, [...uris]));
        });
    }

    /** Exported elements of `type` in the given documents (own document first). */
    private visibleElements(type: string, uris: string[]): AstNodeDescription[] {
        const index = this.indexManager as unknown as { getFileDescriptions?: (uri: string, type: string) => AstNodeDescription[] };
        if (typeof index.getFileDescriptions === 'function') {
            return uris.flatMap((uri) => index.getFileDescriptions!(uri, type));
        }
        return this.indexManager.allElements(type, new Set(uris)).toArray();
    }

    /** Ports of an owner, named by their index. */
    private portScope(owner: Module | Supervisor | undefined, kind: PortKind, direction: PortDirection): Scope {
        if (!owner || (!isModule(owner) && !isSupervisor(owner))) return EMPTY_SCOPE;
        return this.indexScope(portsOfKind(owner, kind, direction));
    }

    private indexScope(nodes: Array<Port | { index: number } & AstNode>): Scope {
        return new IndexScope(nodes, (node, name) => this.descriptions.createDescription(node, name));
    }

    /**
     * Variables of the context, then (outer scope) the constants and enumerations visible from
     * the file (extension: `NJOINTS`, `Mode.AUTO` are written like variables).
     */
    private variableScope(ref: AstNode, globals: Scope): Scope {
        const fn = AstUtils.getContainerOfType(ref, isSupervisionFunction);
        if (fn) {
            if (AstUtils.getContainerOfType(ref, isFunctionParameter)) return globals; // defaults are constants
            if (AstUtils.getContainerOfType(ref, isLocalBlock)) return this.memberScopes.get(fn, 'locals', () => fn.parameters, globals);
            // locals first, then the supervisor's port variables, then parameters (rules may not use
            // them: validation reports it with a clear message rather than "unresolved").
            return this.memberScopes.get(fn, 'rules', () => {
                const sup = fn.$container;
                const ports = isSupervisor(sup) ? sup.eventFlows.flatMap((b) => b.ports) : [];
                return [...localsOf(fn), ...ports, ...fn.parameters];
            }, globals);
        }
        const schema = AstUtils.getContainerOfType(ref, isSchema);
        if (schema) return this.memberScopes.get(schema, 'variables', () => schema.parameters, globals);
        return globals;
    }

    private fieldScope(segment: AstNode & { $containerIndex?: number; $container: AstNode }): Scope {
        const ref = segment.$container;
        if (!isVariableRef(ref)) return EMPTY_SCOPE;
        const index = segment.$containerIndex ?? ref.path.indexOf(segment as never);
        const head = ref.variable?.ref;
        if (index === 0 && isEnumType(head)) return this.memberScopes.get(head, 'members', () => head.members);
        const type = typeOfPathPrefix(ref, index);
        return type.kind === 'struct' ? this.memberScopes.get(type.datatype, 'fields', () => type.datatype.fields) : EMPTY_SCOPE;
    }
}
