/**
 * The CLI's job runner, shared by `contract build` and `contract run`: option parsing (sandbox,
 * format, runtime, cache folder), one job through the build service's in-process pipeline
 * (@contract-studio/build-service JobService, not HTTP) with its live output, the JSON and text
 * reports, and the exit codes (docs/ci.md).
 */
import { existsSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { stat } from 'node:fs/promises';
import type { GccDiagnostic, Job, JobEvent, JobResult, JobService as JobServiceType, SandboxChoice } from '@contract-studio/build-service';
import { CRASH_MARK, crashSiteOfLine, foreignMakefilesMessage, installedRuntimeProblem, renderDiagnostic } from '@contract-studio/build-service';
import { folderOption, type ParsedArgs } from './args.js';
import { EXIT_FAILURE, EXIT_OK, EXIT_USAGE, UsageError, type CliIO } from './command.js';
import { addLimitOption, DEFAULT_PROCESS_LIMIT, emptyLimitOptions, modulesUnderProcessLimit, RENAME_JOURNAL_NAME, SANDBOX_CHOICES, SRC_GEN_DIR, UNUSED_TREE_LINE, withoutStuckAdvice, type LimitOptions } from '@contract-studio/conventions';
import { defaultRuntimeSource } from './runtime-source.js';
import { LiveModuleEnds } from './live-module-ends.js';
import { safeName } from './terminal-text.js';
import { insideProjectRefusal } from './enclosing-project.js';

/** The environment cannot do what was asked (no sandbox, no runtime, a build cache folder that cannot be trusted). */
export const EXIT_ENVIRONMENT = 3;
/** The run ended but did not go as designed: a sandbox limit was hit, ORD declared a module stuck,
 *  or output / CSV logs were cut or left out (the job result's `issues`, docs/ci.md). */
export const EXIT_RUN_INCOMPLETE = 4;
/** Interrupted by Ctrl+C (the job was cancelled, everything stopped). */
export const EXIT_INTERRUPTED = 130;

/** Progress is for people: only when both output streams are a terminal (never in CI logs or pipes). */
export function onTerminal(): boolean {
    return process.stdout.isTTY === true && process.stderr.isTTY === true;
}

export const SANDBOXES: readonly SandboxChoice[] = SANDBOX_CHOICES;
/** Said after the launcher's `run directory` line of a sandboxed run: its pids and paths are not the host's. */
export const SANDBOX_PIDS_NOTE = 'contract run: the pids and paths the run prints are the sandbox\'s (its own pid namespace and root), not the host\'s: docs/runtime-api.md "Process model" (Pids) says how to find a module\'s host pid';
const FORMATS = ['text', 'json'] as const;
type Format = (typeof FORMATS)[number];

export interface JobOptions {
    dir: string;
    dirArg: string;
    sandbox: SandboxChoice;
    format: Format;
    verbose: boolean;
    /** Progress lines (steps, generation counts) on stderr: only on a TTY and in text format. */
    progress: boolean;
    runtime: string | undefined;
    /** --cache-dir (resolved), else undefined: $CONTRACT_CACHE_DIR, else the XDG cache folder. */
    cacheDir: string | undefined;
}

export const COMMON_VALUED = ['sandbox', 'format', 'runtime', 'cache-dir'];
export const COMMON_FLAGS = ['verbose', 'werror'];
/** Options build and run take more than once. */
export const COMMON_REPEATABLE = ['limit'];
/** Their usage line of `--limit` (the reading `contract serve` shares: conventions' limit-option.ts). */
export const LIMIT_USAGE = [
    '  --limit NAME=VALUE (repeatable): one of the build service\'s limits for this job, above or below its default (docs/sandbox.md "Limits"),',
    `               as \`contract serve --limit\`: e.g. processes=512 for an architecture of more than ${modulesUnderProcessLimit(DEFAULT_PROCESS_LIMIT)} module processes`,
    '               (`contract check` warns: architecture-over-process-limit), memoryMiB=1024; runSeconds and buildSeconds replace the CLI\'s own',
];

/** The `--limit NAME=VALUE` values of a command line, read as `contract serve` reads them; a bad one is bad usage. */
export function parseLimitOptions(parsed: ParsedArgs): LimitOptions | undefined {
    const given = parsed.repeated.get('limit');
    if (!given?.length) return undefined;
    const out = emptyLimitOptions();
    for (const text of given) {
        const refused = addLimitOption(out, text);
        if (refused) throw new UsageError(refused);
    }
    return out;
}
export const COMMON_USAGE = [
    '  DIR: the project\'s root, as for contract generate (docs/codegen.md "Where a project is"): its src-gen/ is the tree built',
    '  --sandbox: auto (default: bwrap when it works, else docker), bwrap, docker, none (no isolation)',
    '  --format: text (default) or json (one JSON object on stdout at the end, no progress)',
    '  --runtime: the runtime source folder (default: $CONTRACT_RUNTIME, else the one inside the installed CLI or the repository\'s runtime/)',
    '  --cache-dir: the build cache (built runtime, one work tree per project; default: $CONTRACT_CACHE_DIR,',
    '               else $XDG_CACHE_HOME/contract-studio, else ~/.cache/contract-studio; root: /var/cache/contract-studio)',
    '  --verbose: print every build line and the time of every step (otherwise only gcc diagnostics and the summary)',
    '  --werror: compile the project\'s code (every module, your protected regions and files) with -Werror: a gcc warning fails the build',
    '            (the runtime is warning-free already); without it warnings are printed and the build goes on',
];
export const EXIT_TABLE = 'exit status: 0 success, 1 project errors / build failed / run failed or a module crashed, 2 bad usage, 3 no usable sandbox or a build cache folder that cannot be trusted, 4 run incomplete (a limit hit, a module stuck, hung at the stop or ended early, the start request refused, output or logs cut), 130 interrupted';

/** Parses DIR and the options build and run share. */
export async function parseJobOptions(parsed: ParsedArgs, io: CliIO, isTTY: boolean): Promise<JobOptions> {
    const { positionals, options } = parsed;
    if (positionals.length !== 1) throw new UsageError(positionals.length ? 'expected exactly one DIR' : 'missing DIR (the folder of the .contract files)');
    const dirArg = positionals[0]!;
    const dir = resolve(io.cwd, dirArg);
    const info = await stat(dir).catch(() => undefined);
    if (!info?.isDirectory()) throw new UsageError(`${safeName(dirArg)} is not a directory`);
    const sandbox = (options.get('sandbox') ?? 'auto') as SandboxChoice;
    if (!SANDBOXES.includes(sandbox)) throw new UsageError(`unknown sandbox '${String(sandbox)}' (expected auto, bwrap, docker or none)`);
    const format = (options.get('format') ?? 'text') as Format;
    if (!FORMATS.includes(format)) throw new UsageError(`unknown format '${String(format)}' (expected text or json)`);
    const runtimeOption = options.get('runtime');
    const runtime = typeof runtimeOption === 'string' ? resolve(io.cwd, runtimeOption) : process.env.CONTRACT_RUNTIME || undefined;
    if (runtime && !existsSync(join(runtime, 'Makefile'))) throw new UsageError(`${runtime} is not a runtime folder (no Makefile); pass --runtime PATH to the ContrACT runtime/`);
    // an installed runtime (make install PREFIX=...) has no sources to build: refused before any build
    const installed = runtime && installedRuntimeProblem(runtime, typeof runtimeOption === 'string' ? `--runtime ${runtime}` : `CONTRACT_RUNTIME=${runtime}`);
    if (installed) throw new UsageError(installed);
    const cacheDir = folderOption(options, 'cache-dir', io.cwd);
    return { dir, dirArg, sandbox, format, verbose: options.get('verbose') === true, progress: isTTY && format === 'text', runtime, cacheDir };
}

/** A gcc diagnostic as gcc prints it, its path from where the command was typed (`dirArg`: the project folder as given). */
export function formatGccDiagnostic(d: GccDiagnostic, dirArg = '.'): string {
    // a file outside the tree (a system header, the runtime's) keeps its own absolute path
    const where = d.file ? `${safeName(d.file.startsWith('/') ? d.file : join(dirArg, 'src-gen', d.file))}:${d.line ?? 0}${d.column === null ? '' : `:${d.column}`}: ` : '';
    const region = d.protectedRegion ? ` [in protected region ${d.protectedRegion.id}]` : '';
    return `${where}${d.severity}: ${d.message}${d.option ? ` [${d.option}]` : ''}${region}\n`;
}

export interface JobOutcome {
    job: Job;
    result: JobResult;
    /** Lines of the run step: [source, line] (module tag or 'launcher'/'run'; 'service': its lines of the run's stop, RUN_STOP_LINE). */
    runLines: { source: string; stream: string; line: string }[];
    /**
     * The build step's last error lines (make's `***`, the assembler's, a tool's): told when a
     * build fails with no error gcc or ld reported, so that the report never points at errors
     * "above" that were not printed.
     */
    buildTail: string[];
}

/** The build's error lines a failed build with no diagnostic shows (the last ones). */
const BUILD_TAIL_LINES = 15;
/** A build line that says what failed: make's `***`, the assembler's, a tool's error (matched on its first 500 characters). */
const BUILD_ERROR_LINE = /\*\*\*|\berror\b|Assembler messages|cannot|not found|No such file|Killed|Segmentation fault/i;

export interface RunRequest {
    action: 'build' | 'run';
    start?: string;
    duration?: number;
    /** Seconds every module's init may take before the start request (contract-launch's default: 10). */
    readyTimeout?: number;
    cpus?: string;
    realtime?: boolean;
    /** --werror: the project's code compiled with -Werror (the build service's `werror`). */
    werror?: boolean;
    /** `--stdin NAME=FILE`: module NAME reads FILE (a file of the project, its path from DIR) on its stdin. */
    stdin?: Record<string, string>;
    /** --run-limit: the run step's wall time limit in seconds (default: cliLimits). */
    runLimit?: number;
    /** `--limit NAME=VALUE`: the build service's limits for this job, above or below its defaults (docs/sandbox.md "Limits"), and their texts as written. */
    limitOptions?: LimitOptions;
}

/** The build step's wall time limit of `contract build` and `contract run` (the service's default is 120 s). */
export const CLI_BUILD_SECONDS = 600;
/** Room the CLI's default run time limit keeps past the duration, to start and stop the architecture. */
export const CLI_RUN_ROOM_SECONDS = 60;

/**
 * The time limits the CLI gives its job (packages/cli/README.md, "Limits"): the build gets CLI_BUILD_SECONDS
 * (a cold build of a big project on a slow runner); the run, `--run-limit` when given, else its
 * duration (default 10 s), plus the wait for the modules' inits past the launcher's default 10 s,
 * plus CLI_RUN_ROOM_SECONDS: the run lasts as long as asked. The other limits are the service's
 * defaults (docs/sandbox.md "Limits").
 */
export function cliLimits(request: RunRequest): { runSeconds: number; buildSeconds: number } {
    const runSeconds = request.runLimit ?? Math.ceil((request.duration ?? 10) + Math.max(0, (request.readyTimeout ?? 10) - 10) + CLI_RUN_ROOM_SECONDS);
    return { runSeconds, buildSeconds: CLI_BUILD_SECONDS };
}

/**
 * Runs one job on the in-process service and streams its events to io. `whileOpen` is called
 * after the job ended but before the service removes the workspace (to copy the CSV logs out);
 * `onEvent` sees every event as it comes (the live trace of `contract run --trace`).
 */
export async function runJob(
    opts: JobOptions,
    request: RunRequest,
    io: CliIO,
    whileOpen?: (service: JobServiceType, cacheDir: string, outcome: JobOutcome) => Promise<void>,
    onEvent?: (e: JobEvent) => void,
): Promise<JobOutcome | { error: string; exitCode: number }> {
    // a folder inside a project (P/src of P/src-gen) is no project: it built an empty second tree of defaults
    const inside = insideProjectRefusal(opts.dir, opts.dirArg, request.action, request.action === 'run' ? 'built or run' : 'built');
    if (inside) return { error: inside, exitCode: EXIT_FAILURE };
    const t0 = Date.now();
    const { JobService, ServiceError, DEFAULT_RUNTIME_SOURCE, resolveCacheDir, prepareCacheDir, DEFAULT_LIMITS, LimitsError, mergeLimits } = await import('@contract-studio/build-service');
    // --limit: the service's own check (names, whole counts, ranges), as `contract serve` has it, before anything else
    const limits = { ...cliLimits(request), ...(request.limitOptions?.limits ?? {}) };
    try {
        mergeLimits(DEFAULT_LIMITS, limits, false, request.limitOptions?.limitTexts);
    } catch (e) {
        if (e instanceof LimitsError) return { error: `--limit: ${e.message}`, exitCode: EXIT_USAGE };
        throw e;
    }
    const timing = (what: string, since: number): void => {
        if (opts.verbose && opts.format === 'text') io.err(`time: ${what} ${Date.now() - since} ms\n`);
    };
    timing('loading the build service', t0);
    const runtime = opts.runtime ?? defaultRuntimeSource(DEFAULT_RUNTIME_SOURCE);
    if (opts.sandbox !== 'docker' && !existsSync(join(runtime, 'Makefile'))) {
        return {
            error: `no ContrACT runtime at ${runtime}: pass --runtime PATH (or set CONTRACT_RUNTIME) to the runtime/ folder of ContrACT Studio, or use --sandbox docker (the contract-gcc image carries it)`,
            exitCode: EXIT_ENVIRONMENT,
        };
    }
    // the persistent cache shared with other commands and the IDE (docs/getting-started.md "The build cache")
    const cache = resolveCacheDir(opts.cacheDir, process.env, process.getuid?.(), undefined, io.cwd);
    const refused = prepareCacheDir(cache.dir, process.getuid?.() === 0 && opts.sandbox !== 'docker');
    if (refused) return { error: refused, exitCode: EXIT_ENVIRONMENT };
    if (opts.verbose && opts.format === 'text') io.err(`build cache: ${cache.dir} (${cache.source})\n`);
    const service = new JobService({
        sandbox: opts.sandbox,
        concurrency: 1,
        queueSize: 0,
        projectRoots: [opts.dir],
        cacheDir: cache.dir,
        persistentWorkspaces: true,
        // --limit over the CLI's own time limits (checked above)
        limits,
        ...(request.limitOptions ? { limitTexts: request.limitOptions.limitTexts } : {}),
        runtimeSource: runtime,
    });
    let job: Job | undefined;
    const onSigint = (): void => {
        if (job) void service.cancel(job.id);
    };
    process.on('SIGINT', onSigint);
    process.on('SIGTERM', onSigint);
    // the output's reader went away (`| head`): nobody follows the job any more, stopped as on Ctrl+C
    io.outputClosed?.addEventListener('abort', onSigint);
    try {
        try {
            job = await service.submit({
                action: request.action,
                project: { dir: opts.dir },
                sandbox: opts.sandbox,
                ...(request.start !== undefined ? { start: request.start } : {}),
                ...(request.duration !== undefined ? { duration: request.duration } : {}),
                ...(request.readyTimeout !== undefined ? { readyTimeout: request.readyTimeout } : {}),
                ...(request.cpus !== undefined ? { cpus: request.cpus } : {}),
                ...(request.realtime ? { realtime: true } : {}),
                ...(request.werror ? { werror: true } : {}),
                ...(request.stdin ? { stdin: request.stdin } : {}),
            });
        } catch (e) {
            if (e instanceof ServiceError) return { error: e.message, exitCode: e.status === 503 ? EXIT_ENVIRONMENT : EXIT_FAILURE };
            throw e;
        }
        if (io.outputClosed?.aborted) onSigint();
        const runLines: JobOutcome['runLines'] = [];
        const buildTail: string[] = [];
        const print = makePrinter(opts, io, runLines, buildTail, () => job!.warnings);
        const unsubscribe = job.events.subscribe(0, (e) => {
            print(e);
            try {
                onEvent?.(e);
            } catch {
                /* the caller's handler must not stop the printing */
            }
        });
        await job.finished;
        unsubscribe();
        const outcome: JobOutcome = { job, result: job.result!, runLines, buildTail };
        if (whileOpen) await whileOpen(service, cache.dir, outcome);
        return outcome;
    } finally {
        process.off('SIGINT', onSigint);
        process.off('SIGTERM', onSigint);
        io.outputClosed?.removeEventListener('abort', onSigint);
        const tc = Date.now();
        await service.close();
        timing('closing the build service', tc);
    }
}

/**
 * How the service logs a prepare problem (build-service pipeline/prepare.ts problemAt): the model's
 * `file.contract:line:col: severity: message`; the generator's `src-gen/FILE[:line]: severity: message`,
 * or its own notes `(manifest): ...` and an absolute path.
 */
const PREPARE_PROBLEM_LINE = /^(?:[^\n]*:\d+:\d+|src-gen\/[^\n]*?(?::\d+)?|\([^\n]*?\)|\/[^\n]*?(?::\d+)?): (?:error|warning|info): /;

/** Text output of the job's events: progress on a TTY, diagnostics always, module output for run. */
/** The service's line when a run's stdout or stderr went past its cap (job.ts). */
const OUTPUT_TRUNCATED_LINE = /^\[output truncated: (stdout|stderr) limit .* reached\]$/;
/** The service's line when a run's duration was shortened to fit its run time limit (job.ts). */
const DURATION_CAPPED_LINE = /^duration \S+ s capped to \S+ s: the run time limit is /;
/** The same said among the job's warnings (build-service durationCapMessage). */
const DURATION_CAPPED_WARNING = DURATION_CAPPED_LINE;
/** The service's line while another command holds the project (build-service job.ts onWait): said in every mode. */
const WAITING_LINE = /^waiting for the other command using this project \(/;
/**
 * The service's line of what holds a real-time run (job.ts: `real-time mode: SCHED_FIFO up to 99 (...); ...`):
 * said in every mode, as what a user must see to trust the run's timing (its refusal ends the job and is its status line).
 */
const REALTIME_LINE = /^real-time mode: /;
/** The service's line of the error that ended the prepare step (job.ts): the status line says it (`FAILED: prepare failed: ...`), once. */
const PREPARE_FAILED_LINE = /^error: /;
/** The service's `time: <step> N ms` lines: --verbose only (a terminal's progress lines leave them out). */
const TIME_LINE = /^time: /;

/**
 * The service's lines of a run's stop (job.ts): `memory limit 512 MiB reached: stopping the
 * architecture as at the end of a run (...)` (a limit hit), `stopping the architecture as at the
 * end of a run (...)` (the run time limit, Ctrl+C), `the architecture did not stop within 1000 ms:
 * killed`, `no contract-launch process to ask (...): killed`. Printed on stderr in every text output and kept with the run's lines (`output` in JSON):
 * without them a stop reads as a normal end (`contract-launch: stopping`).
 */
const RUN_STOP_LINE = /^(?:[^\n]{1,200} reached: )?stopping the architecture as at the end of a run \(|^the architecture did not stop within \d+ ms: killed$|^no contract-launch process to ask \([^\n]{1,200}\): killed$|^cancel asked while the run was being stopped by the [^\n]{1,200}: it ends by the limit$/;

/** Keeps `e` in `tail` (the last BUILD_TAIL_LINES) when it is a line of the build that says what failed. */
export function noteBuildErrorLine(tail: string[], e: JobEvent): void {
    if (e.type !== 'line' || e.step !== 'build' || e.source === 'service') return;
    const head = e.line.slice(0, 500);
    if (!BUILD_ERROR_LINE.test(head) || /^g?make(?:\[\d+\])?: Target .* not remade/.test(head)) return;
    tail.push(e.line);
    if (tail.length > BUILD_TAIL_LINES) tail.shift();
}

/** The function ld named, which the service adds to an undefined reference's message (ld-text.ts). */
const LD_FUNCTION_SUFFIX = / \(in function [^()]*\)$/;
/** Linker places remembered for --verbose at most (a build has a few; the job keeps 1000 diagnostics). */
const MAX_LINKER_PLACES = 2000;

/** `generated/...:L: message` of one of ld's lines naming a place in the tree (after `/work/src-gen/`, `/usr/bin/ld: `), else ''. */
function linkerPlaceOf(line: string): string {
    const at = line.indexOf('src-gen/');
    return at < 0 ? '' : line.slice(at + 'src-gen/'.length);
}

/**
 * The printer of a job's events (exported for its tests). `jobWarnings`: the job's warnings so far;
 * the service's `warning: W` line of one of them is left out, in every mode (--verbose, a terminal's
 * progress): the closing lines (reportBuild) say each once. The service adds a warning to the job
 * before it logs its line.
 */
export function makePrinter(opts: JobOptions, io: CliIO, runLines: JobOutcome['runLines'], buildTail: string[], jobWarnings: () => readonly string[] = () => []): (e: JobEvent) => void {
    const madeParts = new Set<string>();
    // the service's log line of each diagnostic printed (its rendering, as the line after it says it),
    // by count: --verbose prints the diagnostic once, as the CLI writes it (the path from here, the region)
    const printedDiagnostics = new Map<string, number>();
    const alreadyPrinted = (line: string): boolean => {
        const n = printedDiagnostics.get(line);
        if (!n) return false;
        if (n > 1) printedDiagnostics.set(line, n - 1); else printedDiagnostics.delete(line);
        return true;
    };
    // the linker's errors printed (--verbose): ld writes each undefined reference on two lines of its
    // own (`/work/src-gen/F:L: undefined reference to ...`, and the same after `/usr/bin/ld: `), which
    // the diagnostic stands for: `F:L: message` (F relative to src-gen, the function ld named left out)
    const printedLinkerPlaces = new Set<string>();
    // a module that ends on its own mid-run, told from the launcher's line as it comes (its pid the module's, from the live trace)
    const moduleEnds = new LiveModuleEnds();
    return (e) => {
        if (e.type === 'trace') {
            if (opts.format === 'text') for (const told of moduleEnds.records(e.records)) io.err(`${told}\n`);
            return;
        }
        noteBuildErrorLine(buildTail, e);
        if (e.type === 'diagnostic') {
            if (opts.format !== 'text') return;
            io.err(formatGccDiagnostic(e.diagnostic, opts.dirArg));
            // --verbose: its notes follow it, written the same way, and the log's lines of both are not printed again
            if (opts.verbose) {
                for (const note of e.diagnostic.children) io.err(formatGccDiagnostic(note, opts.dirArg));
                for (const d of [e.diagnostic, ...e.diagnostic.children]) {
                    const line = renderDiagnostic(d);
                    printedDiagnostics.set(line, (printedDiagnostics.get(line) ?? 0) + 1);
                    if (d.file !== null && d.line !== null && d.column === null && printedLinkerPlaces.size < MAX_LINKER_PLACES) {
                        printedLinkerPlaces.add(`${d.file}:${d.line}: ${d.message.replace(LD_FUNCTION_SUFFIX, '')}`);
                    }
                }
            }
            return;
        }
        if (e.type === 'status') {
            if (opts.progress && e.step) io.err(`[${e.status}]\n`);
            return;
        }
        if (e.type !== 'line') return;
        // the service stopping the architecture (a limit reached, the run time limit, Ctrl+C): said in
        // every output, as the launcher's lines it causes are
        if (e.step === 'run' && e.source === 'service' && RUN_STOP_LINE.test(e.line)) {
            runLines.push({ source: e.source, stream: e.stream, line: e.line });
            if (opts.format === 'text') io.err(`${e.line}\n`);
            return;
        }
        // where a module crashed (the service maps its crash report): read back for `module X crashed (...) at ...`
        if (e.step === 'run' && e.source === 'service' && crashSiteOfLine(e.line)) runLines.push({ source: e.source, stream: e.stream, line: e.line });
        if (e.step === 'run' && e.source !== 'service') {
            runLines.push({ source: e.source, stream: e.stream, line: e.line });
            if (opts.format !== 'text') return;
            // a crashed module's crash report (its frames as offsets): the service tells where it crashed; its lines with --verbose
            if (!opts.verbose && e.source !== 'run' && e.source !== 'launcher' && e.line.startsWith(CRASH_MARK)) return;
            if (e.source === 'run') {
                // make's own lines (directories, recipes) only with --verbose; its errors always
                if (opts.verbose || /\*\*\*|error/i.test(e.line)) io.err(`${e.line}\n`);
            } else {
                // each line on the stream it was written to: a module's stderr (ORD's warnings, a
                // module's errors) and the launcher's lines (it writes on stderr) go to stderr
                const text = e.source === 'launcher' ? `contract-launch: ${e.line}\n` : `[${e.source}] ${e.line}\n`;
                if (e.stream === 'stderr') io.err(text); else io.out(text);
                // the launcher's line of a module's end on its own: one line saying it, as the IDE shows it gone
                const ended = e.source === 'launcher' ? moduleEnds.launcherLine(e.line) : undefined;
                if (ended) io.err(`${ended}\n`);
                // the launcher's first line: in the bwrap or docker sandbox (auto is one of them) the run has a pid namespace of its own
                if (e.source === 'launcher' && e.line.startsWith('run directory ') && opts.sandbox !== 'none') io.err(`${SANDBOX_PIDS_NOTE}\n`);
            }
            return;
        }
        // a command that waits says for whom in every output, in CI too (stderr no terminal): never a silent pause
        if (e.source === 'service' && WAITING_LINE.test(e.line)) {
            io.err(`${e.line}\n`);
            return;
        }
        // what holds a real-time run: said in every mode, once (docs/sandbox.md "Real-time mode")
        if (e.step === 'prepare' && e.source === 'service' && REALTIME_LINE.test(e.line)) {
            io.err(`${e.line}\n`);
            return;
        }
        // a --duration that does not fit in --run-limit: the service shortens it, said on stderr in
        // every output (never silently; also among the job's warnings, `warnings` in JSON)
        if (e.step === 'run' && e.source === 'service' && DURATION_CAPPED_LINE.test(e.line)) {
            io.err(`${e.line}\n`);
            return;
        }
        if (opts.format !== 'text') return;
        // one of the job's warnings (a build's output cut, a real-time run throttled): said once, at the end
        if (e.source === 'service' && e.line.startsWith('warning: ') && jobWarnings().includes(e.line.slice('warning: '.length))) return;
        // the run's output cut at its cap: said where it was cut, in the same stream (the modules' lines go on in their CSV logs)
        // (the cap is per stream: the other one, with the launcher's lines on stderr, goes on)
        const truncated = e.step === 'run' && e.source === 'service' ? OUTPUT_TRUNCATED_LINE.exec(e.line) : null;
        if (truncated) {
            const other = truncated[1] === 'stdout' ? 'stderr' : 'stdout';
            io.out(`${e.line.slice(0, -1)}: the rest of the run's ${truncated[1]} is not shown (its ${other} still is); the CSV logs and --trace are whole]\n`);
            return;
        }
        // the service's own line for each model or generation problem: printed once, at the end, at
        // its path from where the command ran (prepareErrors), not here relative to the project
        if (e.step === 'prepare' && e.source === 'service' && (PREPARE_PROBLEM_LINE.test(e.line) || /^the project has \d+ error\(s\): nothing generated$/.test(e.line))) return;
        // the error that ended the prepare step: said once, by the status line at the end (reportBuild)
        if (e.step === 'prepare' && e.source === 'service' && PREPARE_FAILED_LINE.test(e.line)) return;
        // a diagnostic's line, or one of its notes, in the build's log: printed above with the diagnostic
        if (e.step === 'build' && e.source === 'build' && alreadyPrinted(e.line)) return;
        if (e.step === 'build' && e.source === 'build' && printedLinkerPlaces.size && printedLinkerPlaces.has(linkerPlaceOf(e.line))) return;
        // a second generated tree of the project, not built (docs/codegen.md "Where a project is"): said in every text output
        if (e.step === 'prepare' && e.source === 'service' && (/error/i.test(e.line) || UNUSED_TREE_LINE.test(e.line))) {
            io.err(`${e.line}\n`);
        } else if (e.step === 'prepare' && e.source === 'runtime' && e.stream === 'stderr' && /error/i.test(e.line)) {
            io.err(`${e.line}\n`);
        } else if (opts.verbose) {
            io.err(`${e.line}\n`);
        } else if (opts.progress && (e.source === 'service' || e.source === 'runtime') && !(e.source === 'service' && TIME_LINE.test(e.line))) {
            io.err(`${e.line}\n`);
        } else if (opts.progress && e.step === 'build') {
            // one line per part of the tree make works on (modules, control tools)
            const part = /Entering directory '.*\/(?:modules\/(\w+)_mod|(tools))'/.exec(e.line);
            const name = part ? (part[1] ?? part[2])! : null;
            if (name && !madeParts.has(name)) {
                madeParts.add(name);
                io.err(`  make: ${name}\n`);
            }
        }
    };
}

/**
 * A prepare problem is the model's (a `.contract` file, 1-based line and column: what `contract
 * check` reports) or the generator's (a file of the generated tree, relative to src-gen, its line
 * when known and no column: what `contract generate` reports, e.g. a broken protected-region marker).
 */
export function isModelProblem(p: { file: string }): boolean {
    return p.file.endsWith('.contract');
}

/** Each prepare problem once, gcc-like, at its path from where the command ran. */
export function prepareErrors(job: Job, dirArg: string): string {
    return job.prepareDiagnostics
        .map((p) => {
            if (isModelProblem(p)) return `${safeName(join(dirArg, p.file))}:${p.line}:${p.column}: ${p.severity}: ${p.message}\n`;
            // the generator's own notes ("(manifest)", an absolute path) are not files of src-gen
            const file = p.file.startsWith('(') || p.file.startsWith('/') ? p.file : join(dirArg, SRC_GEN_DIR, p.file);
            return `${safeName(file)}${p.line ? `:${p.line}` : ''}: ${p.severity}: ${p.message}\n`;
        })
        .join('');
}

/** The JSON view printed with --format json. */
export function jobJson(outcome: JobOutcome, extra: Record<string, unknown> = {}): string {
    const { job, result } = outcome;
    return JSON.stringify({
        ok: result.ok,
        status: job.status,
        sandbox: job.sandboxName,
        sandboxNote: job.sandboxNote,
        warnings: job.warnings,
        result,
        prepareDiagnostics: job.prepareDiagnostics,
        diagnostics: job.diagnostics,
        ...extra,
    }, null, 2) + '\n';
}

export function exitCodeOf(result: JobResult, job: Job): number {
    if (result.ok) return EXIT_OK;
    if (job.status === 'cancelled') return EXIT_INTERRUPTED;
    if (result.step === 'run' && (result.limitHit || result.issues.length)) return EXIT_RUN_INCOMPLETE;
    return EXIT_FAILURE;
}

/**
 * The report at the end of a job (json: the whole record); returns its exit code. `problems`: the
 * run's problems as told (run.ts problemLines), when they differ from the service's messages,
 * which the summary line then quotes as told. `afterwards`: what went wrong here after the job (a
 * log that could not be saved): the status line then says FAILED, not ok.
 */
export function reportBuild(opts: JobOptions, outcome: JobOutcome, io: CliIO, extra: Record<string, unknown> = {}, problems?: readonly string[], afterwards: readonly string[] = []): number {
    const { job, result } = outcome;
    if (opts.format === 'json') {
        io.out(jobJson(outcome, extra));
        return exitCodeOf(result, job);
    }
    io.err(prepareErrors(job, opts.dirArg));
    // the duration's cap is said as the run begins (makePrinter), not twice (a job that never ran: moot)
    for (const w of job.warnings) if (!DURATION_CAPPED_WARNING.test(w)) io.err(`warning: ${w}\n`);
    const seconds = (ms: number | undefined) => (ms === undefined ? '-' : (ms / 1000).toFixed(1));
    const d = result.durations_ms;
    // a foreign makefile's refusal names it from where the command ran (DIR/src-gen/...), as every other path here
    let message = job.foreignMakefiles.length ? `prepare failed: ${foreignMakefilesMessage(job.foreignMakefiles, (rel) => join(opts.dirArg, rel))}` : result.message;
    (result.issues ?? []).forEach((i, n) => {
        const told = problems?.[n];
        if (told === undefined || told === i.message) return;
        const short = withoutStuckAdvice(i.message);
        message = message.includes(i.message) ? message.replace(i.message, told) : message.replace(short, told);
    });
    if (afterwards.length) message = `${message}, but ${afterwards.join('; ')}`;
    io.err(`${result.ok && !afterwards.length ? 'ok' : 'FAILED'}: ${message} [${job.sandboxName}; prepare ${seconds(d.prepare)} s, build ${seconds(d.build)} s${d.run !== undefined ? `, run ${seconds(d.run)} s` : ''}]\n`);
    if (!result.ok && result.step === 'prepare' && job.prepareDiagnostics.length) {
        const dir = safeName(opts.dirArg);
        const model = job.prepareDiagnostics.filter((p) => p.severity === 'error' && isModelProblem(p)).length;
        // a rename killed half-way (codegen rename-journal.ts): generate finishes it, nothing to fix by hand
        const journal = job.prepareDiagnostics.some((p) => p.severity === 'error' && (p.file === RENAME_JOURNAL_NAME || p.file.endsWith(`/${RENAME_JOURNAL_NAME}`)));
        const generated = journal ? 0 : job.prepareDiagnostics.filter((p) => p.severity === 'error' && !isModelProblem(p)).length;
        if (journal) io.err(`run \`contract generate ${dir}\` to finish the interrupted rename, then build again\n`);
        if (model) io.err(`fix the model errors above (\`contract check ${dir}\` lists them), then build again\n`);
        if (generated) io.err(`fix the generated tree's errors above in ${safeName(join(opts.dirArg, SRC_GEN_DIR))} (a protected-region marker broken or edited, a merge conflict left in a file, user code a regeneration would move to orphans/: \`contract generate ${dir}\` lists them and moves that code aside in the project), then build again\n`);
        if (!model && !generated && !journal) io.err(`fix the problems above, then build again\n`);
    }
    const buildErrors = result.step === 'build' ? job.diagnostics.filter((x) => x.severity === 'error').length : 0;
    if (!result.ok && result.step === 'build' && !buildErrors && !opts.verbose && outcome.buildTail.length && job.status !== 'cancelled' && !result.limitHit) {
        // nothing gcc or ld reported: make's and the tools' error lines say why (the assembler's, a tool killed);
        // or gcc's diagnostics could not be read (the job's warning): its errors may be among them
        const unread = job.unreadableDiagnosticLines;
        const said = unread ? `gcc's diagnostics could not be read (${unread} line(s) of its JSON output): no error of theirs is reported, they may hold the build's errors` : 'no compiler or linker error was reported';
        io.err(`${said}; the build's last error lines:\n${outcome.buildTail.map((l) => `  | ${safeName(l.length > 500 ? `${l.slice(0, 500)}…` : l)}\n`).join('')}`);
    }
    if (!result.ok && result.step === 'build' && job.status !== 'cancelled') {
        if (buildErrors) io.err(`fix the gcc errors above (your code is in the PROTECTED REGION blocks of ${safeName(join(opts.dirArg, SRC_GEN_DIR))} and in any file of your own there), then build again; --verbose shows every build line\n`);
        // a limit stopped the build: the status line names it (and, for the disk, what filled it); no compiler error to fix
        else if (result.limitHit) io.err(`the build was stopped by a sandbox limit, not by a compiler error (docs/sandbox.md "Limits"); --verbose shows every build line\n`);
        else io.err(`fix what the build's error lines say, then build again; --verbose shows every build line\n`);
    }
    return exitCodeOf(result, job);
}
