/** Messages for unresolved references: what was written, and what would be valid in that context. */
import { AstUtils, type ReferenceInfo } from 'langium';
import {
    isActivateSchema, isActivateSupervisor, isDataCommunication, isDurationEvent, isEndofEvent,
    isEventCommunication, isFieldSegment, isFunctionArgumentAssignment, isFunctionParameter, isLocalBlock,
    isModule, isModuleEvent, isModuleInstance, isNotify, isParameterize, isParameterSetting, isSchema,
    isSchemaArgument, isStartedEvent, isExtraction, isArrayDimension, isIndexSegment, isEnumType, isSubscribe, isSupervisionFunction, isSupervisor, isTypeRef, isVariableRef,
    type Module, type Supervisor, type VariableRef
} from '../generated/ast.js';
import { localsOf, parametersOf, rulesOf } from '../model/blocks.js';
import { portsOfKind, type PortDirection, type PortKind } from '../model/ports.js';
import { typeName, typeOfPathPrefix } from '../model/types.js';
import { closestName } from '../model/near-names.js';

const TOP_LEVEL_WORDS: Record<string, string> = {
    DataType: 'datatype', FunctionPrototype: 'function', Module: 'module', Supervisor: 'supervisor',
    Schema: 'schema', EventSource: 'module or supervisor'
};

function list(items: string[]): string {
    return items.length ? items.join(', ') : 'none';
}

/** ` Did you mean 'X'?` for the closest of `names` (model/near-names.ts: within 1-3 edits, a swap of two letters one), or ''. */
export function nearName(written: string, names: Iterable<string | undefined>): string {
    // a name left undefined by a syntax error is no candidate
    const near = closestName(written, [...names].filter((n): n is string => typeof n === 'string' && n !== ''));
    return near ? ` Did you mean '${near}'?` : '';
}

function portMessage(owner: Module | Supervisor | undefined, index: string, kind: PortKind, direction: PortDirection): string | undefined {
    const what = `${direction === 'in' ? 'input' : 'output'} ${kind} port`;
    if (!owner) return undefined;
    const available = portsOfKind(owner, kind, direction).map((p) => `:${p.index} ${p.name}`);
    return `${owner.name} has no ${what} ${index}; its ${what}s: ${list(available)}.`;
}

/**
 * The message for an unresolved reference, or undefined when it only fails because what it
 * depends on is unresolved (a port of an unknown module, a field of an unknown variable): that
 * cause is reported already. `globals`: the names of the project's top-level elements of the
 * reference's type (for a variable: its constants and enumerations), candidates for "Did you mean".
 */
export function describeUnresolved(info: ReferenceInfo, refText: string, fallback: string, globals: readonly string[] = []): string | undefined {
    const c = info.container;
    const p = info.property;
    if (isTypeRef(c)) {
        return `Unknown type '${refText}': expected int, float, string, bool or a datatype or enumeration defined in this file or in a file it imports.`;
    }
    if (isArrayDimension(c) || isIndexSegment(c)) {
        return `Unknown constant '${refText}': ${isArrayDimension(c) ? 'an array size' : 'an index'} is an integer or an int constant (const int N = 6;) defined in this file or in a file it imports.`;
    }
    if (isParameterSetting(c)) {
        const owner = c.$container;
        const module = isModuleInstance(owner) || isParameterize(owner) ? owner.module?.ref : undefined;
        if (!isModule(module)) return undefined;
        return `${module.name} has no parameter port ${refText}; its parameters: ${list(parametersOf(module).map((q) => `:${q.index} ${q.name}`))}.`;
    }
    if (isDataCommunication(c) && (p === 'sourcePort' || p === 'targetPort')) {
        return p === 'sourcePort' ? portMessage(c.source?.ref, refText, 'data', 'out') : portMessage(c.target?.ref, refText, 'data', 'in');
    }
    if (isEventCommunication(c) && (p === 'sourcePort' || p === 'targetPort')) {
        return p === 'sourcePort' ? portMessage(c.source?.ref, refText, 'event', 'out') : portMessage(c.target?.ref, refText, 'event', 'in');
    }
    if (isModuleEvent(c) && p === 'port') return portMessage(c.source?.ref, refText, 'event', 'out');
    if (isSubscribe(c) && p === 'sourcePort') return portMessage(c.source?.ref, refText, 'event', 'out');
    if (isSubscribe(c) && p === 'targetPort') return portMessage(AstUtils.getContainerOfType(c, isSupervisor), refText, 'event', 'in');
    if (isNotify(c) && p === 'port') return portMessage(AstUtils.getContainerOfType(c, isSupervisor), refText, 'event', 'out');
    if (isSchemaArgument(c)) {
        const schema = isActivateSchema(c.$container) ? c.$container.schema?.ref : undefined;
        return schema
            ? `Schema ${schema.name} has no parameter '${refText}'; its parameters: ${list(schema.parameters.map((q) => q.name))}.${nearName(refText, schema.parameters.map((q) => q.name))}`
            : undefined;
    }
    if (isActivateSupervisor(c) && p === 'function') {
        const sup = c.supervisor?.ref;
        return sup
            ? `Supervisor ${sup.name} has no function '${refText}'; its functions: ${list(sup.functions.map((f) => f.name))}.${nearName(refText, sup.functions.map((f) => f.name))}`
            : undefined;
    }
    if (isFunctionArgumentAssignment(c)) {
        const fn = isActivateSupervisor(c.$container) ? c.$container.function?.ref : undefined;
        return fn
            ? `Function ${fn.name} has no parameter '${refText}'; its parameters: ${list(fn.parameters.map((q) => q.name))}.${nearName(refText, fn.parameters.map((q) => q.name))}`
            : undefined;
    }
    if (isStartedEvent(c) || isEndofEvent(c) || isDurationEvent(c)) {
        const fn = AstUtils.getContainerOfType(c, isSupervisionFunction);
        return `No rule labelled '${refText}' in function ${fn?.name ?? '?'}; its labels: ${list(fn ? rulesOf(fn).map((r) => r.name) : [])}.${nearName(refText, fn ? rulesOf(fn).map((r) => r.name) : [])}`;
    }
    if (isFieldSegment(c)) {
        const ref = c.$container;
        if (isVariableRef(ref)) {
            const head = ref.variable?.ref;
            if (isEnumType(head) && (c.$containerIndex ?? 0) === 0) {
                return `'${refText}' is not a member of enumeration ${head.name}; its members: ${list(head.members.map((m) => m.name))}.${nearName(refText, head.members.map((m) => m.name))}`;
            }
            const type = typeOfPathPrefix(ref, c.$containerIndex ?? 0);
            if (type.kind === 'struct') {
                return `'${refText}' is not a field of ${type.datatype.name}; its fields: ${list(type.datatype.fields.map((f) => f.name))}.${nearName(refText, type.datatype.fields.map((f) => f.name))}`;
            }
            if (type.kind === 'primitive' || type.kind === 'enum' || type.kind === 'array') {
                return `'${refText}': a value of type ${typeName(type)} has no fields${type.kind === 'array' ? ' (an element is written [i])' : ''}.`;
            }
        }
        return undefined; // the variable or an earlier field is unresolved
    }
    if (isVariableRef(c)) return unknownVariable(c, refText, globals);
    const type = info.container && TOP_LEVEL_WORDS[refTypeOf(info)];
    if (type) return `Unknown ${type} '${refText}': no ${type} of this name is defined in this file or in a file it imports.`;
    return fallback;
}

/**
 * An unknown variable: what may be named there, and the nearest of those names (constants and
 * enumerations, `globals`, included; the implicit `ord_schema` where it is valid: the tests and
 * extracted values of an ORD:0/ORD:1 event).
 */
function unknownVariable(ref: VariableRef, refText: string, globals: readonly string[]): string {
    const fn = AstUtils.getContainerOfType(ref, isSupervisionFunction);
    if (fn) {
        if (AstUtils.getContainerOfType(ref, isFunctionParameter)) {
            return `'${refText}': a function parameter's default value is a constant.${nearName(refText, globals)}`;
        }
        const parameters = fn.parameters.map((q) => q.name);
        if (AstUtils.getContainerOfType(ref, isLocalBlock)) {
            return `Unknown variable '${refText}': a local is initialised from constants and the parameters of ${fn.name} (${list(parameters)}).${nearName(refText, [...parameters, ...globals])}`;
        }
        const locals = localsOf(fn).map((l) => l.name);
        const sup = fn.$container;
        const ports = isSupervisor(sup) ? sup.eventFlows.flatMap((b) => b.ports) : [];
        const extraction = isExtraction(ref.$container) ? ref.$container : undefined;
        if (extraction?.target === ref) {
            const owner = extraction.$container;
            // an event's extraction assigns a local; a notify's, the variable of its port
            if (isModuleEvent(owner)) {
                return `Unknown variable '${refText}': an extraction assigns a local of ${fn.name} (${list(locals)}).${nearName(refText, locals)}`;
            }
            if (isNotify(owner) && owner.port?.ref) {
                return `Unknown variable '${refText}': notify :${owner.port.ref.index} assigns the variable of that port, '${owner.port.ref.name}'.${nearName(refText, [owner.port.ref.name])}`;
            }
        }
        const ord = AstUtils.getContainerOfType(ref, isModuleEvent)?.ord === true;
        const names = [...locals, ...ports.map((q) => q.name), ...(ord ? ['ord_schema'] : []), ...globals];
        const what = `rules use the locals of ${fn.name}, the event-port variables of its supervisor and constants`;
        return ord
            ? `Unknown variable '${refText}': ${what}; in this ORD event, also 'ord_schema' (the name of the schema it is about).${nearName(refText, names)}`
            : `Unknown variable '${refText}': ${what}.${nearName(refText, names)}`;
    }
    const schema = AstUtils.getContainerOfType(ref, isSchema);
    if (schema) {
        const parameters = schema.parameters.map((q) => q.name);
        return `Unknown variable '${refText}': a module parameterisation uses constants and the parameters of schema ${schema.name} (${list(parameters)}).${nearName(refText, [...parameters, ...globals])}`;
    }
    return `'${refText}' is not a constant: only constant values (numbers, strings, true/false, {...}, enumeration members, named constants) are allowed here.${nearName(refText, globals)}`;
}

function refTypeOf(info: ReferenceInfo): string {
    const c = info.container;
    const p = info.property;
    if (isModuleEvent(c) || isSubscribe(c)) return 'EventSource';
    if (isActivateSupervisor(c) && p === 'supervisor') return 'Supervisor';
    if (isActivateSchema(c)) return 'Schema';
    if (c.$type === 'SchedulerSchemas') return 'Schema';
    if (c.$type === 'FunctionTest' || c.$type === 'Compute') return 'FunctionPrototype';
    return 'Module';
}
