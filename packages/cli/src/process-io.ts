/**
 * The bin's CliIO on the process's streams. A reader that goes away (`contract trace … | head`,
 * `contract run … | grep -m1 …`) makes the next write to the pipe fail with EPIPE; Node reports it
 * as an 'error' event which, unhandled, ended the command with a stack trace in the middle of its
 * work (a build's cache left mid-write, a run's sandbox stopped without its clean-up).
 *
 * Here a failed write closes that stream for the rest of the command: later writes to it are
 * dropped, the command goes on to its end and its exit status, and `outputClosed` is aborted when
 * it was the standard output, so that a command whose output is the point (a build or run job)
 * stops the way it does on Ctrl+C (packages/cli/README.md, "Exit status"). A failure other than a
 * closed pipe (a full disk) also makes the exit status 1 when the command's was 0.
 */
import type { CliIO } from './command.js';

export function makeProcessIO(
    stdout: NodeJS.WriteStream = process.stdout,
    stderr: NodeJS.WriteStream = process.stderr,
    cwd = process.cwd(),
    onFailedOutput: () => void = failTheProcess,
): CliIO {
    const closed = new AbortController();
    let outOpen = true;
    let errOpen = true;
    stdout.on('error', (e: NodeJS.ErrnoException) => {
        outOpen = false;
        // a closed pipe is the reader's choice; any other failure (a full disk) is said, and the
        // command does not exit 0: its output (a SARIF report, a trace) is not whole
        if (e.code !== 'EPIPE') {
            if (errOpen) stderr.write(`contract: cannot write the standard output (${e.code ?? e.message}): stopping\n`);
            onFailedOutput();
        }
        closed.abort();
    });
    stderr.on('error', () => {
        errOpen = false;
    });
    return {
        out: (text) => {
            if (outOpen) stdout.write(text);
        },
        err: (text) => {
            if (errOpen) stderr.write(text);
        },
        cwd,
        outputClosed: closed.signal,
        drained: () => (outOpen && stdout.writableNeedDrain ? drain(stdout, closed.signal) : Promise.resolve()),
    };
}

/** Resolves at the stream's next 'drain', or when its reader went away (no 'drain' comes then). */
function drain(stream: NodeJS.WriteStream, closed: AbortSignal): Promise<void> {
    return new Promise((resolve) => {
        const done = () => {
            stream.off('drain', done);
            stream.off('close', done);
            closed.removeEventListener('abort', done);
            resolve();
        };
        stream.on('drain', done);
        stream.on('close', done);
        closed.addEventListener('abort', done);
        if (closed.aborted) done();
    });
}

/**
 * The process ends with status 1 at the least. Set when it exits: the failed write's 'error' can
 * come after the command has returned its status (the last write of a report), which the bin then
 * has already taken as the exit code.
 */
function failTheProcess(): void {
    process.once('exit', () => {
        if (!process.exitCode) process.exitCode = 1;
    });
}
