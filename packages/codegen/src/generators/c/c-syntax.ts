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

/** A C double literal: always with a decimal point or exponent (`1.0`, `22.12`, `1e-07`). */
export function cDouble(n: number): string {
    if (!Number.isFinite(n)) return '0.0';
    const s = String(n);
    return /[.eE]/.test(s) ? s : `${s}.0`;
}

export function cLong(n: number): string {
    return String(Math.trunc(n));
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
                return value && (value.kind === 'int' || value.kind === 'real') ? cLong(value.value) : '0';
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
