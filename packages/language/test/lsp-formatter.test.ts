/** Formatter (docs/ide.md "Editor services"): canonical layout, idempotent, never changes the AST, keeps comments. */
import { readdirSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { EmptyFileSystem, isReference, URI, type AstNode, type LangiumDocument } from 'langium';
import { expectFormatting } from 'langium/test';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { createCactalServices } from '../src/cactal-module.js';
import type { CactalFormatter } from '../src/lsp/cactal-formatter.js';

const services = createCactalServices(EmptyFileSystem).Cactal;
const formatter = services.lsp.Formatter as CactalFormatter;
const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
const TUTORIAL_FILES = readdirSync(TUTORIAL).filter((f) => f.endsWith('.contract')).sort();

let counter = 0;
function parse(text: string): LangiumDocument {
    return services.shared.workspace.LangiumDocumentFactory.fromString(text, URI.parse(`file:///fmt/${counter++}.contract`));
}

/** Formats a text (throws when the formatter declines). */
function format(text: string): string {
    const out = formatter.formatText(parse(text));
    if (out === undefined) throw new Error('formatter declined');
    return out;
}

/** A comparable form of the AST: properties without CST/containers, references as their text, event modes in short form. */
function astShape(node: unknown): unknown {
    if (Array.isArray(node)) return node.map(astShape);
    if (isReference(node)) return { ref: node.$refText };
    if (node && typeof node === 'object') {
        const out: Record<string, unknown> = {};
        for (const [key, value] of Object.entries(node as AstNode)) {
            if (key.startsWith('$') && key !== '$type') continue;
            out[key] = key === 'mode' && typeof value === 'string' ? value.replace('==', '=') : astShape(value);
        }
        return out;
    }
    return node;
}

describe('formatter', () => {
    it('lays out a module canonically (Langium expectFormatting)', async () => {
        await expectFormatting(services)({
            before: 'import "t.contract"\nsynchronous   module MSA{scheduling{C=500us;}\n\n\n data flows{out:0 TypeA coordinates;in :1 int   x=-2;}}',
            after: 'import "t.contract"\n\nsynchronous module MSA {\n    scheduling {\n        C = 500us;\n    }\n\n    data flows {\n        out :0 TypeA coordinates;\n        in :1 int x = -2;\n    }\n}\n'
        });
    });

    it('writes ==* and ==> as =* and =>, ports tight, rules with one action per line', () => {
        const out = format(`supervisor SUP { event flows { in :2 string s; } go() { rules {
            A:[elapsed=1ms] subscribe MAA:2==*:2;subscribe MAA:0 ==> :1 [ MAA:2 < s == "x" > {infinite} ]
        } } }`);
        expect(out).toBe([
            'supervisor SUP {',
            '    event flows {',
            '        in :2 string s;',
            '    }',
            '    go() {',
            '        rules {',
            '            A:[elapsed = 1ms]',
            '                subscribe MAA:2 =* :2;',
            '                subscribe MAA:0 => :1',
            '                [MAA:2<s == "x">{infinite}]',
            '        }',
            '    }',
            '}',
            ''
        ].join('\n'));
    });

    it('keeps comments: trailing ones on their line, others on their own line', () => {
        const out = format('/* header */\ndatatype T {int a, // first\n int b};\n// tail\n');
        expect(out).toBe('/* header */\ndatatype T {int a, // first\n    int b};\n// tail\n');
        expect(format(out)).toBe(out);
    });

    it('does not format a file with syntax errors (no edit, no lost text)', () => {
        const doc = parse('synchronous module MSA { data flows { out :0 TypeA ; } ');
        expect(formatter.formatText(doc)).toBeUndefined();
        expect(formatter.formatDocument(doc)).toEqual([]);
    });

    it('returns one minimal edit, none for a formatted file', () => {
        const formatted = format('datatype T {int a};');
        const doc = parse(formatted);
        expect(formatter.formatDocument(doc)).toEqual([]);
        const messy = parse('datatype T {int   a};\n');
        const edits = formatter.formatDocument(messy);
        expect(edits).toEqual([{ range: { start: { line: 0, character: 16 }, end: { line: 0, character: 18 } }, newText: '' }]);
    });

    it('gives the same result whatever the spacing inside lines and the indentation (fast-check)', () => {
        const text = readFileSync(`${TUTORIAL}/supervisor.contract`, 'utf8') + readFileSync(`${TUTORIAL}/sschema1.contract`, 'utf8');
        const expected = format(text);
        // whitespace runs outside comments and strings
        const pieces = /\/\/[^\n]*|\/\*[\s\S]*?\*\/|"(?:\\.|[^"\\])*"|[ \t\r\n]+/g;
        const runs = text.match(pieces)!.filter((m) => /^\s/.test(m)).length;
        fc.assert(fc.property(fc.array(fc.tuple(fc.nat(3), fc.nat(3)), { minLength: runs, maxLength: runs }), (noise) => {
            let i = 0;
            const perturbed = text.replace(pieces, (gap) => {
                if (!/^\s/.test(gap)) return gap;
                const [before, after] = noise[i++]!;
                const newlines = (gap.match(/\n/g) ?? []).length;
                if (newlines === 0) return ' '.repeat(before + 1);
                return ' '.repeat(before) + (newlines >= 2 ? '\n\t\n' : '\n') + '\t'.repeat(after);
            });
            expect(format(perturbed)).toBe(expected);
        }), { numRuns: 25, seed: 42 });
    });

    describe.each(TUTORIAL_FILES)('examples/tutorial/%s', (file) => {
        const text = readFileSync(`${TUTORIAL}/${file}`, 'utf8');
        it('is idempotent and keeps the AST', () => {
            const once = format(text);
            expect(format(once)).toBe(once);
            const before = parse(text).parseResult.value;
            const after = parse(once).parseResult.value;
            expect(astShape(after)).toEqual(astShape(before));
            // every comment survives
            const comments = text.match(/\/\/[^\n]*|\/\*[\s\S]*?\*\//g) ?? [];
            for (const c of comments) expect(once).toContain(c.trimEnd());
        });
    });
});

describe('formatting a file it cannot parse', () => {
    it('declines with the reason: the first syntax error, with its line and column', () => {
        const doc = parse('synchronous module MSZ {\n    scheduling { C=1ms }\n}');
        const result = formatter.tryFormat(doc);
        expect('reason' in result && result.reason).toMatch(/^Not formatted: line 2, column \d+: .+\. Fix the syntax error first/);
        expect(formatter.formatDocument(doc)).toEqual([]); // no connection here: nothing to tell, nothing changed
    });

    it('a lexer error (a character Cactal does not know) is named too', () => {
        const result = formatter.tryFormat(parse('datatype T {int x};\n§'));
        expect('reason' in result && result.reason).toMatch(/^Not formatted: line 2, column 1: /);
    });

    it('a well-formed file still formats', () => {
        expect(formatter.tryFormat(parse('datatype T {int x};'))).toHaveProperty('text');
    });
});
