/**
 * `contract run DIR [--duration 10s] [--start 'SUP.function(p={...})'] [--logs OUT] [--sandbox ...]`:
 * builds the project like `contract build`, runs the architecture for the duration (Seam 5: the
 * generated `make run` and the runtime's launcher), prints every module's output tagged with its
 * name, copies the CSV logs to OUT (default DIR/logs) and exits non-zero when a module crashed.
 */
import { constants, promises as fsp } from 'node:fs';
import { join, resolve } from 'node:path';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, UsageError, type CliIO, type Command } from '../command.js';
import { COMMON_FLAGS, COMMON_USAGE, COMMON_VALUED, EXIT_TABLE, onTerminal, parseJobOptions, reportBuild, runJob, type JobOutcome } from './build.js';

/** `10s`, `500ms`, `2m`, `1.5` (seconds) -> seconds. */
export function parseDuration(text: string): number {
    const m = /^(\d+(?:\.\d+)?)(ms|s|m)?$/.exec(text.trim());
    if (!m) throw new UsageError(`bad duration '${text}' (expected e.g. 10s, 500ms, 2m)`);
    const value = Number(m[1]) * (m[2] === 'ms' ? 0.001 : m[2] === 'm' ? 60 : 1);
    if (!(value > 0)) throw new UsageError(`the duration must be positive (got '${text}')`);
    return value;
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

/** Copies the regular files of `from` (never following links: the sandbox wrote them) into `to`. */
async function copyLogs(from: string, to: string): Promise<string[]> {
    const entries = await fsp.readdir(from, { withFileTypes: true }).catch(() => []);
    const copied: string[] = [];
    for (const entry of entries) {
        if (!entry.isFile() || !/^[\w.-]+\.csv$/.test(entry.name)) continue;
        const handle = await fsp.open(join(from, entry.name), constants.O_RDONLY | constants.O_NOFOLLOW).catch(() => undefined);
        if (!handle) continue;
        try {
            const data = await handle.readFile();
            await fsp.mkdir(to, { recursive: true });
            await fsp.writeFile(join(to, entry.name), data);
            copied.push(entry.name);
        } finally {
            await handle.close();
        }
    }
    return copied.sort();
}

/** The work folders of the service's workspaces (docs/sandbox.md: `<cache>/ws/<workspace>/work`). */
async function workDirs(cacheDir: string): Promise<string[]> {
    const ws = join(cacheDir, 'ws');
    const names = await fsp.readdir(ws).catch(() => [] as string[]);
    return names.map((n) => join(ws, n, 'work'));
}

export const runCommand: Command = {
    name: 'run',
    summary: 'build a Cactal project, run its architecture for a while, collect the CSV logs',
    usage: [
        'usage: contract run DIR [--duration 10s] [--start \'SUP.function(p={...})\'] [--logs OUT] [--sandbox auto|bwrap|docker|none] [--format text|json] [--runtime PATH] [--verbose]',
        '  --duration: how long the architecture runs (default 10s; e.g. 500ms, 30s, 2m); then every module is stopped',
        '  --start: the supervisor start request (default: the top supervisor\'s first function with its default parameters; \'\' starts nothing)',
        '  --logs: folder the CSV logs (one per module) are copied to (default DIR/logs; not available with --sandbox docker)',
        ...COMMON_USAGE,
        '  module output is printed as `[MODULE] line`, launcher lines as they come',
        EXIT_TABLE,
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const parsed = parseArgs(args, [...COMMON_VALUED, 'duration', 'start', 'logs'], COMMON_FLAGS);
        const opts = await parseJobOptions(parsed, io, onTerminal());
        const durationOption = parsed.options.get('duration');
        const duration = typeof durationOption === 'string' ? parseDuration(durationOption) : 10;
        const startOption = parsed.options.get('start');
        const start = typeof startOption === 'string' ? checkStart(startOption) : undefined;
        const logsOption = parsed.options.get('logs');
        const logsDir = typeof logsOption === 'string' ? resolve(io.cwd, logsOption) : join(opts.dir, 'logs');

        let logs: string[] = [];
        const leftovers: string[] = [];
        const outcome = await runJob(opts, { action: 'run', duration, ...(start !== undefined ? { start } : {}) }, io, async (_service, cacheDir, o) => {
            if (o.result.step !== 'run') return;
            for (const work of await workDirs(cacheDir)) {
                logs = logs.concat(await copyLogs(join(work, 'logs'), logsDir));
                for (const f of await fsp.readdir(join(work, 'run')).catch(() => [] as string[])) leftovers.push(f);
            }
        });
        if ('error' in outcome) {
            io.err(`contract run: ${outcome.error}\n`);
            return outcome.exitCode;
        }
        const failures = moduleFailures(outcome.runLines);
        const extra = { logsDir: logs.length ? logsDir : null, logs, moduleFailures: failures, runDirLeftovers: leftovers, output: outcome.runLines };
        const code = reportBuild(opts, outcome, io, extra);
        if (opts.format === 'text') {
            for (const f of failures) io.err(`module ${f.module} crashed (${f.how})\n`);
            if (leftovers.length) io.err(`warning: the run left files in its run directory: ${leftovers.join(', ')}\n`);
            if (logs.length) io.err(`CSV logs: ${logs.length} file(s) in ${logsDir}\n`);
            else if (outcome.result.step === 'run' && outcome.job.sandboxName === 'docker') io.err('CSV logs stay in the container volume with --sandbox docker (use bwrap or none to collect them)\n');
        }
        return failures.length && code === 0 ? EXIT_FAILURE : code;
    },
};
