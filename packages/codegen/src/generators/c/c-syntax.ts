import type { ArchitectureIndex } from '../../model/lookup.js';
import type { TypeRef, Value } from '../../model/architecture.js';

/** C type of a Cactal type: int -> long, float -> double, string -> char (array of 256), datatype -> its struct. */
export function cType(t: TypeRef): string {
    if ('datatype' in t) return t.datatype;
    return t.primitive === 'int' ? 'long' : t.primitive === 'float' ? 'double' : 'char';
}

/** A C declaration of variable `name` of Cactal type `t` (`char name[256]` for strings). */
export function cDeclaration(t: TypeRef, name: string): string {
    return 'primitive' in t && t.primitive === 'string' ? `char ${name}[256]` : `${cType(t)} ${name}`;
}

/** `sizeof(...)` of a Cactal type, as the report writes it. */
export function cSizeof(t: TypeRef): string {
    return 'primitive' in t && t.primitive === 'string' ? 'sizeof(char)*256' : `sizeof(${cType(t)})`;
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
 * "\0", or the datatype's field defaults), nested for datatypes (`{ "\0", 0, { 0.0, 0.0, 0.0 } }`).
 * Variables cannot appear in a static initialiser; they fall back to the default.
 */
export function cInitializer(index: ArchitectureIndex, t: TypeRef, value?: Value): string {
    if (value?.kind === 'var') value = undefined;
    if ('primitive' in t) {
        switch (t.primitive) {
            case 'int':
                return value && (value.kind === 'int' || value.kind === 'real') ? cLong(value.value) : '0';
            case 'float':
                return value && (value.kind === 'int' || value.kind === 'real') ? cDouble(value.value) : '0.0';
            case 'string':
                return value?.kind === 'string' && value.value !== '' ? cString(value.value) : '"\\0"';
        }
    }
    const fields = index.datatype(t.datatype).fields;
    const elements = value?.kind === 'struct' ? value.elements : undefined;
    return `{ ${fields.map((f, i) => cInitializer(index, f.type, elements?.[i] ?? f.default)).join(', ')} }`;
}
