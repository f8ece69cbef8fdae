/**
 * Type checking of written values (docs/language-reference.md §2), reusable wherever a value is written: defaults,
 * parameters, locals, parameterisations, extractions, notify, function arguments.
 * - an int literal fits int and float; a real fits float only (a real for an int is an error);
 * - a number fits its type in the generated C: an int literal for an int is a C long (64 bits), a
 *   number for a float a finite C double, not 0 unless written 0 (`number-out-of-range`);
 * - a string literal fits string and is at most 255 bytes (UTF-8);
 * - a structured value needs exactly one element per field of the datatype, recursively;
 * - (extensions) `true`/`false` fit bool; `{...}` for an array needs exactly its size in elements;
 *   `Mode.AUTO` fits Mode; a constant's name fits wherever its value would, even where variables cannot appear;
 * - a variable (with field path) must have the same type (an int variable fits a float).
 */
import { GrammarUtils, type AstNode, type ValidationAcceptor } from 'langium';
import {
    isBoolLiteral, isConstant, isEnumType, isIntLiteral, isRealLiteral, isStringLiteral, isStructValue, isVariableRef,
    type IntLiteral, type RealLiteral, type TestOperand, type Value, type VariableRef
} from '../generated/ast.js';
import { floatLiteralProblem, intLiteralProblem } from '../model/numbers.js';
import { sameType, typeName, typeOf, typeOfVariableRef, variableRefText, type CactalType } from '../model/types.js';
import { TypeCodes } from './codes/types.js';
import { report } from './report.js';

export const MAX_STRING_BYTES = 255;

const encoder = new TextEncoder();

export interface ValueCheckOptions {
    /** Whether variables (locals, parameters, port variables) may appear in the value. */
    allowVariables: boolean;
    /** What the value is for, used in messages: "default of field 'a'". */
    what?: string;
}

/** An integer property as written (`99999999999999999999`, not the double it was read as). */
export function writtenInt(node: AstNode, property: string): string {
    const cst = node.$cstNode && GrammarUtils.findNodeForProperty(node.$cstNode, property);
    return cst?.text ?? String((node as unknown as Record<string, unknown>)[property]);
}

/** A number literal as written (`99999999999999999999`, not the double it was read as); its value where no text is kept. */
function literalText(value: IntLiteral | RealLiteral): string {
    return value.$cstNode?.text ?? String(value.value);
}

/**
 * Reports a number literal that does not fit `type` in the generated C (model/numbers.ts): an int
 * literal for an int must fit a C long; an int or real literal for a float must be a finite C double
 * that is not 0 unless written 0. Other values are left to the type check.
 */
export function checkNumberRange(value: Value | TestOperand, type: 'int' | 'float', accept: ValidationAcceptor, what?: string): void {
    if (!isIntLiteral(value) && !isRealLiteral(value)) return;
    const text = literalText(value);
    const problem = type === 'int' ? (isIntLiteral(value) ? intLiteralProblem(text) : undefined) : floatLiteralProblem(text);
    if (!problem) return;
    report(accept, TypeCodes['number-out-of-range'],
        `The ${isIntLiteral(value) ? 'integer' : 'real'} ${text}${what ? ` for ${what}` : ''} ${problem}.`, { node: value });
}

function describeValue(value: Value): string {
    if (isIntLiteral(value)) return `the integer ${literalText(value)}`;
    if (isRealLiteral(value)) return `the real ${literalText(value)}`;
    if (isStringLiteral(value)) return 'a string';
    if (isBoolLiteral(value)) return `the bool ${value.value ? 'true' : 'false'}`;
    if (isStructValue(value)) return 'a structured value {...}';
    return `'${variableRefText(value)}'`;
}

function expectedText(expected: CactalType): string {
    switch (expected.kind) {
        case 'struct': {
            const fields = expected.datatype.fields.map((f) => f.name).join(', ');
            return `a ${expected.datatype.name} value {${fields}}`;
        }
        case 'enum':
            return `a ${expected.enumType.name} value (${expected.enumType.members.slice(0, 3).map((m) => `${expected.enumType.name}.${m.name}`).join(', ')}${expected.enumType.members.length > 3 ? ', ...' : ''})`;
        case 'array':
            return `a ${typeName(expected)} value {${expected.size} element${expected.size === 1 ? '' : 's'}}`;
        case 'primitive':
            switch (expected.name) {
                case 'int': return 'an int (integer literal)';
                case 'float': return 'a float (real or integer literal)';
                case 'string': return 'a string ("...")';
                case 'bool': return 'a bool (true or false)';
                default: return `a ${expected.name}`;
            }
        default:
            return 'a value';
    }
}

/** True when a reference names a constant or an enumeration member rather than a variable. */
function isConstantRef(value: VariableRef): boolean {
    const head = value.variable?.ref;
    return isConstant(head) || isEnumType(head);
}

/** Checks `value` against `expected`; reports problems on the value nodes. */
export function checkValue(value: Value, expected: CactalType, accept: ValidationAcceptor, options: ValueCheckOptions): void {
    const where = options.what ? ` for ${options.what}` : '';
    const mismatch = (found: string) =>
        report(accept, TypeCodes['value-type-mismatch'], `Expected ${expectedText(expected)}${where}, found ${found}.`, { node: value });

    if (isStringLiteral(value)) {
        const bytes = encoder.encode(value.value).length;
        if (bytes > MAX_STRING_BYTES) {
            report(accept, TypeCodes['value-string-too-long'],
                `This string is ${bytes} bytes long; strings hold at most ${MAX_STRING_BYTES} bytes (C char[256]).`, { node: value });
        }
    }
    if (isVariableRef(value)) {
        const head = value.variable?.ref;
        if (isEnumType(head) && value.path.length === 0) {
            report(accept, TypeCodes['enum-value-without-member'],
                `'${head.name}' is an enumeration, not a value: write one of its members (${head.members.map((m) => `${head.name}.${m.name}`).join(', ') || 'it has none'}).`,
                { node: value });
            return;
        }
        if (!options.allowVariables && !isConstantRef(value)) {
            if (head || value.ordSchema) {
                report(accept, TypeCodes['value-not-constant'], `Expected a constant${where}, found the variable '${variableRefText(value)}'.`, { node: value });
            }
            return;
        }
        const actual = typeOfVariableRef(value);
        if (actual.kind === 'unknown' || expected.kind === 'unknown') return;
        const intToFloat = expected.kind === 'primitive' && expected.name === 'float' && actual.kind === 'primitive' && actual.name === 'int';
        if (!sameType(actual, expected) && !intToFloat) {
            mismatch(`'${variableRefText(value)}' of type ${typeName(actual)}`);
        }
        return;
    }
    if (isStructValue(value)) {
        if (expected.kind === 'unknown') {
            for (const e of value.elements) checkValue(e, { kind: 'unknown' }, accept, options);
            return;
        }
        if (expected.kind === 'array') {
            if (expected.size !== value.elements.length) {
                report(accept, TypeCodes['value-array-length'],
                    `${typeName(expected)} has ${expected.size} element${expected.size === 1 ? '' : 's'}; this value has ${value.elements.length}${where}.`,
                    { node: value });
            }
            const n = Math.min(expected.size, value.elements.length);
            for (let i = 0; i < n; i++) {
                checkValue(value.elements[i]!, expected.element, accept, { ...options, what: `element ${i}${options.what ? ` of ${options.what}` : ''}` });
            }
            return;
        }
        if (expected.kind !== 'struct') return mismatch(describeValue(value));
        const fields = expected.datatype.fields;
        if (fields.length !== value.elements.length) {
            report(accept, TypeCodes['value-struct-arity'],
                `${expected.datatype.name} has ${fields.length} field${fields.length === 1 ? '' : 's'} (${fields.map((f) => f.name).join(', ')}); this value has ${value.elements.length} element${value.elements.length === 1 ? '' : 's'}${where}.`,
                { node: value });
        }
        const n = Math.min(fields.length, value.elements.length);
        for (let i = 0; i < n; i++) {
            checkValue(value.elements[i]!, typeOf(fields[i]!.type), accept, { ...options, what: `field '${fields[i]!.name}' of ${expected.datatype.name}` });
        }
        return;
    }
    if (expected.kind === 'unknown') return;
    if (expected.kind !== 'primitive') return mismatch(describeValue(value));
    switch (expected.name) {
        case 'int':
            if (!isIntLiteral(value)) mismatch(describeValue(value) + (isRealLiteral(value) ? ' (a real cannot be an int)' : ''));
            else checkNumberRange(value, 'int', accept, options.what);
            return;
        case 'float':
            if (!isIntLiteral(value) && !isRealLiteral(value)) mismatch(describeValue(value));
            else checkNumberRange(value, 'float', accept, options.what);
            return;
        case 'string':
            if (!isStringLiteral(value)) mismatch(describeValue(value));
            return;
        case 'bool':
            if (!isBoolLiteral(value)) mismatch(describeValue(value) + (isIntLiteral(value) ? ' (write true or false)' : ''));
            return;
        default:
            mismatch(describeValue(value));
    }
}
