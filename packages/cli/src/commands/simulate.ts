/**
 * `contract simulate DIR SCENARIO... [--format text|json|junit] [--trace FILE.jsonl]`: steps each
 * scenario's events through the project's supervisors and ORD in virtual time — the real engine
 * cores, linked with the project's generated tables into a native harness (docs/simulation.md) —
 * and reports each step and each failed expectation like a test runner; `--trace` also writes the
 * simulation as the run-time trace records `contract run --trace` writes (one JSON object a line).
 */
import { existsSync, lstatSync, statSync } from 'node:fs';
import { join, resolve } from 'node:path';
import type { FileHandle } from 'node:fs/promises';
import type { JunitSuite, LoadedScenario, ScenarioResult, SimulatorSandboxChoice } from '@contract-studio/simulator';
import { folderOption, parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, EXIT_USAGE, UsageError, type CliIO, type Command } from '../command.js';
import { defaultRuntimeSource } from '../runtime-source.js';
import { EXIT_ENVIRONMENT, formatGccDiagnostic } from '../job-runner.js';
import { safeName } from '../terminal-text.js';
import { lockTraceFile, openTraceFile, toJsonLines, traceNameProblem } from '../trace-files.js';

const FORMATS = ['text', 'json', 'junit'] as const;
/** Lines of the --trace file written at once. */
const TRACE_LINES_PER_WRITE = 10_000;

/**
 * Whether a scenario path names nothing, as lstat sees it (a link not followed): bad usage, said
 * before the simulator is built. What is there but not a scenario (a link, a folder, a FIFO, too
 * large) is said by readScenarioFile, which opens it without waiting or following a link.
 */
function scenarioMissing(path: string): boolean {
    try {
        lstatSync(path);
        return false;
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        return code === 'ENOENT' || code === 'ENOTDIR'; // another problem (a folder that cannot be searched): said when the file is read
    }
}

export const simulateCommand: Command = {
    name: 'simulate',
    summary: 'run .scenario files through the supervisors and ORD in virtual time (no robot, no module code)',
    usage: [
        'usage: contract simulate DIR SCENARIO... [--format text|json|junit] [--trace FILE.jsonl] [--verbose] [--sandbox auto|bwrap|none] [--runtime PATH] [--cache-dir DIR]',
        '  DIR: the project (its .contract files); SCENARIO: .scenario files (format: docs/simulation.md)',
        '  --format: text (default: each step, its rule changes, each failed expectation), json (every step\'s record), junit (JUnit XML)',
        '  --verbose: text also shows each step\'s actions and the engines\' trace lines',
        '  --trace: also write each scenario\'s simulation to FILE as the trace records a run writes (contract run --trace), one JSON',
        '           object a line, in virtual time from 0; each scenario starts with a sim_start record naming it',
        '  --sandbox: where your project\'s C functions (testit, doit...) are compiled and run: bwrap (auto, the default: confined like a',
        '             build job) or none (unconfined, as you: your own code on your own machine only); default $CONTRACT_SIMULATOR_SANDBOX, else auto',
        '  --runtime: the runtime source folder (default: $CONTRACT_RUNTIME, else the one inside the installed CLI or the repository\'s runtime/)',
        '  --cache-dir: the build cache of `contract build`; built simulators are kept in its sim/ (default: $CONTRACT_CACHE_DIR,',
        '               else $XDG_CACHE_HOME/contract-studio, else ~/.cache/contract-studio; root: /var/cache/contract-studio)',
        'exit status: 0 every expectation passed, 1 one failed (or a scenario could not run), 2 usage, model or scenario errors,',
        '             3 a build cache folder that cannot be trusted, or no working bubblewrap for --sandbox auto|bwrap',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        // --cache (before it became --cache-dir) named the simulators' folder itself: told, not guessed
        if (args.some((a) => a === '--cache' || a.startsWith('--cache='))) throw new UsageError('--cache is now --cache-dir: the build cache folder (as for contract build); simulators are kept in its sim/');
        const parsed = parseArgs(args, ['format', 'runtime', 'cache-dir', 'sandbox', 'trace'], ['verbose']);
        const traceOption = parsed.options.get('trace');
        if (traceOption === '') throw new UsageError('--trace needs a file: --trace FILE.jsonl');
        const traceNameBad = typeof traceOption === 'string' ? traceNameProblem(traceOption) : undefined;
        if (traceNameBad) throw new UsageError(traceNameBad);
        // loaded when the command runs: other commands (a no-op `contract build`) do not pay for the simulator and the language
        const {
            DEFAULT_RUNTIME_DIR, JSON_REPORT_END, JSON_REPORT_HEAD, SIMULATOR_SANDBOXES, displayPath, errorCount, jsonScenarioParts, junitReportOf, junitSuite, loadScenario, prepareProject,
            readScenarioFile, runLoadedScenario, simulatorCacheDir, textScenarioParts, textSummary,
        } = await import('@contract-studio/simulator');
        if (parsed.positionals.length < 2) throw new UsageError('expected DIR and at least one SCENARIO file');
        const sandbox = parsed.options.get('sandbox');
        if (sandbox !== undefined && !SIMULATOR_SANDBOXES.includes(sandbox as never)) throw new UsageError(`unknown sandbox '${String(sandbox)}' (expected auto, bwrap or none)`);
        const format = parsed.options.get('format') ?? 'text';
        if (!FORMATS.includes(format as never)) throw new UsageError(`unknown format '${String(format)}' (expected text, json or junit)`);
        const runtimeOption = parsed.options.get('runtime');
        const runtimeDir = typeof runtimeOption === 'string' ? resolve(io.cwd, runtimeOption) : process.env.CONTRACT_RUNTIME || defaultRuntimeSource(DEFAULT_RUNTIME_DIR);
        if (!existsSync(join(runtimeDir, 'include', 'contract', 'vocabulary.h'))) throw new UsageError(`${runtimeDir} is not a ContrACT runtime folder; pass --runtime PATH`);
        const cacheDir = folderOption(parsed.options, 'cache-dir', io.cwd);
        const dir = resolve(io.cwd, parsed.positionals[0]!);
        if (!existsSync(dir)) throw new UsageError(`${parsed.positionals[0]} does not exist`);
        if (!statSync(dir).isDirectory()) throw new UsageError(`${safeName(parsed.positionals[0]!)} is not a directory (DIR is the folder of the .contract files)`);
        // a scenario file that is not there is bad usage, said before the simulator is built (not as Node's ENOENT)
        const missing = parsed.positionals.slice(1).filter((arg) => scenarioMissing(resolve(io.cwd, arg)));
        if (missing.length) throw new UsageError(`no such scenario file: ${missing.map(safeName).join(', ')}`);
        const cache = simulatorCacheDir(cacheDir, process.env, io.cwd);
        if ('error' in cache) {
            io.err(`contract simulate: ${cache.error}\n`);
            return EXIT_ENVIRONMENT;
        }

        const project = await prepareProject(dir, {
            runtimeDir, cacheDir: cache.root.dir, onWait: (what) => io.err(`waiting for ${what} ...\n`), sandbox: sandbox as SimulatorSandboxChoice | undefined,
        });
        if (!('build' in project)) {
            if (project.sandboxError) {
                io.err(`contract simulate: ${project.sandboxError}\n`);
                return EXIT_ENVIRONMENT;
            }
            for (const d of project.modelErrors) io.err(`${safeName(displayPath(io.cwd, join(dir, d.file)))}:${d.line}:${d.column}: error: ${d.message} [${d.code}]\n`);
            if (project.modelErrors.length) {
                io.err(`contract simulate: the model has ${project.modelErrors.length} error(s): fix them first (\`contract check\` shows the model's own; a linked import, refused here as in a build, it shows as warning import-link)\n`);
                return EXIT_USAGE;
            }
            if (project.compile?.diagnostics.length) {
                // the project's C did not compile: told as `contract build` tells it, at the files of DIR/src-gen and their regions
                const dirArg = parsed.positionals[0]!;
                for (const d of project.compile.diagnostics) io.err(formatGccDiagnostic(d, dirArg));
                for (const l of project.compile.other) io.err(`${l}\n`);
                io.err(`contract simulate: cannot ${project.compile.stage === 'link' ? 'link' : 'compile'} the simulator: ${errorCount(project.compile)} error(s) in your C (above; your code is in the PROTECTED REGION blocks of ${safeName(join(dirArg, 'src-gen'))} and in any file of your own there)\n`);
                return EXIT_FAILURE;
            }
            io.err(`contract simulate: ${project.buildError}\n`);
            return EXIT_FAILURE;
        }
        for (const w of project.warnings) io.err(`warning: ${w}\n`);

        // every scenario is read and checked before any runs (its diagnostics first: nothing runs when
        // one has errors); then they run and are reported one at a time, each one's parsed steps (an
        // 8 MiB scenario's take some 210 MB: a large one is parsed again when its turn comes, unless it is the only one) and
        // records let go once its report is written, so that many long scenarios take no more
        // memory than the longest one
        const scenarios: ToRun[] = [];
        let bad = 0;
        for (const arg of parsed.positionals.slice(1)) {
            const file = resolve(io.cwd, arg);
            const display = displayPath(io.cwd, file);
            // in messages and the text report the name is escaped (a newline in it cannot forge a line); json and junit keep it raw
            const shown = safeName(display);
            const text = readScenarioFile(file);
            if (typeof text !== 'string') {
                io.err(`${shown}: error: cannot read this scenario: ${text.error}\n`);
                bad++;
                continue;
            }
            const named = format === 'text' ? shown : display;
            const s = loadScenario(file, named, text, project.index);
            for (const d of s.diagnostics) io.err(`${shown}:${d.line}:${d.column}: ${d.severity}: ${d.message} [${d.code}]\n`);
            if (s.diagnostics.some((d) => d.severity === 'error')) bad++;
            // kept parsed when small, or when it is the command's only scenario (nothing else is checked meanwhile)
            else scenarios.push({ file, named, text, ...(text.length <= KEEP_PARSED_CHARS || parsed.positionals.length === 2 ? { loaded: s } : {}) });
        }
        if (bad) {
            io.err(`contract simulate: ${bad} scenario file(s) with errors: nothing was simulated\n`);
            return EXIT_USAGE;
        }
        const verbose = parsed.options.get('verbose') === true;
        // written in parts (whole lines): the report of a scenario of many steps is never one string
        const write = async (part: string): Promise<void> => {
            io.out(part);
            await io.drained?.();
        };
        const trace = typeof traceOption === 'string' ? new SimulationTrace(resolve(io.cwd, traceOption)) : undefined;
        // a trace file that cannot be written is said before the scenarios run (as contract run does), not after them
        const unwritable = await trace?.open();
        if (unwritable) {
            io.err(`contract simulate: cannot write the trace to ${safeName(unwritable.file)}: ${unwritable.message}\n`);
            return EXIT_FAILURE;
        }
        const suites: JunitSuite[] = [];
        let passed = 0;
        let failed = 0;
        // An async function keeps its temporaries in its frame across its awaits (V8): a scenario's
        // parse handed to its run, or its result, held by the loop's frame, stayed in memory while
        // the next scenario ran (two 8 MiB scenarios took 2.1 GB). So the run starts in a plain
        // function (its frame gone when it returns: the run keeps what it needs of the steps), and each
        // scenario is run and reported in a function of its own, whose frame is gone before the next.
        const startRun = (next: ToRun): Promise<ScenarioResult> => {
            const loaded = next.loaded ?? loadScenario(next.file, next.named, next.text, project.index);
            next.loaded = undefined;
            return runLoadedScenario(project, loaded);
        };
        const runAndReport = async (next: ToRun): Promise<void> => {
            const r = await startRun(next);
            if (r.passed) passed++;
            else failed++;
            if (format === 'json') for (const part of jsonScenarioParts(r, passed + failed === 1)) await write(part);
            else if (format === 'junit') suites.push(junitSuite(r));
            else for (const part of textScenarioParts(r, { verbose })) await write(part);
            await trace?.add(r);
        };
        if (format === 'json') await write(JSON_REPORT_HEAD);
        for (let next = scenarios.shift(); next; next = scenarios.shift()) await runAndReport(next);
        await write(format === 'json' ? JSON_REPORT_END : format === 'junit' ? junitReportOf(suites) : textSummary(passed, failed));
        const traceError = await trace?.close();
        if (traceError) {
            io.err(`contract simulate: cannot write the trace to ${safeName(traceError.file)}: ${traceError.message}\n`);
            return EXIT_FAILURE;
        }
        return failed === 0 ? EXIT_OK : EXIT_FAILURE;
    },
};

/** A scenario checked, waiting for its turn: parsed already when it is small (KEEP_PARSED_CHARS). */
interface ToRun {
    file: string;
    named: string;
    text: string;
    loaded?: LoadedScenario;
}

/** Scenarios up to this many characters stay parsed from their check to their run; a larger one is parsed again (unless it is the only one). */
const KEEP_PARSED_CHARS = 256 * 1024;

/**
 * `--trace FILE`: each scenario's records written once it has run (the file opened at the first),
 * some thousands of lines at a time (the file is toJsonLines of them all, never one string). A
 * write that fails stops the trace and is said at the end (close), after the reports.
 */
class SimulationTrace {
    private handle: FileHandle | undefined;
    private error: Error | undefined;
    private unlock: (() => void) | undefined;

    constructor(private readonly file: string) {}

    /** Takes the file's writer lock (lockTraceFile) and opens (creates or empties) the file now; the fault, if it cannot be. */
    async open(): Promise<{ file: string; message: string } | undefined> {
        try {
            this.unlock ??= lockTraceFile(this.file);
            this.handle ??= await openTraceFile(this.file, { empty: true });
            return undefined;
        } catch (e) {
            return { file: this.file, message: (e as Error).message };
        }
    }

    async add(r: ScenarioResult): Promise<void> {
        if (this.error) return;
        try {
            const { stepsToTrace, traceStepOf } = await import('@contract-studio/simulator/trace');
            this.handle ??= await openTraceFile(this.file, { empty: true });
            const records = stepsToTrace(r.steps.map(traceStepOf), r.file);
            for (let i = 0; i < records.length; i += TRACE_LINES_PER_WRITE) await this.handle.write(toJsonLines(records.slice(i, i + TRACE_LINES_PER_WRITE)));
        } catch (e) {
            this.error = e as Error;
        }
    }

    /** Closes the file (made empty when no scenario ran); the first fault, if any. */
    async close(): Promise<{ file: string; message: string } | undefined> {
        try {
            this.handle ??= this.error ? undefined : await openTraceFile(this.file, { empty: true });
        } catch (e) {
            this.error ??= e as Error;
        }
        await this.handle?.close().catch((e: Error) => (this.error ??= e));
        this.unlock?.();
        return this.error ? { file: this.file, message: this.error.message } : undefined;
    }
}
