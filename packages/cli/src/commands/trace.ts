/**
 * `contract trace LOGDIR [--format text|json]`: tells a recorded run from its CSV logs (the
 * run-time trace, docs/runtime-api.md "Trace records"): supervisor decisions with their causes,
 * schema activations, deadline misses with their cycle; `--format json` prints every record as
 * one JSON line, in time order. The logs are streamed (trace-stream.ts): a run of any length is
 * told in bounded memory, and printing stops when the reader goes away.
 */
import { stat } from 'node:fs/promises';
import { resolve } from 'node:path';
import { LauncherLinesQueue, STORY_FOLLOWED, StoryTeller, TWIN_LOGS_WHY, isUnknown, moduleNamedByLog, ownString, twinLogs, type KnownRecord, type RecordCounts, type TraceRecord, type TraceRecordBase, type UnknownRecord, type LauncherFileLine, isLauncherLine, launcherLineJson } from '@contract-studio/build-service/trace';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { escapeControls, safeName } from '../terminal-text.js';
import { readCrashFiles } from '@contract-studio/build-service/crash-files';
import { jsonLine } from '../trace-files.js';
import { recordJson } from '../record-json.js';
import { closeLogs, jsonLinesOf, LINE_CHARS_HELD, openLogFolder, streamTrace, windowFor, type OpenLog } from '../trace-stream.js';
import { traceFileBatches } from '../trace-file-stream.js';
import { open } from 'node:fs/promises';
import { readLauncherLines } from '../launcher-lines.js';

/** Lines of a trace file that are no record, named one by one before they are only counted. */
const NAMED_PROBLEMS = 20;

export const traceCommand: Command = {
    name: 'trace',
    summary: 'tell a recorded run from its CSV logs or a trace file (rule changes with causes, schemas, deadline misses)',
    usage: [
        'usage: contract trace LOGDIR|FILE.jsonl [--format text|json] [--merge-logs]',
        '  LOGDIR: the folder of a run\'s CSV logs (`contract run --logs`, default PROJECT/logs)',
        '  FILE.jsonl: a trace file (`contract run --trace`, `contract trace --format json`, `contract simulate --trace`), told in its order',
        '  --format: text (default: the story, then a count of the records and, apart, of the unreadable lines) or json (one JSON object per record and line, time order; an unreadable line is an object of kind "unknown"; the launcher\'s end lines, from LOGDIR\'s contract-launch.log or FILE, objects of kind "launcher_line")',
        '  --merge-logs: read two or more logs of one module in LOGDIR (two runs\' logs together) as one, with exit 0; without it they are read as one all the same, said first (stderr, and the story\'s first lines), and the exit status is 1',
        '  a file named like a log that is not read (a symbolic link, a FIFO, socket or device) is left out with a warning',
        'exit status: 0 success, 1 no readable log in LOGDIR, or no record in its logs, or two logs of one module in it without --merge-logs (in FILE.jsonl; unreadable lines are no records), 2 bad usage (LOGDIR missing, not a folder nor a .jsonl file)',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const parsed = parseArgs(args, ['format'], ['merge-logs']);
        if (parsed.positionals.length !== 1) throw new UsageError('expected one LOGDIR or FILE.jsonl');
        const format = parsed.options.get('format') ?? 'text';
        if (format !== 'text' && format !== 'json') throw new UsageError(`unknown format '${String(format)}' (expected text or json)`);
        const dirArg = parsed.positionals[0]!;
        const dir = resolve(io.cwd, dirArg);
        const info = await stat(dir).catch(() => undefined);
        if (info?.isFile() && dirArg.endsWith('.jsonl')) return traceFile(dir, dirArg, format, io);
        if (!info && dirArg.endsWith('.jsonl')) throw new UsageError(`${safeName(dirArg)} does not exist: give a trace file (\`contract run --trace FILE.jsonl\` writes one) or the folder of a run's CSV logs`);
        if (!info?.isDirectory()) throw new UsageError(`${safeName(dirArg)} is not a folder${info ? '' : ' (it does not exist)'}: give the folder of a run's CSV logs (\`contract run\` writes them to PROJECT/logs) or a trace file (FILE.jsonl: \`contract run --trace\`)`);
        const skipped: string[] = [];
        const logs = await openLogFolder(dir, undefined, skipped, dirArg);
        for (const s of skipped) io.err(`contract trace: warning: ${s}\n`);
        if (typeof logs === 'string') {
            io.err(`contract trace: ${logs}\n`);
            return EXIT_FAILURE;
        }
        // two logs of one module (two runs' logs together): said before anything else, in every
        // format, and the exit status 1 unless --merge-logs asked for it (the story's figures add both)
        // (a file that is no log, its first line not the runtime's header, is none of its module's logs: its reader refuses it)
        const twins = twinLogLines(logs.filter((l) => !l.notALog));
        for (const t of twins) io.err(`contract trace: warning: ${t}\n`);
        try {
            // the launcher's own lines (its end line of a module killed from outside): told in the
            // story, and written among the JSON lines (kind launcher_line) as a `--trace` file holds them
            const launcherProblems: string[] = [];
            const launcher = new LauncherLinesQueue(await readLauncherLines(dir, launcherProblems));
            const { late, problems, counts } = format === 'json' ? await printJson(logs, io, launcher) : await printStory(logs, io, launcher, twins);
            problems.push(...launcherProblems);
            if (format === 'text') await printCrashSites(dir, io, problems);
            for (const p of problems) io.err(`contract trace: warning: ${p}\n`);
            if (late) io.err(`contract trace: warning: ${late} record(s) were more than ${windowFor(logs.length)} lines (fewer when lines are longer than ${LINE_CHARS_HELD} characters) from their time's place in their log: told later than their time\n`);
            if (counts?.records === 0) {
                const only = counts.unreadable ? `only ${counts.unreadable} unreadable line(s)` : 'empty, or only their header';
                io.err(`contract trace: no record in the ${logs.length} log(s) of ${safeName(dirArg)} (${only})\n`);
                return EXIT_FAILURE;
            }
            if (twins.length && parsed.options.get('merge-logs') !== true) {
                io.err(`contract trace: ${safeName(dirArg)} holds two or more logs of ${twins.length} module(s), said above (two runs' logs together, read as one): exit 1; give the folder of one run (\`contract run\` moves the previous run's logs to OUT/previous/), or --merge-logs to read them as one with exit 0\n`);
                return EXIT_FAILURE;
            }
            return EXIT_OK;
        } finally {
            await closeLogs(logs);
        }
    },
};

/**
 * `contract trace FILE.jsonl`: the records of a trace file, in its order, told (or printed as JSON
 * lines) as a log folder's; the lines that are no record are named (the first NAMED_PROBLEMS), then counted.
 */
async function traceFile(path: string, arg: string, format: string, io: CliIO): Promise<number> {
    const handle = await open(path, 'r').catch((e: Error) => e);
    if (handle instanceof Error) {
        io.err(`contract trace: cannot read ${safeName(arg)}: ${handle.message}\n`);
        return EXIT_FAILURE;
    }
    let story = new Story(new ModuleEnds([], arg)); // the file's own bad lines are named on stderr below
    let simulations = 0;
    let records = 0;
    let problems = 0;
    try {
        for await (const batch of traceFileBatches(handle, arg)) {
            let piece = '';
            for (const r of batch) {
                if (isLauncherLine(r)) {
                    // the launcher's end line the file holds (no record): told as a logs folder's, at its place
                    piece += format === 'json' ? recordJson(launcherLineJson(r)) + '\n' : story.launcherLine(r);
                    continue;
                }
                // a line of the file that is no record is named (an unreadable line of the logs the file
                // was written from, carried as such, is only counted in the summary, as the logs' reader counts it)
                if (isUnknown(r) && r.file === arg) {
                    if (problems++ < NAMED_PROBLEMS) io.err(`contract trace: warning: ${safeName(arg)}:${r.line}: ${r.reason}\n`);
                } else if (!isUnknown(r) && r.kind !== 'sim_start') records++;
                if (format === 'json') piece += jsonLine(r) + '\n';
                else if (r.kind === 'sim_start') {
                    // a simulation's story starts (at time 0 again): the one before it ends with its own counts
                    if (simulations++ > 0) {
                        piece += story.end();
                        story = new Story(new ModuleEnds([], arg));
                    }
                    piece += `--- ${safeName((r as TraceRecordBase).detail)}\n`;
                    story.simulation(); // its modules ran no code: no flow finding blames it
                } else piece += story.line(r);
            }
            if (!(await print(io, piece))) return EXIT_OK;
        }
    } finally {
        await handle.close();
    }
    if (problems > NAMED_PROBLEMS) io.err(`contract trace: warning: ${problems - NAMED_PROBLEMS} more line(s) of ${safeName(arg)} that are no record\n`);
    if (format === 'text') io.out(story.end());
    if (records === 0) {
        io.err(`contract trace: no record in ${safeName(arg)}\n`);
        return EXIT_FAILURE;
    }
    return EXIT_OK;
}

/** What a print of the logs tells the command: the records and unreadable lines counted (the story's: none when its reader went away first). */
interface Printed {
    late: number;
    problems: string[];
    counts?: RecordCounts;
}

/**
 * Every record as a JSON line (an unreadable line as its `unknown` object), each piece printed once
 * the reader took the last; stops when the reader went away (`| head`: its choice).
 */
async function printJson(logs: readonly OpenLog[], io: CliIO, launcher: LauncherLinesQueue): Promise<Printed> {
    const { outOfOrder, problems, counts } = await jsonLinesOf(logs, (piece) => print(io, piece.toString('utf8')), undefined, launcher);
    return { late: outOfOrder, problems, counts };
}

/**
 * The story: its lines printed as they come (few: a reader gone is seen at the next), then what
 * the logs say of modules that did not end (a crash leaves no exit record), then the counts.
 */
async function printStory(logs: readonly OpenLog[], io: CliIO, launcher?: LauncherLinesQueue, twins: readonly string[] = []): Promise<Printed> {
    const stream = streamTrace(logs);
    const story = new Story(new ModuleEnds(logs), launcher);
    if (!(await print(io, twins.map((t) => `warning: ${t}\n`).join('')))) return { late: 0, problems: [] };
    for await (const batch of stream.batches) {
        if (!(await print(io, batch.map((r) => story.line(r)).join('')))) return { late: stream.outOfOrder(), problems: stream.problems() };
    }
    io.out(story.end());
    return { late: stream.outOfOrder(), problems: stream.problems(), counts: story.counts };
}

/**
 * Where the run's crashed modules crashed, from the logs folder's crash files (MODULE.crash, saved
 * by contract-launch: docs/runtime-api.md "Crash file"), after the story; nothing when none.
 */
async function printCrashSites(dir: string, io: CliIO, problems: string[]): Promise<void> {
    const sites = await readCrashFiles(dir, problems);
    if (!sites.length) return;
    io.out(`\ncrash sites (the logs' crash files):\n${sites.flatMap((s) => s.lines).map((l) => `${escapeControls(l)}\n`).join('')}`);
}

/** Prints `piece` (when any) once the reader took the last; false when the reader went away (`| head`: its choice). */
async function print(io: CliIO, piece: string): Promise<boolean> {
    if (piece) {
        io.out(piece);
        await io.drained?.();
    }
    return !io.outputClosed?.aborted;
}

/**
 * One line per module with two or more logs in the folder (a run writes one per module: two runs'
 * logs together, or a file named as its log that is not one), the first MODULES_FOLLOWED: read as
 * one, so the story and the schema figures add them up. Said before the story.
 */
export function twinLogLines(logs: readonly { name: string }[]): string[] {
    return [...twinLogs(logs.map((l) => l.name))].slice(0, MODULES_FOLLOWED).map(([m, files]) =>
        `${safeName(m)}: ${files.length} logs of it in this folder (${files.slice(0, 3).map(safeName).join(', ')}${files.length > 3 ? ', ...' : ''}), read as one: ${TWIN_LOGS_WHY}; the story and its figures add them up`);
}

/** A story told record by record: its lines, then what the logs say of modules that did not end (ModuleEnds), then the flows that delivered nothing or waited for room, then each periodic schema's figures and the counts. */
class Story {
    private readonly teller = new StoryTeller();

    /** `launcher`: the logs folder's launcher end lines (contract-launch.log), told in time order among the records. */
    constructor(private readonly ends: ModuleEnds, private readonly launcher?: LauncherLinesQueue) {}

    /** The records told (readable ones) and, apart, the unreadable lines: what the line of counts says. */
    get counts(): RecordCounts {
        return this.teller.recordCounts;
    }

    /** The records are a simulation's (its `sim_start`): StoryTeller.simulation. */
    simulation(): void {
        this.teller.simulation();
    }

    /** The record's line of the story ('' when it tells nothing), after those of the launcher's lines said before its time. */
    line(r: TraceRecord): string {
        const before = this.launcher && !isUnknown(r) ? this.launcherLines(this.launcher.before((r as TraceRecordBase).monoNs)) : '';
        this.ends.see(r);
        const told = this.teller.tell(r);
        return before + (told === undefined ? '' : safeName(told) + '\n');
    }

    /** A trace file's launcher end line, read at its place among the records (the file's time order): the story's line for it, or ''. */
    launcherLine(l: LauncherFileLine): string {
        return this.launcherLines([l]);
    }

    /** The story's lines for the launcher's end lines `lines` (a module it says ended on its own, when the line is taken). */
    private launcherLines(lines: readonly LauncherFileLine[]): string {
        let out = '';
        for (const l of lines) {
            const told = this.teller.tellLauncherLine(l);
            if (!told) continue;
            this.ends.launcherSaid(told.module, l.line);
            out += safeName(told.text) + '\n';
        }
        return out;
    }

    /** Each line one line: a newline or a bidi override carried by a record (a trace file's detail, an unreadable line's reason) is escaped, never a line of its own. */
    end(): string {
        const launcher = this.launcher ? this.launcherLines(this.launcher.rest()) : '';
        return launcher + [...this.ends.lines(), ...this.teller.endLines(), ...this.teller.flowLines(), ...this.teller.handlingLines(), ...this.teller.schemaLines(), ...this.teller.moduleCpuLines(), this.teller.summary()].map((l) => safeName(l) + '\n').join('') + this.ends.unreadable().map((l) => safeName(l) + '\n').join('');
    }
}

/** The runtime's last `log-capped` record, written as the module ends (exit, crash, stop signal; runtime/src/csvlog.c write_cap_final). */
const CAP_FINAL = /^(\d+) records not written after the log (reached its \d+-byte bound|could not be written past|stopped at \d+ bytes \(its disk below)/;

/** Unreadable lines named one by one at the end of the story (the rest counted). */
const UNREADABLE_NAMED = 5;
/**
 * Records whose peer the runtime (or ORD) writes as another module of the run: ORD's release, a
 * value or event posted to or received from it. A module named so with no log of its own in the
 * folder is said (its log was not collected, or was removed), not left out of the story.
 */
const NAMING_KINDS = new Set(['ord_release', 'data_posted', 'data_received', 'event_posted', 'event_received']);
/** A module's name (the peers a control tool or the launcher write, `control<M>-PID`, `contract-launch`, are none). */
const MODULE_NAME = /^[A-Za-z_]\w{0,63}$/;
/** Modules without a log of their own named one by one at most (a forged log could name many). */
const UNLOGGED_NAMED = 16;

/** Modules followed at most, as the story follows them (a run writes a log per module, 1,024 at most): the records of others (a forged log) are only counted. */
const MODULES_FOLLOWED = STORY_FOLLOWED;

/**
 * Which modules' logs end without their `module_exit` or `module_crashed` record. The runtime logs
 * `module_exit` as the module returns and `module_crashed` when its code crashes
 * (docs/runtime-api.md "Trace records"); a module that was killed (or an older runtime's that
 * crashed) writes neither, and may have lost the records still buffered, down to an empty log. And
 * whose log does not hold as many records as that last record counts (`records=K`): a record
 * removed, cut or repeated after the run, or lost at the crash.
 */
export class ModuleEnds {
    private t0: bigint | undefined;
    private readonly last = new Map<string, bigint>();
    private readonly started = new Set<string>();
    private readonly exited = new Set<string>();
    /** Modules whose last record is `module_crashed` (its count is a crash record's). */
    private readonly crashed = new Set<string>();
    /** Records read per module (an unreadable line counts for the module its log is named for). */
    private readonly read = new Map<string, number>();
    /** What each module's exit record counts. */
    private readonly counted = new Map<string, number>();
    /** Modules whose log reached its bound (records left out on purpose: log-capped). */
    private readonly capped = new Set<string>();
    /** Modules whose log the build service cut at its bound (its log-capped record, peer build-service): what follows is not in the file. */
    private readonly cutByService = new Set<string>();
    /**
     * Modules whose log ends with the runtime's last log-capped record (CAP_FINAL), with the records
     * it says were not written: the module ended after its log reached its bound, its exit record
     * (or its crash record) among those not written.
     */
    private readonly endsCapped = new Map<string, { dropped: string; why: string }>();
    private readonly unknowns: string[] = [];
    private unknownCount = 0;
    /** The logs' modules, then those of records (a trace file has no log names), each as kept: a copy, never the line it was read from. */
    private readonly modules = new Map<string, string>();
    /** Records of modules past MODULES_FOLLOWED. */
    private notFollowed = 0;
    /** Modules other modules' records name (NAMING_KINDS), at most MODULES_FOLLOWED: the first such record's time and module, and its kind. */
    private readonly named = new Map<string, { at: bigint; by: string; kind: string }>();

    /** Modules the launcher's own end line (the logs folder's contract-launch.log) told ended, with that line. */
    private readonly launcherEnds = new Map<string, string>();

    /** `namedElsewhere`: a trace file whose own bad lines its reader names (not named again here). */
    constructor(logs: readonly { name: string }[], private readonly namedElsewhere?: string) {
        for (const l of logs) {
            const named = moduleNamedByLog(l.name);
            if (named !== undefined) this.follow(named);
        }
    }

    /** The module's name as kept, or undefined past MODULES_FOLLOWED modules (its record is only counted). */
    private follow(m: string): string | undefined {
        const kept = this.modules.get(m);
        if (kept !== undefined) return kept;
        if (this.modules.size >= MODULES_FOLLOWED) {
            this.notFollowed++;
            return undefined;
        }
        const own = ownString(m);
        this.modules.set(own, own);
        return own;
    }

    see(r: TraceRecord): void {
        if (r.kind === 'unknown') {
            const u = r as UnknownRecord;
            if (u.file === this.namedElsewhere) return;
            const named = moduleNamedByLog(u.file);
            const m = named === undefined ? undefined : this.follow(named);
            if (m !== undefined) this.read.set(m, (this.read.get(m) ?? 0) + 1);
            if (this.unknownCount++ < UNREADABLE_NAMED) this.unknowns.push(`unreadable: ${safeName(u.file)} line ${u.line}: ${u.reason}`);
            return;
        }
        const base = r as TraceRecordBase;
        const at = BigInt(base.monoNs);
        this.t0 ??= at;
        const m = this.follow(base.module);
        if (m === undefined) return;
        this.last.set(m, at);
        this.read.set(m, (this.read.get(m) ?? 0) + 1);
        if (NAMING_KINDS.has(r.kind) && base.peer !== m && !this.named.has(base.peer) && this.named.size < MODULES_FOLLOWED && MODULE_NAME.test(base.peer))
            this.named.set(ownString(base.peer), { at, by: m, kind: r.kind });
        const final = r.kind === 'log-capped' && base.peer !== 'build-service' ? CAP_FINAL.exec(base.detail) : null;
        if (final) this.endsCapped.set(m, { dropped: ownString(final[1]!), why: final[2]!.startsWith('reached') ? 'its log reached its bound' : final[2]!.startsWith('stopped') ? 'its log stopped at the logs\' disk reserve (the work dir nearly full)' : 'its log could not be written further (a full disk)' });
        else this.endsCapped.delete(m); // a record after it: its log does not end capped
        if (r.kind === 'module_started') this.started.add(m);
        if (r.kind === 'log-capped') {
            this.capped.add(m);
            if (base.peer === 'build-service') this.cutByService.add(m);
        }
        if (r.kind === 'module_exit' || r.kind === 'module_crashed') {
            this.exited.add(m);
            if (r.kind === 'module_crashed') this.crashed.add(m);
            else this.crashed.delete(m);
            const k = (r as KnownRecord).fields['records'];
            if (typeof k === 'number') this.counted.set(m, k);
        }
    }

    /** The launcher's end line `line` (its pid the module's) told how `module` ended: its last record's line says it. */
    launcherSaid(module: string, line: string): void {
        const m = this.modules.get(module);
        if (m !== undefined) this.launcherEnds.set(m, ownString(line));
    }

    /** The unreadable lines, the first few by file and line (the summary counts them all). */
    unreadable(): string[] {
        const more = this.unknownCount - this.unknowns.length;
        return more > 0 ? [...this.unknowns, `unreadable: ${more} more line(s) (\`--format json\` lists each)`] : this.unknowns;
    }

    /**
     * One line per module whose log has its start but no exit record, records but not its start,
     * or no record at all; said only of a run's logs (some module logged its start: the runtime's
     * logs, not hand-made ones).
     */
    lines(): string[] {
        // a forged log's modules past MODULES_FOLLOWED: their records are counted, not followed
        const past = this.notFollowed ? [`${''.padStart(10)} ${this.notFollowed} record(s) of modules past the first ${MODULES_FOLLOWED} not followed (more modules than a run has)`] : [];
        if (this.t0 === undefined || this.started.size === 0) return past;
        const t0 = this.t0;
        const at = (ns: bigint): string => `+${(Number(ns - t0) / 1e9).toFixed(6)}s`;
        // modules started and never exited, in the order of their last record (the story's order)
        const open = [...this.modules.keys()].filter((m) => this.started.has(m) && !this.exited.has(m) && this.last.has(m))
            .sort((a, b) => (this.last.get(a)! < this.last.get(b)! ? -1 : this.last.get(a)! > this.last.get(b)! ? 1 : 0));
        const out: string[] = [];
        // a log that ends capped lost its exit record to the cap: not a module that did not end
        const uncapped = open.filter((m) => !this.endsCapped.has(m));
        if (uncapped.length > 1 && uncapped.length === this.started.size) {
            // not one module's crash: the whole run ended without its modules' exit records
            out.push(`${at(this.last.get(open.at(-1)!)!)} the records end here: no module wrote its exit record (${open.length} modules): the run was killed before its end, or is still running`);
        } else {
            for (const m of open) {
                const capped = this.endsCapped.get(m);
                out.push(this.cutByService.has(m)
                    ? `${at(this.last.get(m)!)} ${m.padEnd(4)} its log was cut here by the build service (its bound on a collected log): later records, its exit record among them, are not in it`
                    : capped !== undefined
                        ? `${at(this.last.get(m)!)} ${m.padEnd(4)} its log ends capped: the module ended after ${capped.why}, so its exit record is not in it (one of the ${capped.dropped} records not written), not lost to a crash; the launcher's output says how it ended`
                        : this.launcherEnds.has(m)
                            ? `${at(this.last.get(m)!)} ${m.padEnd(4)} its last record: no exit record follows (the launcher's line: contract-launch: ${this.launcherEnds.get(m)!})`
                            : `${at(this.last.get(m)!)} ${m.padEnd(4)} its last record: no exit record follows (it crashed, was killed, or its code called exit(); the launcher's output says which)${this.capped.has(m) ? ` (its log had reached its bound; the last log-capped record, which the runtime writes at any end but a SIGKILL, is missing too)` : ''}`);
            }
        }
        // a log with records but not its start: cut or rewritten after its module began (its own
        // code may have truncated it); with no exit either, how the module ended is not in it
        const headless = [...this.modules.keys()].filter((m) => this.last.has(m) && !this.started.has(m));
        for (const m of headless) {
            out.push(this.exited.has(m)
                ? `${''.padStart(10)} ${m.padEnd(4)} its log lacks its start record: it was cut or rewritten after the module began (its code may have truncated it)`
                : `${at(this.last.get(m)!)} ${m.padEnd(4)} its last record; its log holds neither its start nor its exit record: it was cut or rewritten after the module began (its code may have truncated it), and how it ended is not in it (the launcher's output says it)`);
        }
        for (const m of this.modules.keys()) {
            if (!this.last.has(m)) {
                const unreadable = this.read.get(m) ?? 0;
                out.push(unreadable
                    ? `${''.padStart(10)} ${m.padEnd(4)} no record in its log, only ${unreadable} unreadable line(s): not a runtime log (one begins with the CSV header, then the module's start record)`
                    : `${''.padStart(10)} ${m.padEnd(4)} no record in its log: it crashed, hung or was killed before writing any (the launcher's output says which)`);
            }
            const counted = this.counted.get(m), read = this.read.get(m) ?? 0;
            if (counted !== undefined && counted !== read && !this.capped.has(m)) {
                const crashed = this.crashed.has(m);
                const gap = counted > read ? `${counted - read} missing (${crashed ? 'lost at the crash, or removed or cut after the run?' : 'removed or cut after the run?'})` : `${read - counted} more than it wrote (repeated or added after the run?)`;
                out.push(`${''.padStart(10)} ${m.padEnd(4)} not whole: its log holds ${read} record(s), its ${crashed ? 'crash' : 'exit'} record counts ${counted}: ${gap}`);
            }
        }
        return [...out, ...this.unlogged(at), ...past];
    }

    /**
     * Modules other modules' records name with no record of their own (no log of theirs in the
     * folder, or an empty one is already told above): a log not collected (`contract run` refuses a
     * link planted under its name) or removed; else the story would not name them at all.
     */
    private unlogged(at: (ns: bigint) => string): string[] {
        const missing = [...this.named].filter(([m]) => !this.modules.has(m));
        const told = missing.slice(0, UNLOGGED_NAMED).map(([m, first]) =>
            `${at(first.at)} ${m.padEnd(4)} no log of it here, though other modules' records name it (the first: ${first.by}'s ${first.kind}): its log was not collected (\`contract run\` says why) or was removed`);
        if (missing.length > UNLOGGED_NAMED) told.push(`${''.padStart(10)} ${missing.length - UNLOGGED_NAMED} more module(s) named by other modules' records with no log here`);
        return told;
    }
}
