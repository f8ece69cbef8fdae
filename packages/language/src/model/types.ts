/**
 * Cactal types as seen by validation and code generation: primitives, datatypes (structs), and
 * the type of variables and field paths (`temp_message.value`).
 */
import {
    isDataType, type DataType, type Field, type TypeRef, type Variable, type VariableRef
} from '../generated/ast.js';

export type PrimitiveName = 'int' | 'float' | 'string' | 'bool' | 'void';

export type CactalType =
    | { kind: 'primitive'; name: PrimitiveName }
    | { kind: 'struct'; datatype: DataType }
    /** An unresolved or missing type: checks against it are skipped (the cause is reported elsewhere). */
    | { kind: 'unknown' };

export const UNKNOWN_TYPE: CactalType = { kind: 'unknown' };
export const STRING_TYPE: CactalType = { kind: 'primitive', name: 'string' };

/** The type a TypeRef denotes. */
export function typeOf(ref: TypeRef | undefined): CactalType {
    if (!ref) return UNKNOWN_TYPE;
    if (ref.primitive) return { kind: 'primitive', name: ref.primitive };
    const dt = ref.datatype?.ref;
    return isDataType(dt) ? { kind: 'struct', datatype: dt } : UNKNOWN_TYPE;
}

/** Display name: `int`, `TypeA`, `?`. */
export function typeName(type: CactalType): string {
    switch (type.kind) {
        case 'primitive': return type.name;
        case 'struct': return type.datatype.name;
        default: return '?';
    }
}

/** Written name of a TypeRef even when unresolved. */
export function typeRefText(ref: TypeRef | undefined): string {
    if (!ref) return '?';
    return ref.primitive ?? ref.datatype?.$refText ?? '?';
}

export function isUnknown(type: CactalType): boolean {
    return type.kind === 'unknown';
}

/** Identical types (same primitive or same datatype node). Unknown matches anything. */
export function sameType(a: CactalType, b: CactalType): boolean {
    if (a.kind === 'unknown' || b.kind === 'unknown') return true;
    if (a.kind === 'primitive' && b.kind === 'primitive') return a.name === b.name;
    if (a.kind === 'struct' && b.kind === 'struct') return a.datatype === b.datatype;
    return false;
}

/** True for int and float (they mix in tests). */
export function isNumeric(type: CactalType): boolean {
    return type.kind === 'primitive' && (type.name === 'int' || type.name === 'float');
}

/** Fields of a datatype, in order. */
export function fieldsOf(datatype: DataType): Field[] {
    return datatype.fields;
}

/** The type of a variable (port, parameter, local, ...). */
export function typeOfVariable(variable: Variable | undefined): CactalType {
    return variable ? typeOf(variable.type) : UNKNOWN_TYPE;
}

/**
 * The type of a variable reference with its field path: `temp_message.value` -> TypeA.
 * `ord_schema` is a string. Unresolved segments give the unknown type.
 */
export function typeOfVariableRef(ref: VariableRef): CactalType {
    let type: CactalType = ref.ordSchema ? STRING_TYPE : typeOfVariable(ref.variable?.ref);
    for (const segment of ref.path) {
        const field = segment.field?.ref;
        if (!field) return UNKNOWN_TYPE;
        type = typeOf(field.type);
    }
    return type;
}

/** The type a path prefix (variable + the first `count` segments) has; used by field scoping. */
export function typeOfPathPrefix(ref: VariableRef, count: number): CactalType {
    let type: CactalType = ref.ordSchema ? STRING_TYPE : typeOfVariable(ref.variable?.ref);
    for (const segment of ref.path.slice(0, count)) {
        const field = segment.field?.ref;
        if (!field) return UNKNOWN_TYPE;
        type = typeOf(field.type);
    }
    return type;
}

/** Display text of a variable reference: `temp_message.value`. */
export function variableRefText(ref: VariableRef): string {
    const head = ref.ordSchema ? 'ord_schema' : (ref.variable?.$refText ?? '?');
    return [head, ...ref.path.map((s) => s.field?.$refText ?? '?')].join('.');
}

