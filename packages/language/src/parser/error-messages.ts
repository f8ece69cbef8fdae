/**
 * Syntax error messages in the user's terms: "expected a duration (number + unit, e.g. 500us)"
 * rather than "Expecting token of type 'TIME'"; alternatives listed once, on one line.
 */
import { LangiumParserErrorMessageProvider } from 'langium';
import type { IToken, TokenType } from 'chevrotain';
import { nearKeywords } from '../model/near-names.js';

const TERMINALS: Record<string, string> = {
    TIME: 'a duration (number + unit ns, us, ms or s, e.g. 500us)',
    INT: 'an integer',
    REAL: 'a real number',
    ID: 'a name',
    STRING: 'a string "..."'
};

const MAX_LISTED = 10;

/** Keywords that are also accepted as variable names (grammar rule Name): not listed when "a name" is. */
const SOFT_KEYWORDS = new Set(['data', 'flows', 'graph', 'realtime', 'modules', 'schemas', 'communications', 'configuration',
    'local', 'rules', 'started', 'endof', 'duration', 'elapsed', 'infinite', 'resttime', 'critical', 'periodic', 'event',
    'scheduling', 'parameters', 'in', 'out', 'module', 'schema', 'compute', 'notify', 'subscribe', 'parameterize', 'activate',
    'supervisor', 'scheduler', 'synchronous', 'asynchronous', 'function', 'datatype', 'import']);

const TOP_LEVEL = 'a datatype, function, module, schema, scheduler configuration or supervisor';

export function describeToken(type: TokenType): string {
    if (type.name === 'EOF') return 'the end of the file';
    const name = type.name.endsWith(':KW') ? type.name.slice(0, -3) : type.name;
    return TERMINALS[name] ?? `'${name}'`;
}

function found(token: IToken | undefined): string {
    if (!token || token.tokenType?.name === 'EOF' || token.image === undefined || token.image === '') return 'the end of the file';
    // a 5,000-character word is quoted cut, not echoed whole
    return token.image.length > 64 ? `'${token.image.slice(0, 64)}…'` : `'${token.image}'`;
}

function list(types: TokenType[]): string {
    const hasName = types.some((t) => t.name === 'ID');
    const names = [...new Set(types.filter((t) => !(hasName && SOFT_KEYWORDS.has(t.name))).map(describeToken))];
    const shown = names.slice(0, MAX_LISTED);
    const more = names.length > MAX_LISTED ? `, ... (${names.length - MAX_LISTED} more)` : '';
    if (shown.length <= 1) return (shown[0] ?? 'something else') + more;
    return `one of ${shown.slice(0, -1).join(', ')} or ${shown[shown.length - 1]}${more}`;
}

function tokenMatches(token: IToken, type: TokenType): boolean {
    return token.tokenType === type || token.tokenType?.name === type.name;
}

const ORD_SUBSCRIBE = "ORD events need no subscribe: every supervisor receives them. Remove this subscribe and test 'ORD:n' directly in a rule's condition.";

/** `subscribe ORD:n ...`: the source of a subscribe is a module or supervisor, never the scheduler. */
function isSubscribeToOrd(options: { expected: TokenType; actual: IToken; previous: IToken }): boolean {
    return options.expected.name === 'ID' && options.actual?.image === 'ORD' && options.previous?.image === 'subscribe';
}

/** The words a top-level element starts with (for "did you mean"). */
const TOP_LEVEL_WORDS = ['import', 'datatype', 'enum', 'const', 'function', 'synchronous', 'asynchronous', 'periodic', 'event', 'scheduler', 'supervisor'];

/** " Did you mean 'synchronous'?" when the token is a near miss of one of `words` (a typo in a keyword), else ''. */
export function didYouMean(token: IToken | undefined, words: string[]): string {
    const near = nearKeywords(token?.image, words);
    return near.length ? ` Did you mean '${near[0]}'?` : '';
}

/**
 * `20msec` is read as the duration `20ms` then the name `ec`: say what was meant, once, instead of a
 * puzzle about 'ec'. Empty when `actual` is not a name glued to a duration.
 */
export function unknownTimeUnit(previous: IToken | undefined, actual: IToken | undefined): string {
    if (!previous || !actual || previous.tokenType?.name !== 'TIME' || actual.tokenType?.name !== 'ID') return '';
    if (previous.endOffset === undefined || previous.endOffset + 1 !== actual.startOffset) return '';
    const written = previous.image + actual.image;
    const number = /^-?[0-9]+(\.[0-9]+)?/.exec(written)?.[0] ?? '';
    return `Unknown time unit '${written.slice(number.length)}' in '${written}': the units are ns, us, ms and s (e.g. ${number}ms).`;
}

/** Every keyword of the grammar (cactal.langium; a test checks the list against it), for a typo the expected tokens do not explain (`parametrize` where a
 *  rule's actions or its post-condition '[' may come: Did you mean 'parameterize'?). */
export const ALL_WORDS = ['activate', 'and', 'asynchronous', 'bool', 'communications', 'compute', 'configuration', 'const',
    'critical', 'data', 'datatype', 'duration', 'elapsed', 'endof', 'enum', 'event', 'false', 'float', 'flows', 'function', 'graph',
    'import', 'infinite', 'int', 'local', 'module', 'modules', 'notify', 'ord_schema', 'out', 'parameterize', 'parameters',
    'periodic', 'realtime', 'resttime', 'rules', 'scheduler', 'scheduling', 'schema', 'schemas', 'started', 'string', 'subscribe',
    'supervisor', 'synchronous', 'true', 'void'];

/** Did you mean one of the expected keywords, else any word of the language. */
function nearKeyword(token: IToken | undefined, expected: TokenType[]): string {
    return didYouMean(token, keywordsOf(expected)) || didYouMean(token, ALL_WORDS);
}

/**
 * The name just read, when it is a misspelt keyword that explains the error at the next token
 * (`[elapsd=1ms]`: 'elapsd' read as a module, then '=' where ':' was expected):
 * ` Did you mean 'elapsed' (not 'elapsd')?`, else ''.
 */
function nearKeywordBefore(previous: IToken | undefined): string {
    if (!previous || previous.tokenType?.name !== 'ID') return '';
    const near = didYouMean(previous, ALL_WORDS);
    return near ? near.replace(/\?$/, ` (not '${previous.image}')?`) : '';
}

/** Keywords among the expected token types (names only). */
function keywordsOf(types: TokenType[]): string[] {
    return types.map((t) => (t.name.endsWith(':KW') ? t.name.slice(0, -3) : t.name)).filter((n) => /^[a-z_]+$/i.test(n) && !(n in TERMINALS));
}

export class CactalParserErrorMessageProvider extends LangiumParserErrorMessageProvider {
    override buildMismatchTokenMessage(options: { expected: TokenType; actual: IToken; previous: IToken; ruleName: string }): string {
        const unit = unknownTimeUnit(options.previous, options.actual);
        if (unit) return unit;
        if (options.expected.name === 'EOF') return `Unexpected ${found(options.actual)}: expected ${TOP_LEVEL}.${didYouMean(options.actual, TOP_LEVEL_WORDS)}`;
        if (isSubscribeToOrd(options)) return ORD_SUBSCRIBE;
        return `Expected ${describeToken(options.expected)} but found ${found(options.actual)}.${nearKeyword(options.actual, [options.expected]) || nearKeywordBefore(options.previous)}`;
    }

    override buildNotAllInputParsedMessage(options: { firstRedundant: IToken; ruleName: string }): string {
        return `Unexpected ${found(options.firstRedundant)}: expected ${TOP_LEVEL}.${didYouMean(options.firstRedundant, TOP_LEVEL_WORDS)}`;
    }

    override buildNoViableAltMessage(options: { expectedPathsPerAlt: TokenType[][][]; actual: IToken[]; previous: IToken; customUserDescription: string; ruleName: string }): string {
        // skip the tokens that every viable path and the input share ('activate' before 'schema'/'supervisor'/...)
        const paths = options.expectedPathsPerAlt.flat();
        const matched = (path: TokenType[]) => {
            let m = 0;
            while (m < path.length - 1 && options.actual[m] && tokenMatches(options.actual[m]!, path[m]!)) m++;
            return m;
        };
        const depth = Math.max(0, ...paths.map(matched));
        const next = paths.filter((p) => matched(p) === depth).map((p) => p[depth]).filter((t): t is TokenType => !!t);
        const after = depth > 0 ? `After ${options.actual.slice(0, depth).map((t) => `'${t.image}'`).join(' ')}, expected` : 'Expected';
        const actual = options.actual[depth];
        const unit = unknownTimeUnit(depth > 0 ? options.actual[depth - 1] : options.previous, actual);
        if (unit) return unit;
        const relational = actual && ['<', '>', '<=', '>='].includes(actual.image) && next.some((t) => t.name === '==')
            ? ' A relational test goes in parentheses: <(a > b)>.'
            : actual?.image === '=' && next.some((t) => t.name === '==') ? " A comparison is written '=='." : '';
        return `${after} ${list(next)} but found ${found(actual)}.${relational}${nearKeyword(actual, next)}`;
    }

    override buildEarlyExitMessage(options: { expectedIterationPaths: TokenType[][]; actual: IToken[]; previous: IToken; customUserDescription: string; ruleName: string }): string {
        // `duration(L)=1sec{...} and ...`: the unit is what is wrong, not the missing 'and'
        const unit = unknownTimeUnit(options.previous, options.actual[0]);
        if (unit) return unit;
        const first = options.expectedIterationPaths.map((path) => path[0]).filter((t): t is TokenType => !!t);
        return `Expected at least one ${list(first)} but found ${found(options.actual[0])}.`;
    }
}
