/**
 * A trace file: the records as JSON lines, one object a line (`contract run --trace`, `contract
 * trace --format json`, `contract simulate --trace`), read back as a recorded run. Browser-safe.
 *
 * A trace file is read by the same reader as the CSV logs: each JSON object is written back as the
 * CSV line the runtime writes (mono_ns, wall_time, module, event, peer, port, size, detail) and that
 * line is read by parseRecordLine, so a trace file gets exactly the checks a log gets (the file is
 * hostile: a CI artefact, a download). What a JSON line holds beyond those eight columns (`fields`,
 * a rule's `causeEvent`) is derived again from them, never trusted. Records the reader kept as
 * `unknown` when the file was written (a line of the logs it could not read) are carried as such
 * by recordOfJsonLine (`contract trace FILE.jsonl` counts them as the logs' reader did) and skipped,
 * counted, as logs. The `sim_start` record that heads a simulation is no record of a run: skipped as
 * logs (each simulation of a file starts at time 0 again: the first is kept, the others left out,
 * said) and, read one by one, handed as itself (`contract trace` heads each simulation's story with it).
 * A `launcher_line` (the launcher's end line of a module, which the CLI writes among the records:
 * launcher-line-record.ts) is no record either: read one by one, it is handed as the line it holds;
 * as logs, the file's launcher lines are kept apart (`launcherLines`), as a logs folder's
 * `contract-launch.log` gives them.
 */
import { csvField } from './csv-line.js';
import { CSV_HEADER, UNENDED_LINE, parseRecordLine, type LogFile } from './parse.js';
import type { KnownRecord, TraceRecord, UnknownRecord } from './records.js';
import { LogClocks, type LogClock } from './log-clock.js';
import { LAUNCHER_LINE_KIND, isLauncherLine, launcherLineOfJson, type LauncherLineItem } from './launcher-line-record.js';
import { MAX_LAUNCHER_LINES } from './launcher-lines-file.js';

/** Longer lines are not records (a record's CSV line is at most MAX_LINE_CHARS; its JSON adds the derived fields). */
export const MAX_JSON_LINE_CHARS = 16_384;
/** Modules of one trace file: one log each; records of more modules are left out, said. */
export const MAX_TRACE_FILE_MODULES = 256;
const MODULE = /^[A-Za-z_][A-Za-z0-9_]{0,63}$/;
/** Lines of a module joined at a time while a trace file is read (traceFileToLogsSteps). */
const JOINED_LINES = 2000;

/** What a JSON line is, read: a record's CSV line, an unreadable line of the logs it was written from (`carried`), a line to skip, or why it is none. */
export type JsonLineRead =
    /** `cut`: the record was its log's last line, with no line end (TraceRecordBase.cut) */
    | { csv: string; module: string; cut?: true }
    | { carried: UnknownRecord }
    | { simStart: KnownRecord }
    /** the launcher's end line of a module (kind `launcher_line`), not a record */
    | { launcher: LauncherLineItem }
    | { problem: string };

/** A text field of a carried unknown record, bounded (it is printed). */
const shortText = (v: unknown) => (typeof v === 'string' ? v.slice(0, 200) : '');

/** One line of a trace file -> the CSV line of its record, a line to skip, or why it is no record. */
export function jsonLineToCsv(line: string): JsonLineRead {
    if (line.length > MAX_JSON_LINE_CHARS) return { problem: `longer than ${MAX_JSON_LINE_CHARS} characters` };
    let value: unknown;
    try {
        value = JSON.parse(line);
    } catch {
        return { problem: 'not JSON' };
    }
    if (typeof value !== 'object' || value === null || Array.isArray(value)) return { problem: 'not a JSON object' };
    const r = value as Record<string, unknown>;
    if (r['kind'] === 'unknown') {
        const line = r['line'];
        return { carried: { kind: 'unknown', file: shortText(r['file']), line: Number.isSafeInteger(line) && (line as number) > 0 ? (line as number) : 0, reason: shortText(r['reason']), text: shortText(r['text']) } };
    }
    if (r['kind'] === 'sim_start') {
        const mono = typeof r['monoNs'] === 'string' && /^\d{1,20}$/.test(r['monoNs']) ? r['monoNs'] : '0';
        return { simStart: { kind: 'sim_start', monoNs: mono, wallTime: '', module: 'SIM', peer: '', port: null, size: 0, detail: shortText(r['detail']), fields: {} } };
    }
    if (r['kind'] === LAUNCHER_LINE_KIND) {
        const l = launcherLineOfJson(r);
        return 'problem' in l ? l : { launcher: l };
    }
    const { kind, monoNs, wallTime, module, peer, port, size, detail } = r;
    if (typeof kind !== 'string' || typeof monoNs !== 'string' || typeof module !== 'string' || typeof detail !== 'string') {
        return { problem: 'kind, monoNs, module and detail must be strings' };
    }
    if (!MODULE.test(module)) return { problem: 'bad module name' };
    const wall = typeof wallTime === 'string' ? wallTime : '';
    const from = typeof peer === 'string' ? peer : '';
    const portText = port === null || port === undefined ? '' : typeof port === 'number' ? String(port) : '?';
    const sizeText = typeof size === 'number' ? String(size) : size === undefined ? '0' : '?';
    // a module's own record: its CSV event is the name it logged (fields.event), `user` only when none
    const fields = r['fields'];
    const userEvent = kind === 'user' && typeof fields === 'object' && fields !== null ? (fields as Record<string, unknown>)['event'] : undefined;
    const event = typeof userEvent === 'string' && userEvent ? userEvent : kind;
    const csv = `${csvField(monoNs)},${csvField(wall)},${module},${csvField(event)},${csvField(from)},${portText},${sizeText},${csvField(detail)}`;
    return r['cut'] === true ? { csv, module, cut: true } : { csv, module };
}

/**
 * One line of a trace file as a record (the CSV reader's; `unknown` saying why it is none, with
 * this file and line), or undefined for an empty line or a `launcher_line` (no record). An unreadable line of the logs the file was
 * written from comes back as the unknown record it was (its own file and line); a simulation's
 * `sim_start` as itself (its detail bounded: `simulation start: SCENARIO`).
 */
export function recordOfJsonLine(file: string, lineNo: number, line: string, clocks?: LogClocks): TraceRecord | undefined {
    const item = traceFileItemOfJsonLine(file, lineNo, line, clocks);
    return item && isLauncherLine(item) ? undefined : item;
}

/**
 * One line of a trace file as recordOfJsonLine reads it, but a `launcher_line` (no record: undefined
 * there) handed as the launcher's end line it holds (`contract trace FILE.jsonl` tells it at its place).
 */
export function traceFileItemOfJsonLine(file: string, lineNo: number, line: string, clocks?: LogClocks): TraceRecord | LauncherLineItem | undefined {
    if (line.trim() === '') return undefined;
    const read = jsonLineToCsv(line);
    if ('launcher' in read) return read.launcher;
    if ('simStart' in read) {
        clocks?.reset(); // the next simulation starts at time 0 again: no time of the last one's is 'before'
        return read.simStart;
    }
    if ('carried' in read) return read.carried;
    if ('problem' in read) return { kind: 'unknown', file, line: lineNo, reason: read.problem, text: line.slice(0, 200) };
    const record = parseRecordLine(file, lineNo, read.csv, clocks?.of(read.module));
    return read.cut && record.kind !== 'unknown' ? { ...record, cut: true } : record;
}

/** Why the CSV line of a trace file's record is no record (the logs' reader's reason), or undefined. */
function csvProblem(file: string, lineNo: number, csv: string, clock: LogClock): string | undefined {
    const r = parseRecordLine(file, lineNo, csv, clock);
    return r.kind === 'unknown' ? (r as UnknownRecord).reason : undefined;
}

export interface TraceFileLogs {
    /** One CSV log a module (`<MODULE>_<file>.csv`, the header first), its records in the file's order. */
    files: LogFile[];
    /** Lines that are no record (`line 12: not JSON`), the first `maxProblems` named. */
    problems: string[];
    /** Lines skipped: records the writer could not read (lines of the logs it was written from). */
    skipped: number;
    /** The file's own lines that are no record (not JSON, no record's fields...), all of them: `problems` names the first. */
    unreadable: number;
    /** A simulation's file (its `sim_start`): the scenario ('' when unnamed); of several simulations (several scenarios), the first's, the others left out (said in `problems`). */
    simulation?: string;
    /**
     * The file's order of the records: for each record line of the logs, in the order the file
     * gives them, the index in `files` of its log (each log's lines in its own order). `contract
     * trace FILE` tells the records in the file's order; a reader that merges the logs by time
     * would put records of one time in another order (a simulation writes every record of a step
     * at one time, its causes before their effects: docs/simulation.md "seq"). Its length is the
     * number of record lines of all the logs.
     */
    order: Uint16Array;
    /**
     * The file's launcher end lines (kind `launcher_line`), in the file's order, MAX_LAUNCHER_LINES
     * at most: as a logs folder's contract-launch.log gives them (GET /api/log-folder
     * `launcherLines`); none when the file has none.
     */
    launcherLines?: { monoNs: string; line: string }[];
}

/**
 * A trace file's text as the CSV logs a run writes (one a module), for the readers of a run's
 * logs (the IDE's recorded run, `contract trace`). `name`: the file's name (in the logs' names).
 */
export function traceFileToLogs(name: string, text: string, maxProblems = 20): TraceFileLogs {
    const steps = traceFileToLogsSteps(name, text, Infinity, maxProblems);
    let step = steps.next();
    while (!step.done) step = steps.next();
    return step.value;
}

/**
 * traceFileToLogs in steps: yields every `every` lines read, so that a page can draw between
 * slices (a trace file of a 60 s run of a 1 kHz schema is some 500,000 JSON lines to parse).
 */
export function* traceFileToLogsSteps(name: string, text: string, every = 500, maxProblems = 20): Generator<void, TraceFileLogs> {
    const base = name.replace(/^.*\//, '').replace(/\.jsonl$/i, '').replace(/[^A-Za-z0-9_.-]/g, '_') || 'trace';
    // each module's lines, joined a stretch at a time (one join of 500,000 lines would hold a page 140 ms)
    // lastCut: the module's last record was its log's last line, with no line end (`cut`): its text ends so again
    const lines = new Map<string, { parts: string[]; pending: string[]; lastCut: boolean; index: number }>();
    const problems: string[] = [];
    let bad = 0;
    let skipped = 0;
    let tooMany = 0;
    let simulation: string | undefined;
    const launcherLines: { monoNs: string; line: string }[] = [];
    // the log of each record line, in the file's order (a module's index: its place in `lines`, as in `files`)
    let order = new Uint16Array(1024);
    let records = 0;
    const clocks = new LogClocks();
    for (let pos = 0, n = 1; pos < text.length; n++) {
        if (n % every === 0) yield;
        let nl = text.indexOf('\n', pos);
        if (nl < 0) nl = text.length;
        const line = text.slice(pos, nl > pos && text.charCodeAt(nl - 1) === 13 ? nl - 1 : nl);
        pos = nl + 1;
        if (line.trim() === '') continue;
        const read = jsonLineToCsv(line);
        if ('simStart' in read) {
            // each simulation of the file starts again at time 0: the first one is shown, not a mix of them
            if (simulation !== undefined) {
                problems.push(`the file's other simulations, from line ${n}, left out: one is shown at a time`);
                break;
            }
            simulation = read.simStart.detail.replace(/^simulation start:? ?/, '');
            continue;
        }
        if ('launcher' in read) {
            if (launcherLines.length < MAX_LAUNCHER_LINES) launcherLines.push({ monoNs: String(read.launcher.monoNs), line: read.launcher.line });
            continue;
        }
        if ('carried' in read) {
            // named as `contract trace FILE.jsonl` names it (a warning each), within the same bound
            skipped++;
            const c = read.carried;
            if (bad + skipped <= maxProblems) problems.push(`line ${n}: a line of ${c.file || 'its logs'}${c.line ? ` (line ${c.line})` : ''} that is no record: ${c.reason}`);
            continue;
        }
        // a line whose record the CSV reader does not read (its checks, its log's time check) is
        // named here as `contract trace FILE.jsonl` names it, not left for the logs' reader to count
        const problem = 'problem' in read ? read.problem : csvProblem(name, n, read.csv, clocks.of(read.module));
        if (problem !== undefined || 'problem' in read) {
            if (bad++ + skipped < maxProblems) problems.push(`line ${n}: ${problem}${nl === text.length ? UNENDED_LINE : ''}`);
            continue;
        }
        let log = lines.get(read.module);
        if (!log) {
            if (lines.size >= MAX_TRACE_FILE_MODULES) {
                tooMany++;
                continue;
            }
            lines.set(read.module, (log = { parts: [], pending: [], lastCut: false, index: lines.size }));
        }
        log.pending.push(read.csv);
        log.lastCut = read.cut === true;
        if (records === order.length) {
            const more = new Uint16Array(order.length * 2);
            more.set(order);
            order = more;
        }
        order[records++] = log.index;
        if (log.pending.length >= JOINED_LINES) {
            log.parts.push(log.pending.join('\n'));
            log.pending = [];
        }
    }
    if (bad + skipped > maxProblems) problems.push(`${bad + skipped - maxProblems} more line(s) that are no record`);
    if (tooMany) problems.push(`${tooMany} record(s) of modules past the first ${MAX_TRACE_FILE_MODULES} left out`);
    const files: LogFile[] = [];
    for (const [module, l] of lines) {
        if (l.pending.length) l.parts.push(l.pending.join('\n'));
        files.push({ name: `${module}_${base}.csv`, text: `${CSV_HEADER}\n${l.parts.join('\n')}${l.lastCut ? '' : '\n'}` });
        yield;
    }
    return { files, problems, skipped, unreadable: bad, ...(simulation !== undefined ? { simulation } : {}), order: order.slice(0, records), ...(launcherLines.length ? { launcherLines } : {}) };
}
