/** textContextAt: the scan completion uses to stay quiet inside comments and strings (src/lsp/comment-or-string.ts). */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { textContextAt } from '../src/lsp/comment-or-string.js';

/** The context at the `|` of `marked` (the `|` removed). */
const at = (marked: string) => textContextAt(marked.replace('|', ''), marked.indexOf('|'));

describe('textContextAt', () => {
    it('knows line comments, block comments and strings, closed or still being typed', () => {
        expect(at('int x; // note |')).toBe('comment');
        expect(at('int x; // note\n|')).toBe('code');
        expect(at('/* a |b */')).toBe('comment');
        expect(at('/* a b *|/')).toBe('comment');
        expect(at('/* a b */|')).toBe('code');
        expect(at('/* unclosed\n\n |')).toBe('comment');
        expect(at('import "x|"')).toBe('string');
        expect(at('import "x"|')).toBe('code');
        expect(at('import "x\\"y|"')).toBe('string');
        expect(at('import "unclosed\n|')).toBe('code'); // a string ends with its line
        expect(at('"// not a comment" |')).toBe('code');
        expect(at('// "not a string\n|')).toBe('code');
        expect(at('/* // */ |')).toBe('code');
        expect(at('a / b |')).toBe('code');
    });

    it('agrees with a character-by-character reference on any mix of comment, string and code pieces', () => {
        const piece = fc.constantFrom('//', '/*', '*/', '"', '\\', '\n', ' ', 'x', '/', '*');
        fc.assert(fc.property(fc.array(piece, { maxLength: 40 }).map((p) => p.join('')), fc.nat(), (text, n) => {
            const offset = n % (text.length + 1);
            expect(textContextAt(text, offset)).toBe(reference(text, offset));
        }), { numRuns: 2000 });
    });
});

/** A state machine stepping one character at a time: the definition the scan must meet. */
function reference(text: string, offset: number): string {
    let state: 'code' | 'line' | 'block' | 'string' = 'code';
    for (let i = 0; i < offset; i++) {
        const c = text[i]!, d = text[i + 1];
        if (state === 'code') {
            if (c === '/' && d === '/') { state = 'line'; i++; }
            else if (c === '/' && d === '*') { state = 'block'; i++; }
            else if (c === '"') state = 'string';
        } else if (state === 'line') {
            if (c === '\n') state = 'code';
        } else if (state === 'block') {
            if (c === '*' && d === '/') {
                if (i + 1 >= offset) return 'comment'; // the cursor is between `*` and `/`
                state = 'code'; i++;
            }
        } else if (c === '\\') {
            if (d !== '\n') i++;
        } else if (c === '"' || c === '\n') state = 'code';
    }
    return state === 'line' || state === 'block' ? 'comment' : state;
}
