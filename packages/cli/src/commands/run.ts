/**
 * `contract run DIR [--duration 10s] [--start 'SUP.function(p={...})'] [--logs OUT] [--sandbox ...]`:
 * builds the project like `contract build`, runs the architecture for the duration (Seam 5: the
 * generated `make run` and the runtime's launcher), prints every module's output tagged with its
 * name, writes the CSV logs the build service collected from the sandbox (any sandbox, docker included) to OUT (default DIR/logs),
 * with `--trace FILE` their records as JSON lines as they arrive (docs/build-service-api.md "Trace channel";
 * docs/runtime-api.md "Trace records"), and exits non-zero when a module crashed
 * (1) or when the run did not go as designed (4: a limit hit, a module stuck, output or logs cut; docs/ci.md).
 */
import { constants, promises as fsp } from 'node:fs';
import { join, resolve } from 'node:path';
import { Readable } from 'node:stream';
import { pipeline } from 'node:stream/promises';
import { createGunzip } from 'node:zlib';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, UsageError, type CliIO, type Command } from '../command.js';
import type { RunArtifacts } from '@contract-studio/build-service';
import type { JobEvent } from '@contract-studio/build-service';
import { LiveTrace, settleTraceFile } from '../live-trace.js';
import { COMMON_FLAGS, COMMON_USAGE, COMMON_VALUED, EXIT_TABLE, onTerminal, parseJobOptions, reportBuild, runJob, type JobOutcome } from '../job-runner.js';
import { isCpuList } from '@contract-studio/conventions';

/** `10s`, `500ms`, `2m`, `1.5` (seconds) -> seconds. */
export function parseDuration(text: string): number {
    const m = /^(\d+(?:\.\d+)?)(ms|s|m)?$/.exec(text.trim());
    if (!m) throw new UsageError(`bad duration '${text}' (expected e.g. 10s, 500ms, 2m)`);
    const value = Number(m[1]) * (m[2] === 'ms' ? 0.001 : m[2] === 'm' ? 60 : 1);
    if (!(value > 0)) throw new UsageError(`the duration must be positive (got '${text}')`);
    return value;
}

/** `--cpus` list: `1`, `0-1`, `0,2` (contract-launch checks the CPUs exist on the machine that runs). */
export function checkCpus(text: string): string {
    if (!isCpuList(text)) throw new UsageError(`bad --cpus '${text}' (expected a CPU list such as 1, 0-1 or 0,2)`);
    return text;
}

/** `SUP.function(...)` or empty (start nothing). */
export function checkStart(text: string): string {
    if (text === '') return text;
    if (!/^[A-Za-z_]\w*\.[A-Za-z_]\w*(\(.*\))?$/s.test(text) || /[\n\0]/.test(text)) {
        throw new UsageError(`bad --start '${text}' (expected SUPERVISOR.function(param={...}) e.g. GLB.mission(consigne={1.0,2.0,3.0}), or '' to start nothing)`);
    }
    return text;
}

export interface ModuleFailure {
    module: string;
    how: string;
}

/** Module crashes reported by the launcher (`FAILED: module X crashed`, with the preceding exit/signal line). */
export function moduleFailures(lines: JobOutcome['runLines']): ModuleFailure[] {
    const how = new Map<string, string>();
    const failed: ModuleFailure[] = [];
    for (const { source, line } of lines) {
        if (source !== 'launcher') continue;
        const exit = /^module (\S+) \(pid \d+\) (exited with status \d+|died by signal .*)$/.exec(line);
        if (exit) how.set(exit[1]!, exit[2]!);
        const crash = /^FAILED: module (\S+) crashed/.exec(line);
        if (crash) failed.push({ module: crash[1]!, how: how.get(crash[1]!) ?? 'crashed' });
    }
    return failed;
}

/**
 * Why the default logs folder (DIR/logs) cannot be written, or null. It is a name in the project
 * folder, which is not trusted (a cloned repository can hold any symlink): a link there would have
 * the run's CSV files written wherever it points. A folder the user names with --logs is theirs to
 * choose, link or not.
 */
async function refusedDefaultLogs(logsDir: string): Promise<string | null> {
    const st = await fsp.lstat(logsDir).catch(() => null);
    if (!st || st.isDirectory()) return null;
    if (st.isSymbolicLink()) {
        const target = await fsp.readlink(logsDir).catch(() => '?');
        return `${logsDir} is a symbolic link (to ${target}): the CSV logs are not written through a link found in the project folder; remove it, or name a folder with --logs OUT`;
    }
    return `${logsDir} is not a folder: remove it, or name a folder with --logs OUT`;
}

/**
 * Writes the run's CSV logs, as the build service collected them out of the sandbox (any sandbox:
 * `job.artifacts`), into `to`; never writes through a link found there (the folder itself, when
 * `noFollowDir`, opened O_NOFOLLOW and written through its descriptor: a link put there during the
 * run is not followed either).
 */
async function saveLogs(artifacts: RunArtifacts | null, to: string, noFollowDir: boolean): Promise<string[]> {
    const saved: string[] = [];
    const files = (artifacts?.files ?? []).filter((f) => /^[\w.-]+\.csv$/.test(f.name));
    if (!files.length) return saved;
    await fsp.mkdir(to, { recursive: true });
    const dir = await fsp.open(to, constants.O_RDONLY | constants.O_DIRECTORY | (noFollowDir ? constants.O_NOFOLLOW : 0));
    try {
        for (const file of files) {
            const handle = await fsp.open(`/proc/self/fd/${dir.fd}/${file.name}`, constants.O_WRONLY | constants.O_CREAT | constants.O_TRUNC | constants.O_NOFOLLOW, 0o644);
            // kept gzip-compressed by the service (an hour of logs is hundreds of MB): inflated as it is written
            await pipeline(Readable.from([file.gzip]), createGunzip(), handle.createWriteStream());
            saved.push(file.name);
        }
    } finally {
        await dir.close().catch(() => {});
    }
    return saved.sort();
}

export const runCommand: Command = {
    name: 'run',
    summary: 'build a Cactal project, run its architecture for a while, collect the CSV logs',
    usage: [
        'usage: contract run DIR [--duration 10s] [--start \'SUP.function(p={...})\'] [--logs OUT] [--trace FILE.jsonl] [--cpus LIST] [--realtime] [--sandbox auto|bwrap|docker|none] [--format text|json] [--runtime PATH] [--verbose]',
        '  --duration: how long the architecture runs (default 10s; e.g. 500ms, 30s, 2m); then every module is stopped',
        '  --start: the supervisor start request (default: the top supervisor\'s first function with its default parameters; \'\' starts nothing)',
        '  --cpus: pin every module to these CPUs (e.g. 1, 0-1; default: the system places them) — steadier periods',
        '  --realtime: modules take their SCHED_FIFO priorities in the sandbox, bounded so that a runaway loop cannot freeze the machine (docs/sandbox.md "Real-time mode"); refused, saying why, where the host cannot grant it',
        '  --logs: folder the CSV logs (one per module) are copied to (default DIR/logs, never a link found there; collected from every sandbox, docker included)',
        '  --trace: also write the records of those logs to FILE as JSON lines, in time order, as the run writes them (the live trace channel; as `contract trace --format json`)',
        ...COMMON_USAGE,
        '  module output is printed as `[MODULE] line`, launcher lines as they come',
        EXIT_TABLE,
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const parsed = parseArgs(args, [...COMMON_VALUED, 'duration', 'start', 'logs', 'cpus', 'trace'], [...COMMON_FLAGS, 'realtime']);
        const opts = await parseJobOptions(parsed, io, onTerminal());
        const durationOption = parsed.options.get('duration');
        const duration = typeof durationOption === 'string' ? parseDuration(durationOption) : 10;
        const startOption = parsed.options.get('start');
        const start = typeof startOption === 'string' ? checkStart(startOption) : undefined;
        const cpusOption = parsed.options.get('cpus');
        const cpus = typeof cpusOption === 'string' ? checkCpus(cpusOption) : undefined;
        const realtime = parsed.options.get('realtime') === true;
        const logsOption = parsed.options.get('logs');
        const logsDir = typeof logsOption === 'string' ? resolve(io.cwd, logsOption) : join(opts.dir, 'logs');
        const defaultLogs = typeof logsOption !== 'string';
        // said before the run, not after it
        const refused = defaultLogs ? await refusedDefaultLogs(logsDir) : null;
        if (refused) {
            io.err(`contract run: ${refused}\n`);
            return EXIT_FAILURE;
        }
        const traceOption = parsed.options.get('trace');
        const traceFile = typeof traceOption === 'string' ? resolve(io.cwd, traceOption) : null;

        let live: LiveTrace | null = null;
        if (traceFile) {
            try {
                live = await LiveTrace.open(traceFile);
            } catch (e) {
                io.err(`contract run: cannot write the trace to ${traceFile}: ${(e as Error).message}\n`);
                return EXIT_FAILURE;
            }
        }
        const onEvent = live ? (e: JobEvent) => live.event(e) : undefined;
        const outcome = await runJob(opts, { action: 'run', duration, ...(start !== undefined ? { start } : {}), ...(cpus !== undefined ? { cpus } : {}), ...(realtime ? { realtime } : {}) }, io, undefined, onEvent);
        if ('error' in outcome) {
            await live?.close().catch(() => {});
            io.err(`contract run: ${outcome.error}\n`);
            return outcome.exitCode;
        }
        const artifacts = outcome.job.artifacts;
        let logs: string[];
        try {
            logs = await saveLogs(artifacts, logsDir, defaultLogs);
        } catch (e) {
            io.err(`contract run: cannot write the CSV logs to ${logsDir}: ${(e as Error).message}\n`);
            return EXIT_FAILURE;
        }
        let trace: { file: string; records: number } | null = null;
        if (traceFile && live) {
            try {
                // written live; rewritten from the collected logs when the live channel was not
                // the whole story in order (docker, its kept-lines bound, records sent late):
                // both compared by digest, the logs read as a stream (a long run is gigabytes)
                const digest = await live.close();
                const whole = await settleTraceFile(logsDir, logs, traceFile, { digest, records: live.records });
                if (typeof whole === 'string') throw new Error(whole);
                trace = { file: traceFile, records: whole.records };
            } catch (e) {
                io.err(`contract run: cannot write the trace to ${traceFile}: ${(e as Error).message}\n`);
                return EXIT_FAILURE;
            }
        }
        const leftovers = artifacts?.runDirLeftovers ?? [];
        const leftOut = artifacts?.skipped ?? [];
        const failures = moduleFailures(outcome.runLines);
        const extra = { logsDir: logs.length ? logsDir : null, logs, logsLeftOut: leftOut, moduleFailures: failures, runDirLeftovers: leftovers, trace, output: outcome.runLines };
        const code = reportBuild(opts, outcome, io, extra);
        if (opts.format === 'text') {
            for (const f of failures) io.err(`module ${f.module} crashed (${f.how})\n`);
            if (leftovers.length) io.err(`warning: the run left files in its run directory: ${leftovers.join(', ')}\n`);
            for (const s of leftOut) if (!s.bound) io.err(`warning: log ${s.name} not collected: ${s.reason}\n`);
            for (const i of outcome.result.issues ?? []) io.err(`problem: ${i.message}\n`);
            if (logs.length) io.err(`CSV logs: ${logs.length} file(s) in ${logsDir}\n`);
            if (trace) io.err(`trace: ${trace.records} record(s) in ${trace.file}\n`);
        }
        if (outcome.result.limitHit) return code;
        return failures.length ? EXIT_FAILURE : code;
    },
};
