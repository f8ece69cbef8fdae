import type { ArchitectureIndex } from '../../model/lookup.js';
import type { TypeRef, Value } from '../../model/architecture.js';

/**
 * C type of a non-array Cactal type: int -> long, float -> double, string -> char (array of 256),
 * bool -> bool (<stdbool.h>), datatype -> its struct, enumeration -> its C enum (same name).
 * For an array, the type of its innermost elements.
 */
export function cType(t: TypeRef): string {
    if ('array' in t) return cType(t.array);
    if ('datatype' in t) return t.datatype;
    if ('enum' in t) return t.enum;
    switch (t.primitive) {
        case 'int': return 'long';
        case 'float': return 'double';
        case 'bool': return 'bool';
        default: return 'char';
    }
}

/** True when the C form of the type is a C array (a string or an array type). */
export function isCArray(t: TypeRef): boolean {
    return 'array' in t || ('primitive' in t && t.primitive === 'string');
}

/**
 * A C declaration of `declarator` (a variable name, or `(* p)`) of Cactal type `t`: `char name[256]`
 * for strings, `double q[6]`, `double m[3][3]`, `char names[4][256]` for arrays (outer size first).
 */
export function cDeclaration(t: TypeRef, declarator: string): string {
    if ('array' in t) return cDeclaration(t.array, `${declarator}[${t.size}]`);
    return 'primitive' in t && t.primitive === 'string' ? `char ${declarator}[256]` : `${cType(t)} ${declarator}`;
}

/** The C type name of a Cactal type (for sizeof and casts): `long`, `double[6]`, `char[4][256]`. */
export function cTypeName(t: TypeRef): string {
    return cDeclaration(t, '').replace(' [', '[').trimEnd();
}

/** `sizeof(...)` of a Cactal type, as the report writes it (`sizeof(double[6])` for an array). */
export function cSizeof(t: TypeRef): string {
    if ('array' in t) return `sizeof(${cTypeName(t)})`;
    return 'primitive' in t && t.primitive === 'string' ? 'sizeof(char)*256' : `sizeof(${cType(t)})`;
}

/** The C name of an enumeration member: `Mode_AUTO` (prefixed by the enumeration: collision-safe across enumerations). */
export function cEnumMember(enumName: string, member: string): string {
    return `${enumName}_${member}`;
}

/** A C string literal for `s` (UTF-8 bytes kept, control characters, quotes and backslashes escaped). */
export function cString(s: string): string {
    let out = '"';
    for (const ch of s) {
        const code = ch.codePointAt(0)!;
        if (ch === '"' || ch === '\\') out += '\\' + ch;
        else if (ch === '\n') out += '\\n';
        else if (ch === '\t') out += '\\t';
        else if (ch === '\r') out += '\\r';
        else if (code < 0x20 || code === 0x7f) out += '\\' + code.toString(8).padStart(3, '0');
        else if (ch === '?') out += '\\?'; // no trigraphs
        else out += ch;
    }
    return out + '"';
}

/**
 * A C double literal: always with a decimal point or exponent (`1.0`, `22.12`, `1e-07`), the
 * shortest that reads back as the same double. An infinite or NaN value has no C literal: it is
 * refused (an Error naming it), never written as another value (`1e400` was written `0.0`).
 * `contract check` reports such a number (number-out-of-range); only a model built without the
 * validator gets here.
 */
export function cDouble(n: number): string {
    if (!Number.isFinite(n)) {
        throw new Error(`the float ${n} is not a finite C double (a float is a C double, from -${Number.MAX_VALUE} to ${Number.MAX_VALUE}): no C value for it`);
    }
    const s = String(n);
    return /[.eE]/.test(s) ? s : `${s}.0`;
}

/** The range of a Cactal int, a C long (LP64: 64 bits). */
export const LONG_MIN = -(2n ** 63n);
export const LONG_MAX = 2n ** 63n - 1n;

/**
 * A C long literal of the integer `n`, or of `text` when given (the integer as written, exact: a
 * number is exact up to 2^53 only). `-9223372036854775807L - 1` for LONG_MIN (`-9223372036854775808`
 * is the negation of a constant too large for a long, not a long). A value that is not an integer or
 * does not fit a long is refused (an Error naming it), never written as another value (gcc would
 * truncate `100000000000000000000`; a real used to be truncated to its integer part).
 */
export function cLong(n: number, text?: string): string {
    const exact = text !== undefined && /^\s*[-+]?[0-9]+\s*$/.test(text) ? BigInt(text.trim()) : undefined;
    if (exact === undefined && !Number.isInteger(n)) {
        throw new Error(`the int ${text ?? n} is not an integer: no C long for it`);
    }
    const v = exact ?? BigInt(n);
    if (v < LONG_MIN || v > LONG_MAX) {
        throw new Error(`the int ${text?.trim() ?? v} does not fit a C long (an int is a C long, from ${LONG_MIN} to ${LONG_MAX}): no C value for it`);
    }
    return v === LONG_MIN ? '-9223372036854775807L - 1' : String(v);
}

/** The C long literal of an int or real value given for an int (an integral real: a model built by hand). */
export function cLongOf(value: { kind: 'int'; value: number; text?: string } | { kind: 'real'; value: number }): string {
    return value.kind === 'int' ? cLong(value.value, value.text) : cLong(value.value);
}

/**
 * The C initialiser of a value of type `t`: the given constant, or the type's default (0, 0.0,
 * "\0", false, the first enumeration member, element defaults, or the datatype's field defaults),
 * nested for datatypes and arrays (`{ "\0", 0, { 0.0, 0.0, 0.0 } }`).
 * Variables cannot appear in a static initialiser; they fall back to the default.
 */
export function cInitializer(index: ArchitectureIndex, t: TypeRef, value?: Value): string {
    if (value?.kind === 'var') value = undefined;
    if ('array' in t) {
        const elements = value?.kind === 'struct' ? value.elements : undefined;
        return `{ ${Array.from({ length: t.size }, (_, i) => cInitializer(index, t.array, elements?.[i])).join(', ')} }`;
    }
    if ('enum' in t) {
        const members = index.enumDecl(t.enum).members;
        const member = value?.kind === 'enum' && members.includes(value.member) ? value.member : members[0]!;
        return cEnumMember(t.enum, member);
    }
    if ('primitive' in t) {
        switch (t.primitive) {
            case 'int':
                return value && (value.kind === 'int' || value.kind === 'real') ? cLongOf(value) : '0';
            case 'float':
                return value && (value.kind === 'int' || value.kind === 'real') ? cDouble(value.value) : '0.0';
            case 'bool':
                return value?.kind === 'bool' && value.value ? 'true' : 'false';
            case 'string':
                return value?.kind === 'string' && value.value !== '' ? cString(value.value) : '"\\0"';
        }
    }
    const fields = index.datatype(t.datatype).fields;
    const elements = value?.kind === 'struct' ? value.elements : undefined;
    return `{ ${fields.map((f, i) => cInitializer(index, f.type, elements?.[i] ?? f.default)).join(', ')} }`;
}
