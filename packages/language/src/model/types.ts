/**
 * Cactal types as seen by validation and code generation: primitives, datatypes (structs),
 * enumerations and fixed-size arrays (extensions of the report), and the type of variables and
 * paths (`temp_message.value`, `scan.ranges[90]`, `Mode.AUTO`).
 */
import {
    isConstant, isDataType, isEnumType, isFieldSegment, isIndexSegment,
    type ArrayDimension, type DataType, type EnumType, type Field, type IndexSegment, type TypeRef,
    type Variable, type ValueSymbol, type VariableRef
} from '../generated/ast.js';
import { constantInt } from './constants.js';

export type PrimitiveName = 'int' | 'float' | 'string' | 'bool' | 'void';

export type CactalType =
    | { kind: 'primitive'; name: PrimitiveName }
    | { kind: 'struct'; datatype: DataType }
    | { kind: 'enum'; enumType: EnumType }
    /** `float[6]`: `size` elements of `element`; `float[3][4]` is an array of 3 arrays of 4 floats. */
    | { kind: 'array'; element: CactalType; size: number }
    /** An unresolved or missing type: checks against it are skipped (the cause is reported elsewhere). */
    | { kind: 'unknown' };

export const UNKNOWN_TYPE: CactalType = { kind: 'unknown' };
export const STRING_TYPE: CactalType = { kind: 'primitive', name: 'string' };
export const INT_TYPE: CactalType = { kind: 'primitive', name: 'int' };

/** The size an array dimension denotes (an int literal or an int constant); undefined when unknown or invalid. */
export function dimensionSize(dim: ArrayDimension): number | undefined {
    const n = dim.constant ? constantInt(dim.constant.ref) : dim.size;
    return n !== undefined && Number.isInteger(n) && n >= 1 ? n : undefined;
}

/** The index an index segment denotes (an int literal or an int constant). */
export function segmentIndex(segment: IndexSegment): number | undefined {
    return segment.constant ? constantInt(segment.constant.ref) : segment.index;
}

/** The type a TypeRef denotes (arrays wrap the base type, outer dimension first as in C). */
export function typeOf(ref: TypeRef | undefined): CactalType {
    if (!ref) return UNKNOWN_TYPE;
    let type = baseTypeOf(ref);
    const dimensions = ref.dimensions ?? [];
    for (let i = dimensions.length - 1; i >= 0; i--) {
        const size = dimensionSize(dimensions[i]!);
        if (size === undefined || type.kind === 'unknown') return UNKNOWN_TYPE;
        type = { kind: 'array', element: type, size };
    }
    return type;
}

/** The type a TypeRef denotes without its array dimensions. */
export function baseTypeOf(ref: TypeRef): CactalType {
    if (ref.primitive) return { kind: 'primitive', name: ref.primitive };
    const named = ref.datatype?.ref;
    if (isDataType(named)) return { kind: 'struct', datatype: named };
    if (isEnumType(named)) return { kind: 'enum', enumType: named };
    return UNKNOWN_TYPE;
}

/** Display name: `int`, `TypeA`, `Mode`, `float[3][3]`, `?`. */
export function typeName(type: CactalType): string {
    switch (type.kind) {
        case 'primitive': return type.name;
        case 'struct': return type.datatype.name;
        case 'enum': return type.enumType.name;
        case 'array': {
            const sizes: number[] = [];
            let t: CactalType = type;
            while (t.kind === 'array') {
                sizes.push(t.size);
                t = t.element;
            }
            return `${typeName(t)}${sizes.map((n) => `[${n}]`).join('')}`;
        }
        default: return '?';
    }
}

/** Written name of a TypeRef even when unresolved: `float[NJOINTS]`. */
export function typeRefText(ref: TypeRef | undefined): string {
    if (!ref) return '?';
    const base = ref.primitive ?? ref.datatype?.$refText ?? '?';
    return base + (ref.dimensions ?? []).map((d) => `[${d.constant ? d.constant.$refText : d.size}]`).join('');
}

export function isUnknown(type: CactalType): boolean {
    return type.kind === 'unknown';
}

/** Identical types (same primitive, datatype or enumeration node; arrays of the same size and element). Unknown matches anything. */
export function sameType(a: CactalType, b: CactalType): boolean {
    if (a.kind === 'unknown' || b.kind === 'unknown') return true;
    if (a.kind === 'primitive' && b.kind === 'primitive') return a.name === b.name;
    if (a.kind === 'struct' && b.kind === 'struct') return a.datatype === b.datatype;
    if (a.kind === 'enum' && b.kind === 'enum') return a.enumType === b.enumType;
    if (a.kind === 'array' && b.kind === 'array') return a.size === b.size && sameType(a.element, b.element);
    return false;
}

/** True for int and float (they mix in tests). */
export function isNumeric(type: CactalType): boolean {
    return type.kind === 'primitive' && (type.name === 'int' || type.name === 'float');
}

/** Types whose values are ordered by `<`, `>` (numbers, strings, datatypes through inf_/sup_, enumerations by declaration order). */
export function isOrdered(type: CactalType): boolean {
    return type.kind !== 'array' && !(type.kind === 'primitive' && type.name === 'bool');
}

/** Fields of a datatype, in order. */
export function fieldsOf(datatype: DataType): Field[] {
    return datatype.fields;
}

/** The type of a variable (port, parameter, local, ...) or of a constant. */
export function typeOfVariable(variable: Variable | ValueSymbol | undefined): CactalType {
    if (!variable || isEnumType(variable)) return UNKNOWN_TYPE;
    return typeOf(variable.type);
}

/**
 * The type of a variable reference with its path: `temp_message.value` -> TypeA,
 * `scan.ranges[90]` -> float, `Mode.AUTO` -> Mode, `NJOINTS` -> int. `ord_schema` is a string.
 * Unresolved segments give the unknown type.
 */
export function typeOfVariableRef(ref: VariableRef): CactalType {
    return typeOfPathPrefix(ref, ref.path.length);
}

/** The type a path prefix (head + the first `count` segments) has; used by member scoping. */
export function typeOfPathPrefix(ref: VariableRef, count: number): CactalType {
    if (ref.ordSchema) return count === 0 ? STRING_TYPE : UNKNOWN_TYPE;
    const head = ref.variable?.ref;
    if (isEnumType(head)) {
        // `Mode` alone is not a value; `Mode.AUTO` is a value of Mode
        if (count === 0) return UNKNOWN_TYPE;
        const first = ref.path[0];
        if (!isFieldSegment(first) || !first.field?.ref) return UNKNOWN_TYPE;
        return count === 1 ? { kind: 'enum', enumType: head } : UNKNOWN_TYPE;
    }
    let type: CactalType = typeOfVariable(head);
    for (const segment of ref.path.slice(0, count)) {
        if (isIndexSegment(segment)) {
            if (type.kind !== 'array') return UNKNOWN_TYPE;
            type = type.element;
            continue;
        }
        const field = segment.field?.ref;
        if (!field || isConstant(field) || type.kind !== 'struct' || !type.datatype.fields.includes(field as Field)) return UNKNOWN_TYPE;
        type = typeOf((field as Field).type);
    }
    return type;
}

/** True when the reference names an enumeration member (`Mode.AUTO`). */
export function isEnumMemberRef(ref: VariableRef): boolean {
    return isEnumType(ref.variable?.ref);
}

/** Display text of a variable reference: `temp_message.value`, `scan.ranges[90]`. */
export function variableRefText(ref: VariableRef): string {
    const head = ref.ordSchema ? 'ord_schema' : (ref.variable?.$refText ?? '?');
    return head + ref.path.map((s) => isIndexSegment(s)
        ? `[${s.constant ? s.constant.$refText : s.index}]`
        : `.${s.field?.$refText ?? '?'}`).join('');
}

/** Byte size and alignment of a type in the generated C (LP64: long, double 8; bool 1; enum 4; string char[256]). */
export function cLayout(type: CactalType, depth = 0): { size: number; align: number } | undefined {
    if (depth > 32) return undefined;
    switch (type.kind) {
        case 'primitive':
            switch (type.name) {
                case 'int': case 'float': return { size: 8, align: 8 };
                case 'bool': return { size: 1, align: 1 };
                case 'string': return { size: 256, align: 1 };
                default: return undefined;
            }
        case 'enum': return { size: 4, align: 4 };
        case 'array': {
            const e = cLayout(type.element, depth + 1);
            return e ? { size: e.size * type.size, align: e.align } : undefined;
        }
        case 'struct': {
            let size = 0;
            let align = 1;
            for (const f of type.datatype.fields) {
                const l = cLayout(typeOf(f.type), depth + 1);
                if (!l) return undefined;
                size = Math.ceil(size / l.align) * l.align + l.size;
                align = Math.max(align, l.align);
            }
            if (type.datatype.fields.length === 0) size = 1;
            return { size: Math.ceil(size / align) * align, align };
        }
        default: return undefined;
    }
}
