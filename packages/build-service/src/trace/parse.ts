/**
 * Reads a run's CSV logs into typed, time-ordered trace records (docs/runtime-api.md "Trace
 * records"). Browser-safe (no Node API): the caller hands the files' text. The logs come out of
 * a sandbox, so the input is hostile: lines are bounded, nothing throws, and every line that is
 * not a record of the table is kept as an `unknown` record saying why.
 */
import { splitCsvRecord } from './csv-line.js';
import { MinHeap } from './min-heap.js';
import { USER_KIND, isUserEventName, traceKind } from './record-kinds.js';
import { isDigitsIn, isModuleNameIn, isPlainIntegerIn, spaceIn, wordValueIn } from './field-checks.js';
import { SCHEDULER_LINES, SUPERVISOR_LINES, classifyLine } from './text-lines.js';
import type { KnownRecord, RuleCause, RuleRecord, TraceRecord, UnknownRecord } from './records.js';
import { LogClock, monoTextProblem, posingAs } from './log-clock.js';

export const CSV_HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
/**
 * Why a file read as a log is refused whole: the runtime writes its header as a log's first line
 * (csvlog.c), so a file whose first line is something else was not written by it (a module's code
 * made it, in logs/ or elsewhere: `ORD_<date>.csv` of forged deadline misses). None of its lines
 * is taken for a record: said once, as the Timeline says it (docs/runtime-api.md "Whose records,
 * and their times").
 */
export const NOT_A_LOG_WHY = `not a ContrACT CSV log (it does not begin with the runtime's header \`${CSV_HEADER}\`): none of its lines is taken for a record`;

/** Whether text[from, to) (a file's first line, its newline left out) is the runtime's header (a `\r` before the newline allowed). */
export function isLogHeaderIn(text: string, from = 0, to = text.length): boolean {
    const end = to > from && text.charCodeAt(to - 1) === 13 /* \r */ ? to - 1 : to;
    return end - from === CSV_HEADER.length && text.startsWith(CSV_HEADER, from);
}

/**
 * The one unknown record a refused file (NOT_A_LOG_WHY) is read as: its line 1, the reason. A
 * streamed log's line 1 is such a line too (the build service never sends a log's header, and
 * sends nothing more of a file whose first line is not it: pipeline/trace-lines.ts).
 */
export function notALogRecord(file: string, firstLine: string): UnknownRecord {
    return unknown(file, 1, NOT_A_LOG_WHY, firstLine);
}

/**
 * A line of a log as the build service's live trace sends it (pipeline/trace-lines.ts): its line 1
 * is sent only when it is not the runtime's header (then nothing more of the file is), so a line 1
 * is the one unknown record of a file that is no log; any other line is parseRecordLine's.
 */
export function parseStreamedLine(file: string, lineNo: number, line: string, clock?: LogClock): TraceRecord {
    return lineNo === 1 ? notALogRecord(file, line) : parseRecordLine(file, lineNo, line, clock);
}

/** Longer lines are not records (csvlog.c writes at most about 1 KiB per record). */
export const MAX_LINE_CHARS = 4096;

export interface LogFile {
    name: string;
    text: string;
}

/**
 * A string of its own: a piece cut out of a longer string (slice, split, a regular expression's
 * match) is, in V8, a view that keeps the whole string alive. A record kept (the merge of a
 * streamed trace, a replay's buffer) keeps this copy, never the long line it was cut from.
 */
export function ownString(s: string): string {
    return s.length < 13 ? s : (' ' + s).slice(1); // shorter ones are copied by V8 itself
}

/** A line that is no record: why, and its first 200 characters (copies: the record keeps nothing more of the line). */
function unknown(file: string, line: number, reason: string, text: string): UnknownRecord {
    return { kind: 'unknown', file, line, reason: ownString(reason), text: ownString(text.slice(0, 200)) };
}

/** `key=value` words of a detail (the first of each key: field-checks.ts wordValueIn), values as
 *  numbers when they are plain digits; restKey's value is the rest of the detail. Each key is looked for in place rather than by splitting the
 *  detail into words: this runs for every record of a live trace (thousands a second). */
function detailFields(detail: string, keys: readonly string[], restKey?: string): Record<string, string | number> {
    const out: Record<string, string | number> = {};
    for (const key of keys) {
        const from = wordValueIn(detail, key);
        if (from < 0) continue;
        const end = key === restKey ? detail.length : spaceIn(detail, from, detail.length);
        const value = detail.slice(from, end);
        out[key] = isPlainIntegerIn(value) ? Number(value) : value;
    }
    return out;
}

const CAUSE_EVENT = /^([A-Za-z_]\w*):(\d{1,9}) value=(.*)$/s;
const CAUSE_RULE = /^(started|endof)\(([A-Za-z_]\w*)\)$/;
const CAUSE_DURATION = /^duration\(([A-Za-z_]\w*)\)=(\d{1,19})ns$/;
const CAUSE_ELAPSED = /^elapsed=(\d{1,19})ns$/;

export function parseCause(text: string): RuleCause {
    let m = CAUSE_EVENT.exec(text);
    if (m) return { kind: 'event', module: m[1]!, port: Number(m[2]), value: m[3]! };
    m = CAUSE_RULE.exec(text);
    if (m) return { kind: m[1] as 'started' | 'endof', rule: m[2]! };
    m = CAUSE_DURATION.exec(text);
    if (m) return { kind: 'duration', rule: m[1]!, ns: Number(m[2]) };
    m = CAUSE_ELAPSED.exec(text);
    if (m) return { kind: 'elapsed', ns: Number(m[1]) };
    if (text === 'stop') return { kind: 'stop' };
    return { kind: 'other', text };
}

const RULE_DETAIL = /^([A-Za-z_]\w*)\.([A-Za-z_]\w*) (active|inactive) cause=(.*)$/s;

/** A runtime log's name (runtime/src/csvlog.c: `<MODULE>_<d>-<Mon>-<Y>-<H>h<M>m<S>s.csv`). */
const LOG_NAME = /^(.+)_\d{1,2}-[A-Z][a-z]{2}-\d{4}-\d{2}h\d{2}m\d{2}s\.csv$/;
/**
 * The names LOG_NAME matches, as a shell glob (find -name), a little wider (a day of any digits):
 * the listing of a Docker work volume's logs/ gives these first (docker-folder-list.ts).
 */
export const LOG_NAME_GLOB = '*_[0-9]*-[A-Z][a-z][a-z]-[0-9][0-9][0-9][0-9]-[0-9][0-9]h[0-9][0-9]m[0-9][0-9]s.csv';
/** moduleOfLog's answers (a replay interleaves its logs line by line); bounded, emptied when full. */
const logModules = new Map<string, string | undefined>();

/**
 * The module whose log `file` is, when it is named as the runtime names a log (a folder before it
 * is left out); undefined for any other name (a test's, a trace file's own logs).
 */
export function moduleOfLog(file: string): string | undefined {
    if (logModules.has(file)) return logModules.get(file);
    if (logModules.size >= 4096) logModules.clear();
    const module = LOG_NAME.exec(file.slice(file.lastIndexOf('/') + 1))?.[1];
    logModules.set(file, module);
    return module;
}

/**
 * Which files of a log folder are its logs — one rule for `contract trace`, the Monitor and the IDE
 * server's folder listing: every `*.csv` file (a regular file: a link or a FIFO is named, never read).
 */
export function isLogFileName(name: string): boolean {
    return name.length > 4 && name.endsWith('.csv');
}

/**
 * The module a log's name names: the runtime's `<MODULE>_<date>.csv` exactly (a module named with
 * `_`, `ARM_CTL_<date>.csv`, is ARM_CTL), else the name before its first `_` when it is a name
 * (`CTL_1.csv`: a test's, a copy's), else none (`data.csv`, `copy-of-CTL_1.csv`). Said of logs as a folder holds them (two logs of one module);
 * a record's own module is always its `module` field.
 */
const NAMED_BEFORE_UNDERSCORE = /^([A-Za-z][A-Za-z0-9]*)_.*\.csv$/s;
export function moduleNamedByLog(file: string): string | undefined {
    const exact = moduleOfLog(file);
    if (exact !== undefined) return exact;
    return NAMED_BEFORE_UNDERSCORE.exec(file.slice(file.lastIndexOf('/') + 1))?.[1];
}

/** Why two logs of one module in a folder are said, in a replay and by `contract trace`: a run writes one log per module. */
export const TWIN_LOGS_WHY = 'a run writes one log per module (two runs\' logs together, or a file named as its log that is not one)';

/** The modules with more than one log among `names` (the module a name names: moduleNamedByLog), each with its logs' names in order. */
export function twinLogs(names: Iterable<string>): Map<string, string[]> {
    const byModule = new Map<string, string[]>();
    for (const name of names) {
        const m = moduleNamedByLog(name);
        if (m !== undefined) (byModule.get(m) ?? byModule.set(m, []).get(m)!).push(name);
    }
    for (const [m, files] of byModule) if (files.length < 2) byModule.delete(m);
    return byModule;
}

/**
 * Why a record of `module` read from `file` is not one: a runtime log holds its own module's
 * records only, so a line naming another (ORD's deadline miss, SUP's KILL, in HOG's log) was
 * written by that log's module's code, and is not taken for the other module's. Undefined when
 * the record is where it belongs, or the file is not named as a log.
 */
export function foreignRecordReason(file: string, module: string): string | undefined {
    const owner = moduleOfLog(file);
    return owner === undefined || owner === module ? undefined : foreignReason(owner, module);
}

function foreignReason(owner: string, module: string): string {
    return `a record of ${module.slice(0, 64)} in ${owner}'s log (a module's log holds its own records only: ${owner}'s code wrote this line?)`;
}

/** The names records repeat (peers), each kept once; bounded, emptied when full (a forged log of many names). */
const names = new Map<string, string>();

/**
 * One string for each name a record repeats (its module: its log's name's, its kind: the table's,
 * its peer, up to 64 characters: kept here, a copy of its own): a record held for the merge of a
 * long run keeps no string of its own for them.
 */
function sharedName(name: string): string {
    if (name === '' || name.length > 64) return name;
    const known = names.get(name);
    if (known !== undefined) return known;
    if (names.size >= 4096) names.clear();
    const own = ownString(name);
    names.set(own, own);
    return own;
}

/**
 * One CSV line (not the header) of log `file` -> a record, or an unknown record saying what is wrong.
 * `clock`: the log's time check (log-clock.ts), given by a reader that reads the log's lines in
 * file order: a record whose time it does not believe is an unknown record saying why.
 */
export function parseRecordLine(file: string, lineNo: number, line: string, clock?: LogClock): TraceRecord {
    const r = readRecordLine(file, lineNo, line);
    if (!clock || r.kind === 'unknown') return r;
    const k = r as KnownRecord;
    const why = clock.check(Number(k.monoNs), k.wallTime);
    return why ? unknown(file, lineNo, why, line) : r;
}

function readRecordLine(file: string, lineNo: number, line: string): TraceRecord {
    if (line.length > MAX_LINE_CHARS) return unknown(file, lineNo, `line longer than ${MAX_LINE_CHARS} characters`, line);
    if (line.includes('"')) {
        const f = splitCsvRecord(line);
        if (!f) return unknown(file, lineNo, 'a quoted field is not closed (the line was cut or forged)', line);
        if (f.length !== 8) return unknown(file, lineNo, `${f.length} fields, expected 8`, line);
        return recordOfFields(file, lineNo, line, f[0]!, f[1]!, f[2]!, f[3]!, f[4]!, f[5]!, f[6]!, f[7]!);
    }
    // the common line, with no quoted field: its seven commas found in place, its fields cut out
    // with no array of them (splitCsvRecord's fields of such a line: split at every comma)
    const c1 = line.indexOf(',');
    const c2 = line.indexOf(',', c1 + 1);
    const c3 = line.indexOf(',', c2 + 1);
    const c4 = line.indexOf(',', c3 + 1);
    const c5 = line.indexOf(',', c4 + 1);
    const c6 = line.indexOf(',', c5 + 1);
    const c7 = line.indexOf(',', c6 + 1);
    if (c1 < 0 || c2 < 0 || c3 < 0 || c4 < 0 || c5 < 0 || c6 < 0 || c7 < 0 || line.includes(',', c7 + 1)) return unknown(file, lineNo, `${line.split(',').length} fields, expected 8`, line);
    return recordOfFields(file, lineNo, line, line.slice(0, c1), line.slice(c1 + 1, c2), line.slice(c2 + 1, c3), line.slice(c3 + 1, c4), line.slice(c4 + 1, c5), line.slice(c5 + 1, c6), line.slice(c6 + 1, c7), line.slice(c7 + 1));
}

/** The record of a line of eight fields (their text, unquoted), or an unknown record saying what is wrong. */
function recordOfFields(file: string, lineNo: number, line: string, mono: string, wall: string, moduleText: string, event: string, peerText: string, port: string, size: string, detail: string): TraceRecord {
    // checked by character rather than by regular expression, and the record made as one literal
    // (one shape for all): this runs for every record of a live trace and of `contract trace`
    if (!isDigitsIn(mono, 1, 20)) return unknown(file, lineNo, 'mono_ns is not a number', line);
    const past = monoTextProblem(mono);
    if (past) return unknown(file, lineNo, past, line);
    if (!isModuleNameIn(moduleText)) return unknown(file, lineNo, 'bad module name', line);
    const owner = moduleOfLog(file);
    if (owner !== undefined && owner !== moduleText) return unknown(file, lineNo, foreignReason(owner, moduleText), line);
    const module = owner ?? sharedName(moduleText);
    const peer = sharedName(peerText);
    if ((port !== '' && !isDigitsIn(port, 1, 9)) || !isDigitsIn(size, 1, 15)) return unknown(file, lineNo, 'bad port or size', line);
    const kind = traceKind(event);
    const portN = port === '' ? null : Number(port);
    const sizeN = Number(size);
    // a module's own record (ContractLog with an event name of its own): a `user` record naming it;
    // so is one under the name of an engine's own kind that another module wrote (log-clock.ts posingAs)
    const posing = kind ? posingAs(kind.area, module) : undefined;
    if (!kind || kind === USER_KIND || posing) {
        if (!isUserEventName(event)) return unknown(file, lineNo, `unknown event '${event.slice(0, 64)}'`, line);
        const user: KnownRecord = { kind: 'user', monoNs: mono, wallTime: wall, module, peer, port: portN, size: sizeN, detail, fields: posing ? { event, posingAs: posing } : { event } };
        return user;
    }
    if (event === 'sup_rule') {
        const m = RULE_DETAIL.exec(detail);
        if (!m) return unknown(file, lineNo, 'sup_rule detail is not `F.R active|inactive cause=C`', line);
        // `stop` is the cause of the rules a stopping function turns off, never of a rule turned on
        if (m[3] === 'active' && m[4] === 'stop') return unknown(file, lineNo, 'a rule turned active with cause=stop (only a stopping function gives that cause, to the rules it turns inactive)', line);
        const rule: RuleRecord = { kind: 'sup_rule', monoNs: mono, wallTime: wall, module, peer, port: portN, size: sizeN, detail, function: m[1]!, rule: m[2]!, active: m[3] === 'active', cause: m[4]!, causeEvent: parseCause(m[4]!) };
        return rule;
    }
    const fields = event === 'scheduler' ? classifyLine(SCHEDULER_LINES, detail)
        : event === 'supervisor' ? classifyLine(SUPERVISOR_LINES, detail)
            : detailFields(detail, kind.detailKeys ?? [], kind.restKey);
    const known: KnownRecord = { kind: kind.kind, monoNs: mono, wallTime: wall, module, peer, port: portN, size: sizeN, detail, fields };
    return known;
}

/** The records of one log file, in file order (header and empty lines are not records). */
export function parseLogFile(file: LogFile): TraceRecord[] {
    return [...logFileRecords(file)];
}

function* logFileRecords(file: LogFile): Generator<TraceRecord> {
    // line by line (not one split of the whole text: a log of hundreds of MB would be one long step)
    const text = file.text;
    const clock = new LogClock();
    for (let pos = 0, i = 0; pos < text.length; i++) {
        let nl = text.indexOf('\n', pos);
        const unended = nl < 0;
        if (nl < 0) nl = text.length;
        if (i === 0 && !isLogHeaderIn(text, 0, nl)) {
            // no log: refused whole, said once (NOT_A_LOG_WHY)
            yield notALogRecord(file.name, text.slice(0, Math.min(nl, 200)));
            return;
        }
        const record = recordOfLine(file.name, i, text.slice(pos, nl), clock);
        pos = nl + 1;
        if (record) yield unended ? unendedLine(record) : record;
    }
}

/**
 * A file's last line, which has no line end: when it is no record, its reason says why that may
 * be (`4 fields, expected 8 (the file ends inside this line: ...)`): a module killed while writing.
 * When it reads as a record it is one, marked `cut` (its detail may have lost its end: a record
 * of 8 fields is no proof of a whole line).
 */
export function unendedLine(record: TraceRecord): TraceRecord {
    return record.kind === 'unknown' ? { ...record, reason: `${(record as UnknownRecord).reason}${UNENDED_LINE}` } as TraceRecord : { ...record, cut: true };
}

/** What a file's last line without a line end adds to why it is no record (unendedLine, trace files' problems). */
export const UNENDED_LINE = ' (the file ends inside this line: its writer was stopped, or is still writing it)';

/**
 * The record of line `index` (0-based) of log `file`, as read from the file (a `\r` before its
 * newline taken off); undefined for an empty line and the header on the first line. Shared by the
 * readers of a whole log (here) and of a streamed one (the CLI's `contract trace`).
 */
export function recordOfLine(file: string, index: number, raw: string, clock?: LogClock): TraceRecord | undefined {
    const end = recordLineEnd(raw, index, 0, raw.length);
    return end < 0 ? undefined : parseRecordLine(file, index + 1, end === raw.length ? raw : raw.slice(0, end), clock);
}

/**
 * Where the record of line `index` (0-based) of a log ends when the line is text[from, to) (its
 * newline left out): before a `\r` that ends it; -1 when it holds no record (an empty line, the
 * header on the first line). recordOfLine's rule, for a reader that reads lines in place (the
 * IDE's Monitor builds a recorded run from ranges of its logs' text).
 */
export function recordLineEnd(text: string, index: number, from: number, to: number): number {
    const end = to > from && text.charCodeAt(to - 1) === 13 /* \r */ ? to - 1 : to;
    if (end === from || (index === 0 && end - from === CSV_HEADER.length && text.startsWith(CSV_HEADER, from))) return -1;
    return end;
}

/**
 * Every record of every file, ordered by mono_ns (CLOCK_MONOTONIC, comparable across the
 * modules of one host); records of equal time keep their file order, files in name order. An
 * unknown record stays right after the record that preceded it in its file.
 */
export function parseTrace(files: LogFile[]): TraceRecord[] {
    // each file's records sorted on their own (a log is in time order but for hostile or
    // clock-stepped lines: a sort of a sorted array is one pass), then merged
    const sorted = [...files].sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
    const runs: Keyed[][] = [];
    for (const file of sorted) {
        const run: Keyed[] = [];
        let last = 0n;
        for (const record of logFileRecords(file)) {
            if (record.kind !== 'unknown') last = BigInt((record as KnownRecord).monoNs);
            run.push({ key: last, index: run.length, record });
        }
        run.sort((a, b) => (a.key < b.key ? -1 : a.key > b.key ? 1 : a.index - b.index));
        runs.push(run);
    }
    // merge: a heap of the files by their next record (time, then file order)
    const at = runs.map(() => 0);
    const heap = new MinHeap<number>((f, g) => {
        const a = runs[f]![at[f]!]!.key;
        const b = runs[g]![at[g]!]!.key;
        return a < b || (a === b && f < g);
    });
    runs.forEach((run, f) => run.length && heap.push(f));
    const out: TraceRecord[] = [];
    while (heap.size) {
        const f = heap.peek()!;
        out.push(runs[f]![at[f]!++]!.record);
        if (at[f]! >= runs[f]!.length) heap.pop();
        else heap.topChanged();
    }
    return out;
}

interface Keyed {
    key: bigint;
    index: number;
    record: TraceRecord;
}
