/**
 * `contract run DIR [--duration 10s] [--start 'SUP.function(p={...})'] [--logs OUT] [--sandbox ...]`:
 * builds the project like `contract build`, runs the architecture for the duration (Seam 5: the
 * generated `make run` and the runtime's launcher), prints every module's output tagged with its
 * name, writes the CSV logs the build service collected from the sandbox (any sandbox, docker included) to OUT (default DIR/logs),
 * with `--trace FILE` their records as JSON lines as they arrive (docs/build-service-api.md "Trace channel";
 * docs/runtime-api.md "Trace records"), and exits non-zero when a module crashed
 * (1) or when the run did not go as designed (4: a limit hit, a module stuck, hung at the stop or ended early, the start request refused, output or logs cut; docs/ci.md).
 */
import { lstatSync } from 'node:fs';
import { stat } from 'node:fs/promises';
import { cpus as machineCpus } from 'node:os';
import { isAbsolute, join, relative, resolve, sep } from 'node:path';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import type { JobEvent } from '@contract-studio/build-service';
import { LAUNCHER_LINES_FILE, StoryTeller } from '@contract-studio/build-service/trace';
import { LiveTrace, settleTraceFile } from '../live-trace.js';
import { traceNameProblem } from '../trace-files.js';
import { CLI_BUILD_SECONDS, CLI_RUN_ROOM_SECONDS, COMMON_FLAGS, COMMON_REPEATABLE, COMMON_USAGE, COMMON_VALUED, EXIT_TABLE, LIMIT_USAGE, onTerminal, parseJobOptions, parseLimitOptions, reportBuild, runJob } from '../job-runner.js';
import { MIN_READY_TIMEOUT_SECONDS, addStdinEntry, cpuMissingFrom, emptyStdinEntries, isCpuList } from '@contract-studio/conventions';
import { safeName } from '../terminal-text.js';
import { PREVIOUS_DIR, refusedDefaultLogs, refusedLogsOut, refusedPrevious, saveLogs, type SavedLogs } from './run-logs.js';
import { gitignoreHint } from '../gitignore-hint.js';
import { failureText, moduleFailures, problemLines } from './run-problems.js';
import { runFigures, runFiguresOf } from './run-schemas.js';
import { loadRunModel, startProblem, stdinProblem } from './run-model-checks.js';

/** Saved logs of at least this many bytes: `--trace`'s final check of its file is said before it begins. */
const TRACE_CHECK_SAID_BYTES = 64 * 1048576;

/** The bytes of the saved logs `names` in `dir` (a file gone or unreadable counts 0). */
function logsBytes(dir: string, names: readonly string[]): number {
    let sum = 0;
    for (const n of names) {
        try {
            sum += lstatSync(join(dir, n)).size;
        } catch {
            /* counted as 0 */
        }
    }
    return sum;
}

/**
 * A folder as the text report names it: relative to the current directory when inside it
 * (`my-robot/logs`), so the path opens from where the command ran; else absolute (JSON keeps it absolute).
 */
export function fromCwd(cwd: string, path: string): string {
    const rel = relative(cwd, path);
    return rel === '' ? '.' : rel === '..' || rel.startsWith(`..${sep}`) || isAbsolute(rel) ? path : rel;
}

/** `10s`, `500ms`, `2m`, `1.5` (seconds: said, bareDurationWarning) -> seconds. */
export function parseDuration(text: string): number {
    const m = /^(\d+(?:\.\d+)?)(ms|s|m)?$/.exec(text.trim());
    if (!m) throw new UsageError(`bad duration '${text}' (expected e.g. 10s, 500ms, 2m)`);
    const value = Number(m[1]) * (m[2] === 'ms' ? 0.001 : m[2] === 'm' ? 60 : 1);
    if (!(value > 0)) throw new UsageError(`the duration must be positive (got '${text}')`);
    return value;
}

/**
 * The warning for a duration option given as a bare number (`--duration 500`): read as seconds,
 * but said on stderr, since a 500 meant as milliseconds runs 8 minutes (field test ft58c); null
 * when the value has its unit. The same rule for every duration option of `contract run`.
 */
export function bareDurationWarning(option: string, text: string): string | null {
    const value = text.trim();
    if (!/^\d+(?:\.\d+)?$/.test(value) || !(Number(value) > 0)) return null; // a bad value: refused by parseDuration
    return `--${option} ${value}: a number without a unit is seconds (${value} s); write ${value}ms for milliseconds, ${value}s to say seconds`;
}

/** The `--stdin MODULE=FILE` options as module -> file (the build service checks the file: inside the project, a regular file, its size). */
function stdinFiles(values: readonly string[]): Record<string, string> | undefined {
    if (!values.length) return undefined;
    const out = emptyStdinEntries();
    for (const v of values) {
        const refused = addStdinEntry(out, v);
        if (refused) throw new UsageError(`bad --stdin '${v}': ${refused}`);
    }
    return out;
}

/** `--ready-timeout` as seconds: a duration (parseDuration) of MIN_READY_TIMEOUT_SECONDS at least. */
export function checkReadyTimeout(text: string): number {
    let seconds: number;
    try {
        seconds = parseDuration(text);
    } catch (e) {
        // the option named, as --run-limit's refusal names its own
        if (e instanceof UsageError) throw new UsageError(`bad --ready-timeout '${text}': ${e.message}`);
        throw e;
    }
    if (seconds < MIN_READY_TIMEOUT_SECONDS) throw new UsageError(`bad --ready-timeout '${text}': at least ${MIN_READY_TIMEOUT_SECONDS * 1000}ms`);
    return seconds;
}

/**
 * The shortest `--run-limit`: the launcher needs about 1 s to stop the architecture (the build
 * service's grace, CANCEL_GRACE_MS), and the run half of the limit to start it; a shorter limit
 * stops the run while its modules still start, and blames one of them (field test ft57b: `--run-limit
 * 100ms`, `ENC did not end when the run stopped`).
 */
export const MIN_RUN_LIMIT_SECONDS = 2;

/**
 * `--run-limit` as seconds: a duration (parseDuration) of MIN_RUN_LIMIT_SECONDS at least, the run
 * step's wall time limit. A run still going then is stopped as at the end of a run and fails
 * `killed: run time limit N s` (exit 4).
 */
export function checkRunLimit(text: string): number {
    let seconds: number;
    try {
        seconds = parseDuration(text);
    } catch (e) {
        throw new UsageError(`bad --run-limit '${text}': ${(e as Error).message}`);
    }
    if (seconds < MIN_RUN_LIMIT_SECONDS) {
        throw new UsageError(`bad --run-limit '${text}': at least ${MIN_RUN_LIMIT_SECONDS}s (the architecture needs about 1 s to start and 1 s to stop: a shorter limit would stop it while its modules still start, and blame one of them)`);
    }
    return seconds;
}

/**
 * `--cpus` list: `1`, `0-1`, `0,2`. A CPU this machine does not have (`online`: its online CPUs,
 * which the sandbox on this machine runs on) is refused here, before anything is built;
 * contract-launch checks the rest (a CPU online but outside the run's affinity).
 */
export function checkCpus(text: string, online = machineCpus().length): string {
    if (!isCpuList(text)) throw new UsageError(`bad --cpus '${text}' (expected a CPU list such as 1, 0-1 or 0,2)`);
    const missing = online > 0 ? cpuMissingFrom(text, online) : undefined;
    if (missing !== undefined) throw new UsageError(`bad --cpus '${text}': CPU ${missing} is not available here (${online} CPUs online: 0-${online - 1})`);
    return text;
}

/** `SUP.function(...)` or empty (start nothing). */
export function checkStart(text: string): string {
    if (text === '') return text;
    if (!/^[A-Za-z_]\w*\.[A-Za-z_]\w*(\(.*\))?$/s.test(text) || /[\n\0]/.test(text)) {
        throw new UsageError(`bad --start '${text}' (expected SUPERVISOR.function(param={...}) e.g. GLB.mission(consigne={1.0,2.0,3.0}), or '' to start nothing)`);
    }
    // the build service's rule (the request ends up in a make recipe): said here, as bad usage
    if (!/^[\w .,:;=+\-(){}[\]"]*$/.test(text) || text.length > 4096) {
        throw new UsageError(`bad --start '${text}': a start request holds letters, digits, spaces and . , : ; = + - ( ) { } [ ] " only (no backslash, single quote, $ or other sign), at most 4096 characters`);
    }
    const glued = gluedNumber(text);
    if (glued) throw new UsageError(`bad --start '${text}': '${glued}' is not a number (a value starting with a digit is a number: 1.5, -2, 1e3); nothing was started`);
    return text;
}

/**
 * A value of a start request that starts as a number and goes on with letters (`1.5x`, `20ms`,
 * `3m`): no reader takes it (a name never starts with a digit), and the supervisor would refuse
 * it only once the run is built and started. Text between double quotes is not looked at.
 */
export function gluedNumber(text: string): string | undefined {
    const outside = text.replace(/"[^"]*"?/g, '""');
    for (const m of outside.matchAll(/(?<![\w.])[-+]?\.?\d[\w.+-]*/g)) {
        const word = m[0].replace(/[+-]+$/, '');
        if (!/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(word)) return word;
    }
    return undefined;
}

export const runCommand: Command = {
    name: 'run',
    summary: 'build a Cactal project, run its architecture for a while, collect the CSV logs',
    usage: [
        'usage: contract run DIR [--duration 10s] [--run-limit DURATION] [--start \'SUP.function(p={...})\'] [--logs OUT] [--trace FILE.jsonl] [--ready-timeout 10s] [--cpus LIST] [--realtime] [--werror] [--stdin MODULE=FILE]... [--limit NAME=VALUE]... [--sandbox auto|bwrap|docker|none] [--format text|json] [--runtime PATH] [--cache-dir DIR] [--verbose]',
        '  --duration: how long the architecture runs (default 10s; e.g. 500ms, 30s, 2m); then every module is stopped',
        '  DURATION (--duration, --run-limit, --ready-timeout): a number and its unit, ms, s or m; a number without a unit is seconds, with a warning on stderr',
        `  --run-limit: the run step's wall time limit (default: the duration + ${CLI_RUN_ROOM_SECONDS}s, and the --ready-timeout past 10s: the run lasts as long as asked);`,
        `             at least ${MIN_RUN_LIMIT_SECONDS}s (the architecture needs about 1s to start and 1s to stop; a shorter one is refused, exit 2);`,
        '             a run still going then is stopped and fails `killed: run time limit N s` (exit 4). A --duration longer than the limit less',
        `             5s (half of it under 10s) is shortened to fit, said on stderr. The build step's limit is ${CLI_BUILD_SECONDS}s; the other limits are the`,
        '             build service\'s defaults (memory 512 MiB, 256 processes, disk 256 MiB: docs/sandbox.md "Limits")',
        '  --start: the supervisor start request (default: the top supervisor\'s first function with its default parameters; \'\' starts nothing);',
        '           a supervisor, function or parameter the model does not have, or a value of the wrong type, is refused before the build (exit 2, with what it has)',
        '  --ready-timeout: how long every module\'s init may take before the start request is sent (default 10s); a module whose init has not returned by then stops the run (exit 4)',
        '  --cpus: pin every module to these CPUs (e.g. 1, 0-1; default: the system places them) — steadier periods',
        '  --stdin MODULE=FILE: module MODULE reads FILE, a file of the project (its path from DIR, at most 1 MiB), on its stdin; every other module\'s stdin is /dev/null;',
        '           a MODULE the model does not have is refused before the build (exit 2, with the closest name and its modules)',
        '  --realtime: modules take their SCHED_FIFO priorities in the sandbox, bounded so that a runaway loop cannot freeze the machine (docs/sandbox.md "Real-time mode"); refused, saying why, where the host cannot grant it',
        '  --logs: folder the CSV logs (one per module) are copied to (default DIR/logs, never a link found there; collected from every sandbox, docker included);',
        '          it holds one run: the previous run\'s logs there are moved to OUT/previous/run-<time>/ first (never deleted)',
        '  --trace: also write the records of those logs to FILE as JSON lines, in time order, as the run writes them (the live trace channel); at the end the same as `contract trace OUT --format json` (the launcher\'s end lines of modules that ended on their own among them, kind launcher_line; a normal run\'s file is only appended to, else it is written again at the end, said on stderr). FILE is named *.jsonl, a regular file or none (never a link or a FIFO); it is emptied at the run\'s first record: a build that fails leaves it as it was',
        ...LIMIT_USAGE,
        ...COMMON_USAGE,
        '  module output is printed as `[MODULE] line`, launcher lines as they come',
        EXIT_TABLE,
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const parsed = parseArgs(args, [...COMMON_VALUED, 'duration', 'run-limit', 'start', 'logs', 'cpus', 'trace', 'ready-timeout'], [...COMMON_FLAGS, 'realtime'], [...COMMON_REPEATABLE, 'stdin']);
        const limitOptions = parseLimitOptions(parsed);
        const opts = await parseJobOptions(parsed, io, onTerminal());
        // a bare number is seconds, said: `--duration 500` meant as milliseconds would run 8 minutes
        for (const name of ['duration', 'run-limit', 'ready-timeout']) {
            const value = parsed.options.get(name);
            const warning = typeof value === 'string' ? bareDurationWarning(name, value) : null;
            if (warning) io.err(`contract run: warning: ${warning}\n`);
        }
        const durationOption = parsed.options.get('duration');
        const duration = typeof durationOption === 'string' ? parseDuration(durationOption) : 10;
        const runLimitOption = parsed.options.get('run-limit');
        const runLimit = typeof runLimitOption === 'string' ? checkRunLimit(runLimitOption) : undefined;
        // --limit runSeconds=N is --run-limit said the service's way: one of the two, with the same least value
        const runSecondsText = limitOptions?.limitTexts.runSeconds;
        if (runSecondsText !== undefined) {
            if (runLimit !== undefined) throw new UsageError(`--run-limit and --limit runSeconds=${runSecondsText} both set the run's time limit: give one`);
            if (limitOptions!.limits.runSeconds! < MIN_RUN_LIMIT_SECONDS) throw new UsageError(`bad --limit runSeconds=${runSecondsText}: at least ${MIN_RUN_LIMIT_SECONDS} (the architecture needs about 1 s to start and 1 s to stop: a shorter limit would stop it while its modules still start, and blame one of them)`);
        }
        const readyOption = parsed.options.get('ready-timeout');
        const readyTimeout = typeof readyOption === 'string' ? checkReadyTimeout(readyOption) : undefined;
        const startOption = parsed.options.get('start');
        const start = typeof startOption === 'string' ? checkStart(startOption) : undefined;
        const cpusOption = parsed.options.get('cpus');
        const cpus = typeof cpusOption === 'string' ? checkCpus(cpusOption) : undefined;
        const realtime = parsed.options.get('realtime') === true;
        const werror = parsed.options.get('werror') === true;
        const stdin = stdinFiles(parsed.repeated.get('stdin') ?? []);
        const traceOption = parsed.options.get('trace');
        if (traceOption === '') throw new UsageError('--trace needs a file: --trace FILE.jsonl');
        const traceNameBad = typeof traceOption === 'string' ? traceNameProblem(traceOption) : undefined;
        if (traceNameBad) throw new UsageError(traceNameBad);
        const logsOption = parsed.options.get('logs');
        const logsDir = typeof logsOption === 'string' ? resolve(io.cwd, logsOption) : join(opts.dir, 'logs');
        const defaultLogs = typeof logsOption !== 'string';
        // said before the run, not after it
        const refused = (defaultLogs ? await refusedDefaultLogs(logsDir) : await refusedLogsOut(logsDir)) ?? (await refusedPrevious(logsDir));
        if (refused) {
            io.err(`contract run: ${refused}\n`);
            return EXIT_FAILURE;
        }
        // a misspelt function is refused before anything is built or started (the run would idle),
        // and so is a stdin file for no module (every module would read /dev/null)
        if (start || stdin) {
            const model = await loadRunModel(opts.dir);
            const problem = (start ? await startProblem(start, opts.dir, model) : null) ?? (stdin ? await stdinProblem(stdin, model) : null);
            // bad usage as any other: the message, then the synopsis
            if (problem) throw new UsageError(problem);
        }
        const traceFile = typeof traceOption === 'string' ? resolve(io.cwd, traceOption) : null;

        let live: LiveTrace | null = null;
        if (traceFile) {
            try {
                live = await LiveTrace.open(traceFile);
            } catch (e) {
                io.err(`contract run: cannot write the trace to ${safeName(traceFile)}: ${(e as Error).message}\n`);
                return EXIT_FAILURE;
            }
        }
        const onEvent = live ? (e: JobEvent) => live.event(e) : undefined;
        const outcome = await runJob(opts, { action: 'run', duration, ...(runLimit !== undefined ? { runLimit } : {}), ...(readyTimeout !== undefined ? { readyTimeout } : {}), ...(start !== undefined ? { start } : {}), ...(cpus !== undefined ? { cpus } : {}), ...(realtime ? { realtime } : {}), ...(werror ? { werror } : {}), ...(stdin ? { stdin } : {}), ...(limitOptions ? { limitOptions } : {}) }, io, undefined, onEvent);
        if ('error' in outcome) {
            const untouched = await live?.abandon();
            io.err(`contract run: ${outcome.error}\n`);
            if (traceFile && untouched) io.err(`contract run: ${safeName(traceFile)} was left as it was (no record: nothing ran)\n`);
            return outcome.exitCode;
        }
        const artifacts = outcome.job.artifacts;
        let savedLogs: SavedLogs;
        // what this run creates in the project that git should ignore: said once (gitignore-hint.ts)
        const logsBefore = defaultLogs && (await stat(logsDir).catch(() => undefined)) !== undefined;
        const previousBefore = defaultLogs && (await stat(join(logsDir, PREVIOUS_DIR)).catch(() => undefined)) !== undefined;
        try {
            savedLogs = await saveLogs(artifacts, logsDir, defaultLogs);
        } catch (e) {
            io.err(`contract run: cannot write the CSV logs to ${safeName(logsDir)}: ${(e as Error).message}\n`);
            await live?.abandon();
            return EXIT_FAILURE;
        }
        // the CSV logs (and crash files) saved; the launcher's lines file beside them is no log: not counted nor listed
        const logs = savedLogs.saved.filter((name) => name !== LAUNCHER_LINES_FILE);
        let trace: { file: string; records: number; unreadable: number } | null = null;
        // each periodic schema's figures, for a CI script's gate (--format json only): told by the
        // pass over the saved logs that checks the trace file, else by a read of its own
        const teller = opts.format === 'json' && traceFile && logs.length ? new StoryTeller() : null;
        if (traceFile && live && !logs.length && !live.counts.records && !live.counts.unreadable) {
            // nothing ran (a build that failed): an earlier trace in the file is left as it was
            if (await live.abandon()) io.err(`contract run: ${safeName(traceFile)} was left as it was (no record: nothing ran)\n`);
        } else if (traceFile && live) {
            try {
                // written live; rewritten from the collected logs when the live channel was not
                // the whole story in order (docker, its kept-lines bound, records sent late):
                // both compared by digest, the logs read as a stream (a long run is gigabytes)
                const { digest, intact } = await live.close();
                // a pass over every saved record: long for a long run (2 M records, ~10 s of CPU), said first
                const bytes = logsBytes(logsDir, logs);
                if (bytes >= TRACE_CHECK_SAID_BYTES) io.err(`trace: checking ${safeName(traceFile)} against the ${Math.round(bytes / 1048576)} MiB of CSV logs saved (one pass over every record)...\n`);
                const whole = await settleTraceFile(logsDir, logs, traceFile, { digest, counts: live.counts, intact }, teller ? (r) => teller.tell(r) : undefined);
                if (typeof whole === 'string') throw new Error(whole);
                const { replaced, rewritten, ...counted } = whole;
                // a follower of the file must know: by descriptor it reads the old file to its end, by name the new one from its start
                if (rewritten && !replaced) io.err(`trace: ${safeName(traceFile)} was written again from the saved logs at the run's end, a new file renamed over its path: the records the live channel gave differ from the logs' (a module's end the launcher said, placed at its own time; records that came late or not at all); a follower that reopens it by name reads it again from its start (packages/cli/README.md "Following a trace file")\n`);
                if (replaced) io.err(`trace: ${safeName(traceFile)} was written by another process, or moved or replaced, during the run: ${logs.length ? 'written again whole from this run\'s logs' : 'no log to write it again from: it is not this run\'s trace'}\n`);
                trace = { file: traceFile, ...counted };
            } catch (e) {
                io.err(`contract run: cannot write the trace to ${safeName(traceFile)}: ${(e as Error).message}\n`);
                return EXIT_FAILURE;
            } finally {
                live.release();
            }
        }
        const leftovers = artifacts?.runDirLeftovers ?? [];
        const leftOut = artifacts?.skipped ?? [];
        const failures = moduleFailures(outcome.runLines, outcome.result.limitHit, realtime);
        const figures = opts.format !== 'json' ? null : teller && trace ? runFiguresOf(teller) : await runFigures(logsDir, logs).catch(() => null);
        const schemas = figures?.schemas ?? null, eventHandling = figures?.eventHandling ?? null, moduleCpu = figures?.moduleCpu ?? null, engineCpu = figures?.engineCpu ?? null;
        const extra = {
            logsDir: logs.length ? logsDir : null, logs, logsRefused: savedLogs.refused, previousLogs: savedLogs.movedAside,
            logsLeftOut: leftOut, moduleFailures: failures, runDirLeftovers: leftovers, trace, schemas, eventHandling, moduleCpu, engineCpu, output: outcome.runLines,
        };
        const problems = problemLines(outcome.result.issues ?? [], failures, realtime);
        const notSaved = savedLogs.refused.map((r) => `log ${r.replace(/: /, ' not written: ')}`);
        const code = reportBuild(opts, outcome, io, extra, problems, notSaved);
        if (opts.format === 'text') {
            for (const f of failures) io.err(`module ${safeName(failureText(f))}\n`);
            // a run a sandbox limit killed left its modules' files: expected, not a warning (the limit is the problem told)
            if (leftovers.length && !outcome.result.limitHit) io.err(`warning: the run left files in its run directory: ${leftovers.map(safeName).join(', ')}\n`);
            for (const s of leftOut) if (!s.bound) io.err(`warning: log ${safeName(s.name)} not collected: ${s.reason}\n`);
            for (const p of problems) io.err(`problem: ${p}\n`);
            if (savedLogs.movedAside) io.err(`previous run's CSV logs: ${savedLogs.movedAside.files} file(s) moved to ${safeName(fromCwd(io.cwd, savedLogs.movedAside.folder))}\n`);
            if (logs.length) io.err(`CSV logs: ${logs.length} file(s) in ${safeName(fromCwd(io.cwd, logsDir))}\n`);
            for (const r of savedLogs.refused) io.err(`contract run: log not written to ${safeName(logsDir)}: ${safeName(r)}\n`);
            if (trace) io.err(`trace: ${trace.records} record(s)${trace.unreadable ? `, ${trace.unreadable} unreadable line(s)` : ''} in ${safeName(trace.file)}\n`);
            const created = !defaultLogs ? [] : !logsBefore && logs.length ? [`logs/${logs[0]}`] : !previousBefore && savedLogs.movedAside ? [relative(opts.dir, savedLogs.movedAside.folder).split(sep).join('/')] : [];
            const hint = await gitignoreHint(opts.dir, safeName(fromCwd(io.cwd, opts.dir)), created);
            if (hint) io.err(hint);
        }
        if (outcome.result.limitHit) return code;
        if (failures.length) return EXIT_FAILURE;
        // a log refused (a link planted under its name): the others are written, the run is not whole on disk
        return savedLogs.refused.length && code === EXIT_OK ? EXIT_FAILURE : code;
    },
};

// the parts of `contract run` that live in their own files, for their tests
export { failureText, moduleFailures, problemLines, type ModuleFailure } from './run-problems.js';
export { refusedPrevious, saveLogs, type SavedLogs } from './run-logs.js';
export { startProblem } from './run-model-checks.js';
