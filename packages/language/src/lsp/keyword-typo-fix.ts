/**
 * The quick fix of a misspelt keyword (docs/ide.md "Editor services"): a syntax error that ends
 * `Did you mean 'synchronous'?` is on the misspelt word (the parser's keyword repair puts it
 * there); when the squiggled text is a word that is a near miss of that keyword, the fix replaces
 * it. Anything else under the squiggle (a bracket, a whole line) gets no fix: only a word the
 * suggestion is about is changed.
 */
import type { LangiumDocument } from 'langium';
import { CodeActionKind, type CodeAction, type Diagnostic } from 'vscode-languageserver-protocol';
import { nearKeywords } from '../model/near-names.js';

const SUGGESTION = /Did you mean '([A-Za-z_]\w*)'/;

export function keywordTypoFix(document: LangiumDocument, diagnostic: Diagnostic): CodeAction | undefined {
    const keyword = SUGGESTION.exec(diagnostic.message)?.[1];
    if (!keyword) return undefined;
    const word = document.textDocument.getText(diagnostic.range);
    if (!nearKeywords(word, [keyword]).includes(keyword)) return undefined;
    return {
        title: `Replace '${word}' with '${keyword}'`,
        kind: CodeActionKind.QuickFix,
        diagnostics: [diagnostic],
        isPreferred: true,
        edit: { changes: { [document.textDocument.uri]: [{ range: diagnostic.range, newText: keyword }] } }
    };
}
