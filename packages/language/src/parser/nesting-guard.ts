/**
 * Guards the parser against pathological nesting (`{{{{...}}}}` thousands deep), which would
 * overflow the JavaScript stack inside the recursive-descent parser and take the language server
 * down. Text nested deeper than MAX_NESTING yields an empty model with one clear error instead.
 */
import { DefaultLangiumDocumentFactory, type AstNode, type ParseResult, type URI } from 'langium';
import type { CancellationToken } from 'vscode-languageserver-protocol';

/** Deepest bracket nesting accepted ({, (, [ together). Real Cactal nests a handful of levels. */
export const MAX_NESTING = 64;

export interface NestingProblem {
    offset: number;
    line: number;
    column: number;
    depth: number;
}

/** The first place where brackets nest deeper than `max` (strings and comments skipped), if any. */
export function findExcessiveNesting(text: string, max = MAX_NESTING): NestingProblem | undefined {
    let depth = 0;
    let line = 1;
    let lineStart = 0;
    for (let i = 0; i < text.length; i++) {
        const c = text[i]!;
        if (c === '\n') { line++; lineStart = i + 1; continue; }
        if (c === '"') {
            for (i++; i < text.length && text[i] !== '"' && text[i] !== '\n'; i++) if (text[i] === '\\') i++;
            if (text[i] === '\n') { line++; lineStart = i + 1; }
            continue;
        }
        if (c === '/' && text[i + 1] === '/') {
            while (i < text.length && text[i] !== '\n') i++;
            if (i < text.length) { line++; lineStart = i + 1; }
            continue;
        }
        if (c === '/' && text[i + 1] === '*') {
            for (i += 2; i < text.length && !(text[i] === '*' && text[i + 1] === '/'); i++) {
                if (text[i] === '\n') { line++; lineStart = i + 1; }
            }
            i++;
            continue;
        }
        if (c === '{' || c === '(' || c === '[') {
            depth++;
            if (depth > max) return { offset: i, line, column: i - lineStart + 1, depth };
        } else if (c === '}' || c === ')' || c === ']') {
            depth = Math.max(0, depth - 1);
        }
    }
    return undefined;
}

function emptyResult<T extends AstNode>(message: string, at: { offset: number; line: number; column: number }): ParseResult<T> {
    return {
        value: { $type: 'Model', imports: [], elements: [] } as unknown as T,
        lexerErrors: [{ message, offset: at.offset, line: at.line, column: at.column, length: 1 }],
        parserErrors: []
    } as ParseResult<T>;
}

const tooDeep = (): string => `Brackets are nested ${MAX_NESTING + 1} levels deep here; Cactal accepts at most ${MAX_NESTING}. The file is not analysed until this is fixed.`;
const overflowed = (err: RangeError): string => `The file is too deeply nested to be parsed (${err.message}).`;

/**
 * Document factory that refuses pathological nesting before it reaches the parser, on both of
 * Langium's ways in: `parse` (a document made from a text: `contract check`) and `parseAsync`
 * (a document the language server opens or updates). The server went through the second one
 * only, unguarded: 5,000 levels crashed it (RangeError), and such a file on disk left it silent.
 */
export class CactalDocumentFactory extends DefaultLangiumDocumentFactory {
    protected override parse<T extends AstNode>(uri: URI, text: string, options?: Parameters<DefaultLangiumDocumentFactory['parse']>[2]): ParseResult<T> {
        const deep = findExcessiveNesting(text);
        if (deep) return emptyResult(tooDeep(), deep);
        try {
            return super.parse<T>(uri, text, options);
        } catch (err) {
            if (err instanceof RangeError) return emptyResult(overflowed(err), { offset: 0, line: 1, column: 1 });
            throw err;
        }
    }

    protected override async parseAsync<T extends AstNode>(uri: URI, text: string, cancellationToken: CancellationToken): Promise<ParseResult<T>> {
        const deep = findExcessiveNesting(text);
        if (deep) return emptyResult(tooDeep(), deep);
        try {
            return await super.parseAsync<T>(uri, text, cancellationToken);
        } catch (err) {
            if (err instanceof RangeError) return emptyResult(overflowed(err), { offset: 0, line: 1, column: 1 });
            throw err;
        }
    }
}
