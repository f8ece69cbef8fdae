/**
 * String literals (docs/language-reference.md §2): `\n`, `\t`, `\r`, `\b`, `\f` and `\0` stand for
 * those control characters, a backslash before any other character for that character (`\"`, `\\`;
 * `\x` is `x`). One reading for a `.contract` file (parser/value-converter.ts), a scenario
 * (scenario/parse.ts) and the runtime's reader (runtime/src/engines/engine_values.c string_escape).
 */

/** The escapes that stand for a control character (a Map: messages list them in this order). */
export const STRING_ESCAPES: ReadonlyMap<string, string> = new Map([['n', '\n'], ['t', '\t'], ['r', '\r'], ['b', '\b'], ['f', '\f'], ['0', '\0']]);

/** The text between a string literal's quotes with its escapes read. */
export function unescapeString(body: string): string {
    return body.replace(/\\(.)/g, (_, c: string) => STRING_ESCAPES.get(c) ?? c);
}

/**
 * The escapes of `body` (the text between the quotes) that are none of the known ones nor `\\`,
 * `\"`: `"\u001b"`, `"\x41"`, `"\e"` are read as `u001b`, `x41`, `e`, which is seldom what was
 * meant. `offset` is the backslash's offset in `body`.
 */
export function unknownEscapes(body: string): Array<{ offset: number; char: string }> {
    const found: Array<{ offset: number; char: string }> = [];
    for (const m of body.matchAll(/\\(.)/g)) {
        const c = m[1]!;
        if (!STRING_ESCAPES.has(c) && c !== '\\' && c !== '"') found.push({ offset: m.index!, char: c });
    }
    return found;
}

/** What an unknown escape is read as, and how to write a backslash followed by that character. */
export function unknownEscapeMessage(c: string): string {
    const known = [...STRING_ESCAPES.keys(), '\\', '"'].map((k) => `\\${k}`).join(' ');
    return `Unknown escape '\\${c}' in a string: it is read as '${c}'. Known escapes: ${known}; write '\\\\${c}' for a backslash followed by ${c}.`;
}
