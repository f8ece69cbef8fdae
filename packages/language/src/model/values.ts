/**
 * Constant values: what a written value means once its type is known, and the defaults
 * (0, 0.0, "", false, an enumeration's first member, arrays of element defaults, or a datatype's
 * own field defaults) when no value is written (docs/language-reference.md §2).
 * Validation checks written values against types separately (value-checker.ts).
 */
import {
    isBoolLiteral, isConstant, isEnumType, isFieldSegment, isIntLiteral, isRealLiteral, isStringLiteral,
    isStructValue, isVariableRef,
    type DataType, type EnumType, type TypeRef, type Value, type VariableRef
} from '../generated/ast.js';
import { segmentIndex, typeOf, type CactalType } from './types.js';
import { exactInteger } from './numbers.js';

/** The decimal text of the integer literal `text` (`007` -> `7`, exact beyond 2^53), or undefined. */
export function exactIntegerText(text: string | undefined): string | undefined {
    const n = text === undefined ? undefined : exactInteger(text);
    return n === undefined ? undefined : n.toString();
}

export type ConstantValue =
    /** `text`: the integer written, exact, in decimal (`value` is exact up to 2^53 only); absent for a default. */
    | { kind: 'int'; value: number; text?: string }
    | { kind: 'float'; value: number }
    | { kind: 'string'; value: string }
    | { kind: 'bool'; value: boolean }
    /** `Mode.AUTO`: `ordinal` is the member's position (its C value). */
    | { kind: 'enum'; enumType: EnumType; member: string; ordinal: number }
    | { kind: 'array'; elements: ConstantValue[] }
    | { kind: 'struct'; datatype: DataType; fields: Array<{ name: string; value: ConstantValue }> };

const MAX_DEPTH = 32;

/** The default of a type: 0, 0.0, "", false, the first enumeration member, element defaults, or the datatype's field defaults (recursively). */
export function defaultValue(type: CactalType, depth = 0): ConstantValue | undefined {
    if (depth > MAX_DEPTH) return undefined; // recursive datatype: reported by validation
    switch (type.kind) {
        case 'primitive':
            switch (type.name) {
                case 'int': return { kind: 'int', value: 0 };
                case 'float': return { kind: 'float', value: 0 };
                case 'string': return { kind: 'string', value: '' };
                case 'bool': return { kind: 'bool', value: false };
                default: return undefined;
            }
        case 'enum': {
            const first = type.enumType.members[0];
            return first ? { kind: 'enum', enumType: type.enumType, member: first.name, ordinal: 0 } : undefined;
        }
        case 'array': {
            const element = defaultValue(type.element, depth + 1);
            return element ? { kind: 'array', elements: Array.from({ length: type.size }, () => element) } : undefined;
        }
        case 'struct': {
            const fields: Array<{ name: string; value: ConstantValue }> = [];
            for (const field of type.datatype.fields) {
                const v = effectiveValue(field, depth + 1);
                if (!v) return undefined;
                fields.push({ name: field.name, value: v });
            }
            return { kind: 'struct', datatype: type.datatype, fields };
        }
        default:
            return undefined;
    }
}

/**
 * The constant a written value denotes for a type (an int literal for a float becomes a float;
 * a constant's name stands for its value; `Mode.AUTO` for a Mode). Undefined when the value
 * refers to variables or does not fit the type.
 */
export function constantValue(value: Value, type: CactalType, depth = 0): ConstantValue | undefined {
    if (depth > MAX_DEPTH) return undefined;
    if (isVariableRef(value)) return namedConstantValue(value, type, depth);
    switch (type.kind) {
        case 'primitive':
            if (type.name === 'int' && isIntLiteral(value)) {
                const text = exactIntegerText(value.$cstNode?.text);
                return text === undefined ? { kind: 'int', value: value.value } : { kind: 'int', value: value.value, text };
            }
            if (type.name === 'float' && (isIntLiteral(value) || isRealLiteral(value))) return { kind: 'float', value: value.value };
            if (type.name === 'string' && isStringLiteral(value)) return { kind: 'string', value: value.value };
            if (type.name === 'bool' && isBoolLiteral(value)) return { kind: 'bool', value: value.value };
            return undefined;
        case 'array': {
            if (!isStructValue(value) || value.elements.length !== type.size) return undefined;
            const elements: ConstantValue[] = [];
            for (const e of value.elements) {
                const v = constantValue(e, type.element, depth + 1);
                if (!v) return undefined;
                elements.push(v);
            }
            return { kind: 'array', elements };
        }
        case 'struct': {
            if (!isStructValue(value)) return undefined;
            const fieldDefs = type.datatype.fields;
            if (fieldDefs.length !== value.elements.length) return undefined;
            const fields: Array<{ name: string; value: ConstantValue }> = [];
            for (let i = 0; i < fieldDefs.length; i++) {
                const v = constantValue(value.elements[i]!, typeOf(fieldDefs[i]!.type), depth + 1);
                if (!v) return undefined;
                fields.push({ name: fieldDefs[i]!.name, value: v });
            }
            return { kind: 'struct', datatype: type.datatype, fields };
        }
        default:
            return undefined;
    }
}

/** `Mode.AUTO`, `NJOINTS`, `HOME.x`, `LIMITS[2]`: the value of an enumeration member or of a constant (with a path). */
function namedConstantValue(ref: VariableRef, type: CactalType, depth: number): ConstantValue | undefined {
    const head = ref.variable?.ref;
    if (isEnumType(head)) {
        const segment = ref.path[0];
        if (ref.path.length !== 1 || !isFieldSegment(segment)) return undefined;
        const ordinal = head.members.findIndex((m) => m.name === segment.field?.$refText);
        if (ordinal < 0 || type.kind !== 'enum' || type.enumType !== head) return undefined;
        return { kind: 'enum', enumType: head, member: head.members[ordinal]!.name, ordinal };
    }
    if (!isConstant(head)) return undefined;
    let v = constantValue(head.value, typeOf(head.type), depth + 1);
    for (const segment of ref.path) {
        if (!v) return undefined;
        if (isFieldSegment(segment)) {
            v = v.kind === 'struct' ? v.fields.find((f) => f.name === segment.field?.$refText)?.value : undefined;
        } else {
            const i = segmentIndex(segment);
            v = v.kind === 'array' && i !== undefined ? v.elements[i] : undefined;
        }
    }
    if (!v) return undefined;
    // an int constant used for a float
    if (v.kind === 'int' && type.kind === 'primitive' && type.name === 'float') return { kind: 'float', value: v.value };
    return fits(v, type) ? v : undefined;
}

function fits(v: ConstantValue, type: CactalType): boolean {
    switch (type.kind) {
        case 'primitive': return v.kind === type.name;
        case 'enum': return v.kind === 'enum' && v.enumType === type.enumType;
        case 'struct': return v.kind === 'struct' && v.datatype === type.datatype;
        case 'array': return v.kind === 'array' && v.elements.length === type.size && v.elements.every((e) => fits(e, type.element));
        default: return false;
    }
}

/**
 * The value a declaration starts with: its written constant value, or its type's default when
 * nothing is written. Works for fields, parameters, ports, schema/function parameters, locals, constants.
 */
export function effectiveValue(node: { type: TypeRef; value?: Value }, depth = 0): ConstantValue | undefined {
    const type = typeOf(node.type);
    if (node.value) return constantValue(node.value, type, depth);
    return defaultValue(type, depth);
}

/** Cactal/C textual form of a constant: `{1.0,{2,"a"}}`, `true`, `AUTO`, arrays `{0.0,0.1}` (the form control tools parse). */
export function formatConstant(value: ConstantValue): string {
    switch (value.kind) {
        case 'int': return value.text ?? String(value.value);
        case 'float': return Number.isInteger(value.value) ? value.value.toFixed(1) : String(value.value);
        case 'string': return JSON.stringify(value.value);
        case 'bool': return value.value ? 'true' : 'false';
        case 'enum': return value.member;
        case 'array': return `{${value.elements.map(formatConstant).join(',')}}`;
        case 'struct': return `{${value.fields.map((f) => formatConstant(f.value)).join(',')}}`;
    }
}
