/**
 * Whether an offset of a Cactal text is inside a comment (`// …` to the end of its line, `/* … *\/`)
 * or a string literal (`"…"` on one line): completion offers nothing there (docs/ide.md "Editor
 * services"), or typing a comment whose words start like a keyword would bring up the keyword list
 * at each space (a trigger character), and Enter at the end of the line would insert a keyword
 * instead of a new line. A plain scan rather than the lexer: a comment or string still being typed
 * (`/* todo`, `"abc`) does not lex as one, and it is exactly then that the question is asked.
 */
export type TextContext = 'code' | 'comment' | 'string';

export function textContextAt(text: string, offset: number): TextContext {
    const end = Math.max(0, Math.min(offset, text.length));
    let i = 0;
    while (i < end) {
        const c = text.charCodeAt(i);
        if (c === 0x2f /* / */ && text.charCodeAt(i + 1) === 0x2f) {
            const nl = lineEnd(text, i + 2);
            if (nl >= end) return 'comment'; // the cursor is on the comment's line, after `//`
            i = nl;
        } else if (c === 0x2f && text.charCodeAt(i + 1) === 0x2a /* * */) {
            const close = text.indexOf('*/', i + 2);
            if (close < 0 || close + 2 > end) return 'comment'; // unclosed, or the cursor is before `*/` ends
            i = close + 2;
        } else if (c === 0x22 /* " */) {
            // the closing `"`, or the line break that ends a string never closed (the lexer's rule too)
            const close = stringEnd(text, i + 1);
            if (close >= end) return 'string';
            i = close + 1;
        } else {
            i++;
        }
    }
    return 'code';
}

/** Index of the first line break at or after `from` (text.length when none). */
function lineEnd(text: string, from: number): number {
    for (let i = from; i < text.length; i++) {
        const c = text.charCodeAt(i);
        if (c === 0x0a || c === 0x0d) return i;
    }
    return text.length;
}

/** Index of the `"` closing a string opened before `from` (escapes skipped), or of the line break or end of text that comes first. */
function stringEnd(text: string, from: number): number {
    for (let i = from; i < text.length; i++) {
        const c = text.charCodeAt(i);
        if (c === 0x0a || c === 0x0d) return i;
        if (c === 0x5c /* \ */) {
            const next = text.charCodeAt(i + 1);
            if (next !== 0x0a && next !== 0x0d) i++; // an escaped character; a line break still ends the string
        } else if (c === 0x22) return i;
    }
    return text.length;
}
