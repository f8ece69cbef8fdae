/** What every `contract` sub-command provides. One file per command in `src/commands/`. */

/** Where a command writes; tests capture it, the bin uses process streams. */
export interface CliIO {
    out(text: string): void;
    err(text: string): void;
    /** Directory relative paths are resolved from. */
    cwd: string;
    /** Aborted when the standard output's reader went away (a pipe closed: `| head`); writes to it are then dropped. */
    outputClosed?: AbortSignal;
    /** Resolves when what `out` was given has gone to the reader (or it went away): a command
     *  printing gigabytes (`contract trace --format json`) waits on it rather than buffer them. */
    drained?: () => Promise<void>;
}

export interface Command {
    name: string;
    /** One line for `contract --help`. */
    summary: string;
    /** Usage text for `contract <name> --help` and usage errors. */
    usage: string;
    /** Runs the command; resolves to the process exit code. */
    run(args: string[], io: CliIO): Promise<number>;
}

/** Exit codes shared by all commands. */
export const EXIT_OK = 0;
export const EXIT_FAILURE = 1;
export const EXIT_USAGE = 2;

/** A usage error: the dispatcher prints the message and the command's usage, exit code 2. */
export class UsageError extends Error {}
