/**
 * `contract build DIR [--sandbox auto|bwrap|docker|none] [--format text|json]`: generates and
 * compiles a Cactal project in a sandbox through the job runner (job-runner.ts).
 */
import { parseArgs } from '../args.js';
import type { CliIO, Command } from '../command.js';
import { CLI_BUILD_SECONDS, COMMON_FLAGS, COMMON_REPEATABLE, COMMON_USAGE, COMMON_VALUED, EXIT_TABLE, LIMIT_USAGE, onTerminal, parseJobOptions, parseLimitOptions, reportBuild, runJob } from '../job-runner.js';

export const buildCommand: Command = {
    name: 'build',
    summary: 'generate and compile a Cactal project in a sandbox (gcc + make)',
    usage: [
        'usage: contract build DIR [--werror] [--limit NAME=VALUE]... [--sandbox auto|bwrap|docker|none] [--format text|json] [--runtime PATH] [--cache-dir DIR] [--verbose]',
        '  generates DIR/src-gen (user code in protected regions kept) in a private copy and compiles it;',
        '  gcc diagnostics are printed against src-gen/ paths, naming the protected region they are in.',
        `  limits: the build step may take ${CLI_BUILD_SECONDS}s (the build service's default is 120s); the others are the service's defaults`,
        '          (memory 512 MiB, 256 processes, disk 256 MiB: docs/sandbox.md "Limits"); a build a limit stopped says so',
        ...LIMIT_USAGE,
        ...COMMON_USAGE,
        EXIT_TABLE,
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const parsed = parseArgs(args, COMMON_VALUED, COMMON_FLAGS, COMMON_REPEATABLE);
        const limitOptions = parseLimitOptions(parsed);
        const opts = await parseJobOptions(parsed, io, onTerminal());
        const werror = parsed.options.get('werror') === true;
        const outcome = await runJob(opts, { action: 'build', ...(werror ? { werror } : {}), ...(limitOptions ? { limitOptions } : {}) }, io);
        if ('error' in outcome) {
            io.err(`contract build: ${outcome.error}\n`);
            return outcome.exitCode;
        }
        return reportBuild(opts, outcome, io);
    },
};

