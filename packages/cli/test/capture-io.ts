/** A CliIO that keeps what a command prints, for tests that call runCli in-process. */
import type { CliIO } from '../src/command.js';

export type CapturedIO = CliIO & { stdout: string; stderr: string };

export function capture(cwd: string): CapturedIO {
    const io: CapturedIO = {
        stdout: '',
        stderr: '',
        cwd,
        out(text: string) { io.stdout += text; },
        err(text: string) { io.stderr += text; },
    };
    return io;
}
