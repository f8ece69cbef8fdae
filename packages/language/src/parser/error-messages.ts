/**
 * Syntax error messages in the user's terms: "expected a duration (number + unit, e.g. 500us)"
 * rather than "Expecting token of type 'TIME'"; alternatives listed once, on one line.
 */
import { LangiumParserErrorMessageProvider } from 'langium';
import type { IToken, TokenType } from 'chevrotain';

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
    return `'${token.image}'`;
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

export class CactalParserErrorMessageProvider extends LangiumParserErrorMessageProvider {
    override buildMismatchTokenMessage(options: { expected: TokenType; actual: IToken; previous: IToken; ruleName: string }): string {
        if (options.expected.name === 'EOF') return `Unexpected ${found(options.actual)}: expected ${TOP_LEVEL}.`;
        if (isSubscribeToOrd(options)) return ORD_SUBSCRIBE;
        return `Expected ${describeToken(options.expected)} but found ${found(options.actual)}.`;
    }

    override buildNotAllInputParsedMessage(options: { firstRedundant: IToken; ruleName: string }): string {
        return `Unexpected ${found(options.firstRedundant)}: expected ${TOP_LEVEL}.`;
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
        const relational = actual && ['<', '>', '<=', '>='].includes(actual.image) && next.some((t) => t.name === '==')
            ? ' A relational test goes in parentheses: <(a > b)>.' : '';
        return `${after} ${list(next)} but found ${found(actual)}.${relational}`;
    }

    override buildEarlyExitMessage(options: { expectedIterationPaths: TokenType[][]; actual: IToken[]; previous: IToken; customUserDescription: string; ruleName: string }): string {
        const first = options.expectedIterationPaths.map((path) => path[0]).filter((t): t is TokenType => !!t);
        return `Expected at least one ${list(first)} but found ${found(options.actual[0])}.`;
    }
}
