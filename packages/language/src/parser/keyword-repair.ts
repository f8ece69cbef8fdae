/**
 * A misspelt keyword is read as the keyword it was meant to be. The parser's recovery does not
 * know what was meant: `activate restime module MAA` in a rule's actions gave 23 errors down to the
 * end of the file (the rules after it read as supervision functions), and 9 `import-unused` hints
 * (the rules that used the imports were lost). The error says which keyword was probably meant; the
 * text is parsed again with the misspelt word read as that keyword, and the repair is kept when the
 * parser then reads the word and the CHECK_TOKENS tokens after it without an error (a repair by
 * substitution, as Burke and Fisher's). The file then reports the misspelling, with the keyword that
 * fits, and whatever else is wrong in it read as the user meant it: no follow-on errors.
 */
import {
    CstUtils, DefaultLexer, GrammarUtils, LangiumParser, createParser,
    type AstNode, type LangiumCoreServices, type LexerResult, type ParseResult, type ParserOptions, type TokenizeOptions
} from 'langium';
import type { IRecognitionException, IToken, TokenType } from 'chevrotain';
import { nearKeywords } from '../model/near-names.js';
import { ALL_WORDS } from './error-messages.js';

/** At most this many parses of one text (the first included): each repair tried costs one. */
const MAX_PARSES = 8;
/** The tokens after a repaired word that must parse for the repair to be kept. */
const CHECK_TOKENS = 3;

/** The lexer, reading the keywords of the repairs being tried in place of the misspelt words. */
export class CactalLexer extends DefaultLexer {
    /** Offset of a misspelt word -> the keyword read there (empty but during a repair). */
    readonly readAs = new Map<number, TokenType>();

    override tokenize(text: string, options?: TokenizeOptions): LexerResult {
        const result = super.tokenize(text, options);
        if (this.readAs.size === 0) return result;
        for (const token of result.tokens) {
            const keyword = this.readAs.get(token.startOffset);
            if (keyword) {
                token.tokenType = keyword;
                token.tokenTypeIdx = keyword.tokenTypeIdx!;
            }
        }
        return result;
    }
}

interface Repair {
    error: IRecognitionException;
    token: IToken;
    keyword: string;
}

export class CactalParser extends LangiumParser {
    override parse<T extends AstNode = AstNode>(input: string, options?: ParserOptions): ParseResult<T> {
        let result = super.parse<T>(input, options);
        const lexer = this.lexer;
        if (result.parserErrors.length === 0 || !(lexer instanceof CactalLexer)) return result;
        const tokens = lexer.tokenize(input).tokens;
        const repairs: Repair[] = [];
        let parses = 1;
        let done = -1; // the errors up to this offset are repaired or cannot be
        try {
            search: for (;;) {
                for (const error of result.parserErrors) {
                    const at = offsetOf(error, input);
                    if (at <= done) continue;
                    done = at;
                    for (const { token, index, keyword } of candidates(error, tokens, lexer)) {
                        if (lexer.readAs.has(token.startOffset)) continue; // repaired already
                        if (parses++ >= MAX_PARSES) break search;
                        lexer.readAs.set(token.startOffset, keyword);
                        const next = this.parseOrUndefined<T>(input, options);
                        // no error from the first error to CHECK_TOKENS tokens after the word
                        const from = Math.min(at, token.startOffset);
                        const until = tokens[index + CHECK_TOKENS]?.startOffset ?? input.length;
                        if (next && !next.parserErrors.some((e) => offsetOf(e, input) >= from && offsetOf(e, input) <= until)) {
                            result = next;
                            repairs.push({ error, token, keyword: keyword.name });
                            done = Math.max(done, token.startOffset);
                            continue search; // the errors of the new parse after this one
                        }
                        lexer.readAs.delete(token.startOffset);
                    }
                }
                break;
            }
        } finally {
            lexer.readAs.clear();
        }
        for (const repair of repairs) {
            repair.error.message = suggesting(repair.error.message, repair.token.image, repair.keyword);
            // on the misspelt word, not where the recovery tripped (`[elapsd=1ms]` failed at '=')
            repair.error.token = repair.token;
            readAsKeyword(result.value, repair);
        }
        result.parserErrors = [...repairs.map((r) => r.error), ...result.parserErrors].sort((a, b) => offsetOf(a, input) - offsetOf(b, input));
        return result;
    }

    /** A parse with the repairs being tried; undefined when it overflows the stack (the recovery of thousands of errors nests). */
    private parseOrUndefined<T extends AstNode>(input: string, options?: ParserOptions): ParseResult<T> | undefined {
        try {
            return super.parse<T>(input, options);
        } catch (err) {
            if (err instanceof RangeError) return undefined;
            throw err;
        }
    }
}

/** Where an error is: its token, or the token before an inserted one, or the end of the text. */
function offsetOf(error: IRecognitionException, input: string): number {
    const previous = (error as { previousToken?: IToken }).previousToken;
    if (Number.isFinite(error.token.startOffset)) return error.token.startOffset;
    return previous && Number.isFinite(previous.startOffset) ? previous.startOffset : input.length;
}

/**
 * The words around an error that may be misspelt keywords, with the keywords to try: the error's
 * token, the name read just before it (`[elapsd=1ms]` fails at '='), and the two after it (the
 * lookahead of a choice: `activate restime` fails at 'activate').
 */
function candidates(error: IRecognitionException, tokens: IToken[], lexer: CactalLexer): Array<{ token: IToken; index: number; keyword: TokenType }> {
    const at = firstTokenFrom(tokens, error.token.startOffset);
    if (at === tokens.length) return [];
    return [at, at - 1, at + 1, at + 2].flatMap((index) => {
        const token = tokens[index];
        if (!token || token.tokenType.name !== 'ID') return [];
        return nearKeywords(token.image, ALL_WORDS).slice(0, 3).flatMap((word) => {
            const keyword = lexer.definition[word];
            return keyword ? [{ token, index, keyword }] : [];
        });
    });
}

/** Index of the first token at or after `offset` (tokens.length when none, or for NaN): a binary search. */
function firstTokenFrom(tokens: IToken[], offset: number): number {
    if (Number.isNaN(offset)) return tokens.length;
    let low = 0;
    let high = tokens.length;
    while (low < high) {
        const mid = (low + high) >> 1;
        if (tokens[mid]!.startOffset < offset) low = mid + 1;
        else high = mid;
    }
    return low;
}

/** The error's message, suggesting the keyword that made the text parse. */
function suggesting(message: string, word: string, keyword: string): string {
    const base = message.replace(/ Did you mean .*\?$/, '');
    // `Expected '[' but found 'subscrib'` names what the parser's recovery wanted, which the keyword
    // meant is not (a rule's actions go on after a pre-condition): the word and the keyword say it all
    if (/^Expected .* but found /.test(base)) return `Unexpected '${word}'. Did you mean '${keyword}'? (the rest of the file is checked as if it were)`;
    if (message.includes(`Did you mean '${keyword}'`)) return message;
    return `${base} Did you mean '${keyword}'${base.includes(`found '${word}'`) ? '' : ` (not '${word}')`}?`;
}

/** The AST holds the keyword, not the misspelt word (`kind = 'periodic'` for `periodc schema`). */
function readAsKeyword(root: AstNode, { token, keyword }: Repair): void {
    const leaf = root.$cstNode && CstUtils.findLeafNodeAtOffset(root.$cstNode, token.startOffset);
    const assignment = leaf && GrammarUtils.findAssignment(leaf);
    if (!leaf || !assignment) return;
    const node = leaf.astNode as unknown as Record<string, unknown>;
    if (node[assignment.feature] === token.image) node[assignment.feature] = keyword;
}

/** The Langium parser of the grammar, as `createLangiumParser` builds it, with the repairs. */
export function createCactalParser(services: LangiumCoreServices): LangiumParser {
    const parser = new CactalParser(services);
    createParser(services.Grammar, parser, services.parser.Lexer.definition);
    parser.finalize();
    return parser;
}
