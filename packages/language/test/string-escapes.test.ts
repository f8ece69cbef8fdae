/** String escapes (docs/language-reference.md §2): one reading everywhere, and a warning on an unknown escape. */
import { describe, expect, it } from 'vitest';
import { isConstant, isStringLiteral } from '../src/generated/ast.js';
import { parseScenario } from '../src/scenario/parse.js';
import { build, parse } from './helpers.js';

/** The value read from `const string S = <literal>;`. */
function read(literal: string): string | undefined {
    const c = parse(`const string S = ${literal};`).model.elements[0];
    return isConstant(c) && isStringLiteral(c.value) ? c.value.value : undefined;
}

describe('string escapes', () => {
    it('reads \\n \\t \\r \\b \\f \\0 as control characters and any other escaped character as itself', () => {
        expect(read('"\\n\\t\\r\\b\\f\\0"')).toBe('\n\t\r\b\f\0');
        expect(read('"q\\"c"')).toBe('q"c');
        expect(read('"a\\\\b"')).toBe('a\\b');
        expect(read('"\\u001b\\x41\\e"')).toBe('u001bx41e');
        // as the scenario reader and the runtime read it (Langium's own reader took \v for a vertical tab)
        expect(read('"\\v"')).toBe('v');
    });

    it('warns on an unknown escape, on the escape itself, and says how it is read', async () => {
        const built = await build({ 'a.contract': 'datatype T {string s = "x\\u001b[0m", string ok = "\\n\\t\\r\\b\\f\\0\\\\u\\""};' });
        expect(built.lines).toEqual([
            "a.contract:1:26 warning value-string-unknown-escape Unknown escape '\\u' in a string: it is read as 'u'. Known escapes: \\n \\t \\r \\b \\f \\0 \\\\ \\\"; write '\\\\u' for a backslash followed by u."
        ]);
        const range = built.docs.get('a.contract')!.diagnostics![0]!.range;
        expect(range).toEqual({ start: { line: 0, character: 25 }, end: { line: 0, character: 27 } });
    });

    it('warns in every string: a value of a rule, an import path', async () => {
        const built = await build({
            'a.contract': 'import "sub\\mods.contract";\nsupervisor SUP { f() { local { string s; } rules { R: [elapsed=1ms] compute g("\\e") [elapsed=1ms] } } }'
        });
        const warnings = built.diagnostics.filter((d) => d.code === 'value-string-unknown-escape');
        expect(warnings.map((d) => `${d.line}: ${d.message.split(':')[0]}`)).toEqual([
            "1: Unknown escape '\\m' in a string",
            "2: Unknown escape '\\e' in a string"
        ]);
    });

    it('a scenario reads its strings the same way, with the same warning', () => {
        const p = parseScenario('t=1ms MAA:2 "a\\eb\\n"');
        expect((p.steps[0] as unknown as { value: { value: string } }).value.value).toBe('aeb\n');
        expect(p.diagnostics).toEqual([{
            line: 1, column: 15, endColumn: 17, severity: 'warning', code: 'scenario-unknown-escape',
            message: "Unknown escape '\\e' in a string: it is read as 'e'. Known escapes: \\n \\t \\r \\b \\f \\0 \\\\ \\\"; write '\\\\e' for a backslash followed by e."
        }]);
        // also on a line that is wrong after the string
        expect(parseScenario('t=1ms MAA:2 "\\e" junk').diagnostics.map((d) => d.code).sort()).toEqual(['scenario-syntax', 'scenario-unknown-escape']);
    });
});
