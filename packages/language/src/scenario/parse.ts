/**
 * The `.scenario` parser (docs/simulation.md "Scenario files"): text -> typed steps with source
 * positions, and diagnostics. Browser-safe (no Node import) and total: it never throws, whatever
 * the text; every problem is a diagnostic naming the line and column, what is wrong and what was
 * expected. Names are not checked here (no model): `checkScenario` (model-check.ts) does that.
 *
 * One line = one directive, optionally timed: `[t=TIME] DIRECTIVE`; `expect at TIME ...` is the
 * same as `t=TIME expect ...`. A line without a time takes the previous line's time (0 at first).
 */
import { formatNanoseconds } from '@contract-studio/conventions';
import { didYouMean } from './did-you-mean.js';
import { unescapeString, unknownEscapeMessage, unknownEscapes } from '../model/strings.js';

/** 1-based line and columns; `endColumn` is exclusive. */
export interface SourceSpan {
    line: number;
    column: number;
    endColumn: number;
}

export interface ScenarioDiagnostic extends SourceSpan {
    severity: 'error' | 'warning';
    /** Stable code, e.g. `scenario-syntax`, `scenario-time-order`, `scenario-unknown-rule`. */
    code: string;
    message: string;
}

/** A value written in Cactal's value syntax (docs/language-reference.md). */
export type ScenarioValue =
    /** `value` is exact up to 2^53 only: `text` is the integer as written. */
    | { kind: 'int'; value: number; text: string; span: SourceSpan }
    | { kind: 'real'; value: number; text: string; span: SourceSpan }
    | { kind: 'string'; value: string; text: string; span: SourceSpan }
    | { kind: 'bool'; value: boolean; text: string; span: SourceSpan }
    /** `Mode.AUTO`: a member of an enumeration (extension, docs/language-reference.md §2.1). */
    | { kind: 'enum'; enumName: string; member: string; text: string; span: SourceSpan }
    | { kind: 'struct'; elements: ScenarioValue[]; text: string; span: SourceSpan };

/** A named thing of the project, with where it is written. */
export interface Name {
    text: string;
    span: SourceSpan;
}

export interface Argument {
    name: Name;
    value: ScenarioValue;
}

export type Expectation =
    | { kind: 'rule'; supervisor: Name; function: Name; rule: Name; active: boolean }
    | { kind: 'schema'; schema: Name; active: boolean }
    | { kind: 'function'; supervisor: Name; function: Name; running: boolean }
    | { kind: 'module'; module: Name; running: boolean }
    /** `local [SUP.fn.]name == value`: supervisor/function undefined when not written. */
    | { kind: 'local'; supervisor?: Name; function?: Name; local: Name; value: ScenarioValue }
    /** `deadline misses S == N` / `overruns S == N`: the periodic schema's count since the scenario started. */
    | { kind: 'count'; what: ScheduleCount; schema: Name; count: number };

/** What `expect deadline misses` and `expect overruns` count: ORD's figures of a periodic schema. */
export type ScheduleCount = 'deadline misses' | 'overruns';

export type StepBody =
    /** An event of a module's (or a supervisor's, or ORD's) out event port. */
    | { kind: 'event'; module: Name; port: number; portSpan: SourceSpan; portName?: Name; value?: ScenarioValue }
    | { kind: 'start'; supervisor: Name; function: Name; args: Argument[] }
    | { kind: 'stop'; supervisor: Name; function: Name }
    /** The module crashes: it stops running, never acks a release again. */
    | { kind: 'crash'; module: Name }
    /**
     * The asynchronous module's own code ends its run, as a real module's does; a supervisor that
     * needs it again starts it. Now (its current run), or, with `afterNs`, each run started from
     * now on (`once`: the next one only) ends that long after its start.
     */
    | { kind: 'finish'; module: Name; afterNs?: number; once?: boolean }
    /** From now on (or for its next release only) each release of the module takes `execNs`. */
    | { kind: 'exec'; module: Name; execNs: number; once: boolean }
    | { kind: 'expect'; expectation: Expectation };

export type Step = StepBody & {
    /** Virtual time of the step, in nanoseconds since the scenario started. */
    atNs: number;
    /** Whole line span (`column` 1, `endColumn` after the last character). */
    span: SourceSpan;
    /** The line's text without its comment, trimmed. */
    source: string;
};

export interface ParsedScenario {
    title?: string;
    /** `until TIME`: the virtual end of the scenario; undefined = the last step's time. */
    untilNs?: number;
    steps: Step[];
    diagnostics: ScenarioDiagnostic[];
}

/** Bounds: a scenario is hand-written or generated; anything above these is refused. */
export const MAX_SCENARIO_BYTES = 8 * 1024 * 1024;
export const MAX_STEPS = 1_000_000;
const MAX_VALUE_DEPTH = 32;
const MAX_DIAGNOSTICS = 200;
/** Longest message of a diagnostic (it quotes what was written). */
const MAX_MESSAGE_CHARS = 300;
/** Virtual times above one day are refused (int64 ns holds far more; this catches typos). */
export const MAX_TIME_NS = 86_400_000_000_000;

const UNIT_NS: Record<string, number> = { ns: 1, us: 1_000, ms: 1_000_000, s: 1_000_000_000 };

/** Parses a time literal (`300ms`, `1.5s`, `0`) to nanoseconds; undefined when it is not one. */
export function parseTimeLiteral(text: string): number | undefined {
    if (text === '0') return 0;
    const m = /^([0-9]+(?:\.[0-9]+)?)(ns|us|ms|s)$/.exec(text);
    if (!m) return undefined;
    const ns = Math.round(Number(m[1]) * UNIT_NS[m[2]!]!);
    return Number.isFinite(ns) ? ns : undefined;
}

/** Readable time: the largest unit that keeps it exact (`1s`, `300ms`, `1500us`, `7ns`). */
export function formatTime(ns: number): string {
    return ns === 0 ? '0' : formatNanoseconds(ns);
}

class Failure {
    constructor(readonly column: number, readonly endColumn: number, readonly message: string, readonly code = 'scenario-syntax') {}
}

/** A cursor over one line (0-based offsets; spans are reported 1-based). */
class LineCursor {
    pos = 0;
    /** Warnings about what the line's values hold (an unknown escape in a string): reported whether the line parses or not. */
    readonly warnings: Array<{ column: number; endColumn: number; code: string; message: string }> = [];
    constructor(readonly text: string, readonly line: number) {}

    skipSpaces(): void {
        while (this.pos < this.text.length && (this.text[this.pos] === ' ' || this.text[this.pos] === '\t')) this.pos++;
    }
    atEnd(): boolean {
        this.skipSpaces();
        return this.pos >= this.text.length;
    }
    span(from: number, to: number): SourceSpan {
        return { line: this.line, column: from + 1, endColumn: Math.max(to, from + 1) + 1 };
    }
    fail(message: string, from = this.pos, to = this.tokenEnd(from)): never {
        throw new Failure(from + 1, Math.max(to, from + 1) + 1, message);
    }
    /** End of the whitespace-delimited token starting at `from`. */
    tokenEnd(from: number): number {
        let i = from;
        while (i < this.text.length && !/[\s]/.test(this.text[i]!)) i++;
        return i;
    }
    peekWord(): string {
        this.skipSpaces();
        const m = /^[A-Za-z_][A-Za-z0-9_]*/.exec(this.text.slice(this.pos));
        return m ? m[0] : '';
    }
    /** An identifier, or a failure that says what was expected. */
    ident(what: string): Name {
        this.skipSpaces();
        const m = /^[A-Za-z_][A-Za-z0-9_]*/.exec(this.text.slice(this.pos));
        if (!m) this.fail(this.pos >= this.text.length ? `expected ${what} at the end of the line` : `expected ${what}, found '${this.text.slice(this.pos, this.tokenEnd(this.pos))}'`);
        const from = this.pos;
        this.pos += m[0].length;
        return { text: m[0], span: this.span(from, this.pos) };
    }
    keyword(word: string): boolean {
        this.skipSpaces();
        const rest = this.text.slice(this.pos);
        if (rest.startsWith(word) && !/[A-Za-z0-9_]/.test(rest[word.length] ?? '')) {
            this.pos += word.length;
            return true;
        }
        return false;
    }
    char(c: string): boolean {
        this.skipSpaces();
        if (this.text[this.pos] === c) {
            this.pos++;
            return true;
        }
        return false;
    }
    expectChar(c: string, what: string): void {
        if (!this.char(c)) this.fail(this.pos >= this.text.length ? `expected '${c}' ${what} at the end of the line` : `expected '${c}' ${what}, found '${this.text[this.pos]}'`, this.pos, this.pos + 1);
    }
    time(what: string): { ns: number; span: SourceSpan } {
        this.skipSpaces();
        const from = this.pos;
        const m = /^[0-9A-Za-z.]+/.exec(this.text.slice(this.pos));
        const text = m ? m[0] : '';
        const ns = parseTimeLiteral(text);
        if (ns === undefined) this.fail(`expected ${what} (a time such as 300ms, 1.5s, 250us, 0), found '${text || this.text.slice(this.pos, this.tokenEnd(this.pos)) || 'the end of the line'}'`, from, from + Math.max(text.length, 1));
        if (ns > MAX_TIME_NS) this.fail(`${text} is beyond the longest scenario (1 day)`, from, from + text.length);
        // the virtual clock counts whole nanoseconds: a finer time was rounded without a word (a
        // unit of 10^k ns takes k decimals)
        const fine = /\.([0-9]+)(ns|us|ms|s)$/.exec(text);
        const decimals = fine ? String(UNIT_NS[fine[2]!]).length - 1 : 0;
        if (fine && fine[1]!.replace(/0+$/, '').length > decimals) this.fail(`${text} is not a whole number of nanoseconds (the virtual clock's step): ${decimals === 0 ? 'no fraction of a nanosecond' : `at most ${decimals} decimals in ${fine[2]}`}`, from, from + text.length);
        this.pos += text.length;
        return { ns, span: this.span(from, this.pos) };
    }
    value(depth = 0): ScenarioValue {
        this.skipSpaces();
        const from = this.pos;
        if (depth > MAX_VALUE_DEPTH) this.fail(`value nested deeper than ${MAX_VALUE_DEPTH} levels`);
        const rest = this.text.slice(this.pos);
        if (rest.startsWith('{')) {
            this.pos++;
            const elements: ScenarioValue[] = [];
            if (!this.char('}')) {
                for (;;) {
                    elements.push(this.value(depth + 1));
                    if (this.char('}')) break;
                    this.expectChar(',', 'or \'}\' in a structured value');
                }
            }
            // a copy of its own length: V8 gave the array pushed to room for 17 elements (152 bytes for two)
            return { kind: 'struct', elements: elements.slice(), text: this.text.slice(from, this.pos), span: this.span(from, this.pos) };
        }
        const str = /^"((?:\\.|[^"\\\r\n])*)"/.exec(rest);
        if (str) {
            // a raw control character (a NUL, an escape) would not reach the harness whole: written as an escape only
            if (/[\u0000-\u0008\u000b-\u001f\u007f]/.test(str[1]!)) this.fail('a string holds no raw control character: write it as an escape (\\n, \\t, \\r)', from, from + str[0].length);
            this.pos += str[0].length;
            // the language's escapes (as in a .contract file): \n \t \r \b \f \0, any other character itself, with a warning
            for (const e of unknownEscapes(str[1]!)) {
                const at = from + 1 + e.offset;
                this.warnings.push({ column: at + 1, endColumn: at + 3, code: 'scenario-unknown-escape', message: unknownEscapeMessage(e.char) });
            }
            const value = unescapeString(str[1]!);
            return { kind: 'string', value, text: str[0], span: this.span(from, this.pos) };
        }
        const bool = /^(true|false)(?![A-Za-z0-9_])/.exec(rest);
        if (bool) {
            this.pos += bool[0].length;
            return { kind: 'bool', value: bool[1] === 'true', text: bool[0], span: this.span(from, this.pos) };
        }
        const member = /^([A-Za-z_][A-Za-z0-9_]*)\.([A-Za-z_][A-Za-z0-9_]*)/.exec(rest);
        if (member) {
            this.pos += member[0].length;
            return { kind: 'enum', enumName: member[1]!, member: member[2]!, text: member[0], span: this.span(from, this.pos) };
        }
        if (rest.startsWith('"')) this.fail('unterminated string (a string ends with " on the same line)', from, this.text.length);
        const real = /^-?([0-9]+\.[0-9]*([eE][-+]?[0-9]+)?|\.[0-9]+([eE][-+]?[0-9]+)?|[0-9]+[eE][-+]?[0-9]+)/.exec(rest);
        if (real) {
            this.pos += real[0].length;
            return { kind: 'real', value: Number(real[0]), text: real[0], span: this.span(from, this.pos) };
        }
        const int = /^-?[0-9]+/.exec(rest);
        if (int) {
            this.pos += int[0].length;
            // whether it fits is the model check's, by its type (an int is a C long, a float a C double:
            // 99999999999999999999 is a float, not an int); the harness is given the text, exact
            return { kind: 'int', value: Number(int[0]), text: int[0], span: this.span(from, this.pos) };
        }
        this.fail(`expected a value (integer, real, "string", true, false, Enum.MEMBER or {structured, value}), found '${this.text.slice(this.pos, this.tokenEnd(this.pos)) || 'the end of the line'}'`);
    }
    endOfLine(after: string): void {
        if (this.atEnd()) return;
        // `crash SCN at 10ms`: only `expect` takes `at TIME`; another step's time comes first
        const at = /^at\s+(\S+)\s*$/.exec(this.text.slice(this.pos));
        const step = this.text.slice(0, this.pos).trim();
        const hint = !at ? '' : /^t\s*=/.test(step) ? " (only 'expect' takes 'at TIME')"
            : ` (only 'expect' takes 'at TIME': write 't=${at[1]} ${step}')`;
        this.fail(`unexpected '${this.text.slice(this.pos, this.tokenEnd(this.pos))}' after ${after}${hint}`, this.pos, this.text.length);
    }
}

/** Removes a `#` comment that is not inside a string. */
function stripComment(line: string): string {
    let inString = false;
    for (let i = 0; i < line.length; i++) {
        const c = line[i];
        if (inString) {
            if (c === '\\') i++;
            else if (c === '"') inString = false;
        } else if (c === '"') inString = true;
        else if (c === '#') return line.slice(0, i);
    }
    return line;
}

function qualified(cur: LineCursor, what: string): { supervisor: Name; function: Name } {
    const supervisor = cur.ident(`a supervisor name (${what})`);
    cur.expectChar('.', `between the supervisor and the function (${what})`);
    const fn = cur.ident(`a function name (${what})`);
    return { supervisor, function: fn };
}

/** The words a step may start with (besides an event `MODULE:PORT value`): the IDE's Simulate panel injects these but `start`. */
export const STEP_DIRECTIVES: readonly string[] = ['start', 'stop', 'crash', 'finish', 'exec', 'expect'];
/** The words a scenario line may start with (besides an event `MODULE:PORT value`). */
const DIRECTIVES = [...STEP_DIRECTIVES, 'scenario', 'until'];

function activeWord(cur: LineCursor, yes: string, no: string): boolean {
    if (cur.keyword(yes)) return true;
    if (cur.keyword(no)) return false;
    const found = cur.peekWord();
    return cur.fail(`expected '${yes}' or '${no}'${found ? `, found '${found}'${didYouMean(found, [yes, no])}` : ''}`);
}

/** What `expect` may be followed by. */
const EXPECTED_WHAT = ['rule', 'schema', 'function', 'module', 'local', 'deadline', 'overruns'];
/** The largest count `expect deadline misses` / `expect overruns` takes. */
const MAX_COUNT = 1_000_000_000;

/** `SCHEMA == N` after `deadline misses` or `overruns`. */
function scheduleCount(cur: LineCursor, what: ScheduleCount): Expectation {
    const schema = cur.ident('a periodic schema name');
    cur.skipSpaces();
    if (!cur.text.startsWith('==', cur.pos)) cur.fail(`expected '==' after the schema's name (expect ${what} ${schema.text} == N)`);
    cur.pos += 2;
    cur.skipSpaces();
    const m = /^[0-9]+(?![A-Za-z0-9_.])/.exec(cur.text.slice(cur.pos));
    if (!m || Number(m[0]) > MAX_COUNT) cur.fail(`expected a count (a whole number, 0 to ${MAX_COUNT}) after '=='`);
    cur.pos += m[0].length;
    return { kind: 'count', what, schema, count: Number(m[0]) };
}

function parseExpectation(cur: LineCursor): Expectation {
    const what = cur.peekWord();
    switch (what) {
        case 'rule': {
            cur.keyword('rule');
            const q = qualified(cur, 'SUP.function.RULE');
            cur.expectChar('.', 'between the function and the rule (SUP.function.RULE)');
            const rule = cur.ident('a rule label (SUP.function.RULE)');
            return { kind: 'rule', ...q, rule, active: activeWord(cur, 'active', 'inactive') };
        }
        case 'schema': {
            cur.keyword('schema');
            const schema = cur.ident('a schema name');
            return { kind: 'schema', schema, active: activeWord(cur, 'active', 'inactive') };
        }
        case 'function': {
            cur.keyword('function');
            const q = qualified(cur, 'SUP.function');
            return { kind: 'function', ...q, running: activeWord(cur, 'running', 'stopped') };
        }
        case 'module': {
            cur.keyword('module');
            const module = cur.ident('a module name');
            return { kind: 'module', module, running: activeWord(cur, 'running', 'stopped') };
        }
        case 'local': {
            cur.keyword('local');
            const parts = [cur.ident('a local variable')];
            while (parts.length < 3 && cur.char('.')) parts.push(cur.ident('a name after \'.\''));
            if (parts.length === 2) cur.fail('expected SUP.function.local or a bare local name', parts[0]!.span.column - 1, parts[1]!.span.endColumn - 1);
            cur.skipSpaces();
            if (!cur.text.startsWith('==', cur.pos)) cur.fail(`expected '==' after the local's name`);
            cur.pos += 2;
            const value = cur.value();
            return parts.length === 3
                ? { kind: 'local', supervisor: parts[0], function: parts[1], local: parts[2]!, value }
                : { kind: 'local', local: parts[0]!, value };
        }
        case 'deadline':
            cur.keyword('deadline');
            if (!cur.keyword('misses')) cur.fail(`expected 'misses' after 'deadline' (expect deadline misses SCHEMA == N)`);
            return scheduleCount(cur, 'deadline misses');
        case 'overruns':
            cur.keyword('overruns');
            return scheduleCount(cur, 'overruns');
        default:
            return cur.fail(`expected what to expect: ${EXPECTED_WHAT.join(', ')}${what ? `, found '${what}'${didYouMean(what, EXPECTED_WHAT)}` : ''}`);
    }
}

function parseArgs(cur: LineCursor): Argument[] {
    const args: Argument[] = [];
    if (!cur.char('(')) return args;
    if (cur.char(')')) return args;
    for (;;) {
        const name = cur.ident('a parameter name');
        cur.expectChar('=', `after the parameter name '${name.text}'`);
        args.push({ name, value: cur.value() });
        if (cur.char(')')) return args;
        cur.expectChar(',', 'or \')\' between parameters');
    }
}

/** The directive after the optional time: returns the step body, or a header effect. */
function parseDirective(cur: LineCursor, out: ParsedScenario, timed: boolean): StepBody | undefined {
    const word = cur.peekWord();
    const wordSpan = cur.span(cur.pos, cur.pos + word.length);
    const headerOnly = (name: string) => {
        if (timed) throw new Failure(wordSpan.column, wordSpan.endColumn, `'${name}' takes no time (t=...): it is about the whole scenario`);
    };
    if (word === 'scenario') {
        headerOnly('scenario');
        if (out.title !== undefined) throw new Failure(wordSpan.column, wordSpan.endColumn, `a second 'scenario' line: a scenario has one title ('${out.title.slice(0, 60)}' already)`);
        cur.keyword('scenario');
        cur.skipSpaces();
        out.title = cur.text.slice(cur.pos).trim();
        return undefined;
    }
    if (word === 'until') {
        headerOnly('until');
        if (out.untilNs !== undefined) throw new Failure(wordSpan.column, wordSpan.endColumn, `a second 'until' line: a scenario has one end (${formatTime(out.untilNs)} already)`);
        cur.keyword('until');
        out.untilNs = cur.time('the end of the scenario').ns;
        cur.endOfLine('the end time');
        return undefined;
    }
    if (word === 'start' && !/^start\s*:/.test(cur.text.slice(cur.pos))) {
        cur.keyword('start');
        const q = qualified(cur, 'SUP.function(param = value, ...)');
        const args = parseArgs(cur);
        cur.endOfLine('the function\'s parameters');
        return { kind: 'start', ...q, args };
    }
    if (word === 'stop') {
        cur.keyword('stop');
        const q = qualified(cur, 'SUP.function');
        cur.endOfLine('the function');
        return { kind: 'stop', ...q };
    }
    if (word === 'crash') {
        cur.keyword('crash');
        const module = cur.ident('the module that crashes');
        cur.endOfLine('the module');
        return { kind: 'crash', module };
    }
    if (word === 'finish') {
        cur.keyword('finish');
        const module = cur.ident('the asynchronous module whose code ends its run');
        if (!cur.keyword('after')) {
            cur.endOfLine("the module (or 'after TIME' for each of its runs)");
            return { kind: 'finish', module };
        }
        const time = cur.time('how long each of its runs lasts');
        const once = cur.keyword('once');
        cur.endOfLine(once ? "'once'" : "the time (or 'once')");
        return { kind: 'finish', module, afterNs: time.ns, once };
    }
    if (word === 'exec') {
        cur.keyword('exec');
        const module = cur.ident('a synchronous module');
        const time = cur.time('its execution time per release');
        const once = cur.keyword('once');
        cur.endOfLine(once ? "'once'" : "the execution time (or 'once')");
        return { kind: 'exec', module, execNs: time.ns, once };
    }
    if (word === 'expect') {
        cur.keyword('expect');
        if (cur.keyword('at')) {
            if (timed) cur.fail("the time is already given by 't=' on this line");
            const time = cur.time('the time of the expectation');
            (cur as LineCursor & { expectAt?: number }).expectAt = time.ns;
        }
        const expectation = parseExpectation(cur);
        cur.endOfLine('the expectation');
        return { kind: 'expect', expectation };
    }
    if (word !== '') {
        // MODULE:PORT [name=]value
        const module = cur.ident('a module');
        if (!cur.char(':')) {
            cur.fail(`unknown directive '${word}': expected start, stop, crash, finish, exec, expect, scenario, until or an event MODULE:PORT value${didYouMean(word, DIRECTIVES)}`, wordSpan.column - 1, wordSpan.endColumn - 1);
        }
        cur.skipSpaces();
        const pm = /^[0-9]+/.exec(cur.text.slice(cur.pos));
        if (!pm) cur.fail(`expected an event port number after '${module.text}:'`);
        const portSpan = cur.span(cur.pos, cur.pos + pm[0].length);
        const port = Number(pm[0]);
        cur.pos += pm[0].length;
        if (port > 65535) throw new Failure(portSpan.column, portSpan.endColumn, `port ${pm[0]} is out of range`);
        if (cur.atEnd()) return { kind: 'event', module, port, portSpan };
        let portName: Name | undefined;
        const save = cur.pos;
        if (/^[A-Za-z_]/.test(cur.text.slice(cur.pos))) {
            portName = cur.ident('the port variable');
            if (!cur.char('=')) {
                cur.pos = save;
                portName = undefined;
            }
        }
        const value = cur.value();
        cur.endOfLine('the event\'s value');
        return { kind: 'event', module, port, portSpan, portName, value };
    }
    return cur.fail('expected a directive: start, stop, crash, finish, exec, expect, an event MODULE:PORT value, scenario or until');
}

/**
 * The lines of a text, one at a time (an 8 MiB scenario's 200,000 lines are not all held at once):
 * a line ends at LF, CRLF or a lone CR (an old Mac's, as editors read it: a CR inside a line was quoted as '').
 */
function* linesOf(text: string): Generator<string> {
    const lineBreak = /\r\n|\r|\n/g;
    let start = 0;
    for (let m = lineBreak.exec(text); m; m = lineBreak.exec(text)) {
        yield text.slice(start, m.index);
        start = lineBreak.lastIndex;
    }
    yield text.slice(start);
}

/**
 * The step of a body: its time, line span and source added to the body itself. Not a spread
 * (`{ ...body, atNs, span, source }`): once V8 has seen a few kinds of body, it gives each copy a
 * hidden class of its own: some 330 bytes a step, a third of what an 8 MiB scenario of mixed lines kept.
 */
function asStep(body: StepBody, atNs: number, span: SourceSpan, source: string): Step {
    return Object.assign(body, { atNs, span, source });
}

/** Parses a whole scenario text. Never throws. */
export function parseScenario(text: string): ParsedScenario {
    const out: ParsedScenario = { steps: [], diagnostics: [] };
    let unlisted = 0;
    let lastLine = 1;
    const diag = (d: Omit<ScenarioDiagnostic, 'severity'> & { severity?: 'error' | 'warning' }) => {
        lastLine = d.line;
        // a message quotes what was written: a 10,000-character word is cut, not echoed whole
        const message = d.message.length > MAX_MESSAGE_CHARS ? `${d.message.slice(0, MAX_MESSAGE_CHARS)}…` : d.message;
        if (out.diagnostics.length < MAX_DIAGNOSTICS) out.diagnostics.push({ severity: 'error', ...d, message });
        else unlisted++;
    };
    const said = () => {
        if (unlisted > 0) out.diagnostics.push({ severity: 'error', line: lastLine, column: 1, endColumn: 2, code: 'scenario-syntax', message: `${unlisted} more problem(s) not listed: the first ${MAX_DIAGNOSTICS} are` });
        return out;
    };
    if (typeof text !== 'string') {
        diag({ line: 1, column: 1, endColumn: 2, code: 'scenario-syntax', message: 'a scenario is text' });
        return out;
    }
    if (text.length > MAX_SCENARIO_BYTES) {
        diag({ line: 1, column: 1, endColumn: 2, code: 'scenario-too-large', message: `the scenario is ${text.length} characters long; at most ${MAX_SCENARIO_BYTES} are read` });
        return out;
    }
    // a byte order mark (a file saved by a Windows editor) is no part of the first line
    if (text.charCodeAt(0) === 0xfeff) text = text.slice(1);
    let now = 0;
    let sawStep = false;
    let i = -1; // the line's index (0-based)
    for (const raw of linesOf(text)) {
        i++;
        const body = stripComment(raw).replace(/\s+$/, '');
        if (body.trim() === '') continue;
        const cur = new LineCursor(body, i + 1);
        try {
            let timed = false;
            let atNs = now;
            let timeSpan: SourceSpan | undefined;
            cur.skipSpaces();
            if (cur.text.startsWith('t=', cur.pos) || cur.text.startsWith('t =', cur.pos)) {
                cur.pos = cur.text.indexOf('=', cur.pos) + 1;
                const time = cur.time('the step\'s time after t=');
                atNs = time.ns;
                timeSpan = time.span;
                timed = true;
            }
            const stepBody = parseDirective(cur, out, timed);
            if (!stepBody) {
                if (sawStep) diag({ line: i + 1, column: 1, endColumn: body.length + 1, code: 'scenario-header-late', severity: 'warning', message: 'scenario and until are header lines: put them before the first step' });
                continue;
            }
            const expectAt = (cur as LineCursor & { expectAt?: number }).expectAt;
            if (expectAt !== undefined) {
                atNs = expectAt;
                timeSpan = undefined;
            }
            if (atNs < now) {
                const span = timeSpan ?? { line: i + 1, column: 1, endColumn: body.length + 1 };
                diag({ ...span, code: 'scenario-time-order', message: `steps go forward in time: ${formatTime(atNs)} is before the previous step's ${formatTime(now)}` });
                continue;
            }
            now = atNs;
            if (out.steps.length >= MAX_STEPS) {
                diag({ line: i + 1, column: 1, endColumn: body.length + 1, code: 'scenario-too-large', message: `more than ${MAX_STEPS} steps; the rest is ignored` });
                break;
            }
            sawStep = true;
            const leading = body.length - body.trimStart().length;
            out.steps.push(asStep(stepBody, atNs, { line: i + 1, column: leading + 1, endColumn: body.length + 1 }, body.trim()));
        } catch (e) {
            if (e instanceof Failure) diag({ line: i + 1, column: e.column, endColumn: e.endColumn, code: e.code, message: e.message });
            else diag({ line: i + 1, column: 1, endColumn: body.length + 1, code: 'scenario-syntax', message: `cannot read this line (${e instanceof Error ? e.message : String(e)})` });
        } finally {
            for (const w of cur.warnings) diag({ line: i + 1, ...w, severity: 'warning' });
        }
    }
    if (out.untilNs !== undefined && out.steps.length > 0 && out.untilNs < now) {
        const last = out.steps[out.steps.length - 1]!;
        diag({ ...last.span, code: 'scenario-time-order', message: `this step at ${formatTime(now)} is after the scenario's end (until ${formatTime(out.untilNs)})` });
    }
    return said();
}
