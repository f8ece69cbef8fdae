/** Messages for unresolved references: what was written, and what would be valid in that context. */
import { AstUtils, type ReferenceInfo } from 'langium';
import {
    isActivateSchema, isActivateSupervisor, isDataCommunication, isDurationEvent, isEndofEvent,
    isEventCommunication, isFieldSegment, isFunctionArgumentAssignment, isFunctionParameter, isLocalBlock,
    isModule, isModuleEvent, isModuleInstance, isNotify, isParameterize, isParameterSetting, isSchema,
    isSchemaArgument, isStartedEvent, isArrayDimension, isIndexSegment, isEnumType, isSubscribe, isSupervisionFunction, isSupervisor, isTypeRef, isVariableRef,
    type Module, type Supervisor
} from '../generated/ast.js';
import { parametersOf, rulesOf } from '../model/blocks.js';
import { portsOfKind, type PortDirection, type PortKind } from '../model/ports.js';
import { typeName, typeOfPathPrefix } from '../model/types.js';
import { closestName } from '../scenario/did-you-mean.js';

const TOP_LEVEL_WORDS: Record<string, string> = {
    DataType: 'datatype', FunctionPrototype: 'function', Module: 'module', Supervisor: 'supervisor',
    Schema: 'schema', EventSource: 'module or supervisor'
};

function list(items: string[]): string {
    return items.length ? items.join(', ') : 'none';
}

/** ` Did you mean 'X'?` for the closest of `names` (scenario/did-you-mean.ts: within 1-3 edits), or ''. */
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
 * cause is reported already.
 */
export function describeUnresolved(info: ReferenceInfo, refText: string, fallback: string): string | undefined {
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
    if (isVariableRef(c)) {
        const fn = AstUtils.getContainerOfType(c, isSupervisionFunction);
        if (fn) {
            if (AstUtils.getContainerOfType(c, isFunctionParameter)) {
                return `'${refText}': a function parameter's default value is a constant.`;
            }
            if (AstUtils.getContainerOfType(c, isLocalBlock)) {
                return `Unknown variable '${refText}': a local is initialised from constants and the parameters of ${fn.name} (${list(fn.parameters.map((q) => q.name))}).`;
            }
            return `Unknown variable '${refText}': rules use the locals of ${fn.name} and the event-port variables of its supervisor.`;
        }
        const schema = AstUtils.getContainerOfType(c, isSchema);
        if (schema) {
            return `Unknown variable '${refText}': a module parameterisation uses constants and the parameters of schema ${schema.name} (${list(schema.parameters.map((q) => q.name))}).`;
        }
        return `'${refText}' is not a constant: only constant values (numbers, strings, true/false, {...}, enumeration members, named constants) are allowed here.`;
    }
    const type = info.container && TOP_LEVEL_WORDS[refTypeOf(info)];
    if (type) return `Unknown ${type} '${refText}': no ${type} of this name is defined in this file or in a file it imports.`;
    return fallback;
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
