/**
 * Constant values: what a written value means once its type is known, and the defaults
 * (0, 0.0, "", or a datatype's own field defaults) when no value is written (docs/language-reference.md §2).
 * Code generation prints these; validation checks written values against types separately.
 */
import {
    isIntLiteral, isRealLiteral, isStringLiteral, isStructValue,
    type DataType, type TypeRef, type Value
} from '../generated/ast.js';
import { typeOf, type CactalType } from './types.js';

export type ConstantValue =
    | { kind: 'int'; value: number }
    | { kind: 'float'; value: number }
    | { kind: 'string'; value: string }
    | { kind: 'struct'; datatype: DataType; fields: Array<{ name: string; value: ConstantValue }> };

const MAX_DEPTH = 32;

/** The default of a type: 0, 0.0, "", or the datatype's field defaults (recursively). */
export function defaultValue(type: CactalType, depth = 0): ConstantValue | undefined {
    if (type.kind === 'primitive') {
        switch (type.name) {
            case 'int': return { kind: 'int', value: 0 };
            case 'float': return { kind: 'float', value: 0 };
            case 'string': return { kind: 'string', value: '' };
            default: return undefined;
        }
    }
    if (type.kind === 'struct') {
        if (depth > MAX_DEPTH) return undefined; // recursive datatype: reported by validation
        const fields: Array<{ name: string; value: ConstantValue }> = [];
        for (const field of type.datatype.fields) {
            const v = effectiveValue(field, depth + 1);
            if (!v) return undefined;
            fields.push({ name: field.name, value: v });
        }
        return { kind: 'struct', datatype: type.datatype, fields };
    }
    return undefined;
}

/**
 * The constant a written value denotes for a type (an int literal for a float becomes a float).
 * Undefined when the value refers to variables or does not fit the type.
 */
export function constantValue(value: Value, type: CactalType, depth = 0): ConstantValue | undefined {
    if (depth > MAX_DEPTH) return undefined;
    if (type.kind === 'primitive') {
        if (type.name === 'int' && isIntLiteral(value)) return { kind: 'int', value: value.value };
        if (type.name === 'float' && (isIntLiteral(value) || isRealLiteral(value))) return { kind: 'float', value: value.value };
        if (type.name === 'string' && isStringLiteral(value)) return { kind: 'string', value: value.value };
        return undefined;
    }
    if (type.kind === 'struct' && isStructValue(value)) {
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
    return undefined;
}

/**
 * The value a declaration starts with: its written constant value, or its type's default when
 * nothing is written. Works for fields, parameters, ports, schema/function parameters, locals.
 */
export function effectiveValue(node: { type: TypeRef; value?: Value }, depth = 0): ConstantValue | undefined {
    const type = typeOf(node.type);
    if (node.value) return constantValue(node.value, type, depth);
    return defaultValue(type, depth);
}

/** Cactal/C textual form of a constant: `{1.0,{2,"a"}}` (the form control tools parse). */
export function formatConstant(value: ConstantValue): string {
    switch (value.kind) {
        case 'int': return String(value.value);
        case 'float': return Number.isInteger(value.value) ? value.value.toFixed(1) : String(value.value);
        case 'string': return JSON.stringify(value.value);
        case 'struct': return `{${value.fields.map((f) => formatConstant(f.value)).join(',')}}`;
    }
}
