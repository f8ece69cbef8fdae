/**
 * Terminal-safe output. Text that reaches the user's terminal may come from a sandbox (module and
 * make output, gcc messages) or from a project (file names, identifiers); a control character in it
 * would be interpreted by the terminal (OSC retitles it, CSI clears it or moves the cursor, a bare CR
 * overwrites the line, C1 \x9b is an 8-bit CSI). Every control character except tab and newline is
 * therefore written as a visible `\uXXXX` escape (packages/cli/README.md, "Terminal output").
 *
 * The same spelling is a JSON string escape: `--format json` output, where JSON.stringify has already
 * escaped C0 but leaves DEL and C1 raw, stays valid JSON that parses back to the raw text.
 */
import type { CliIO } from './command.js';

/** C0 except \t (0x09) and \n (0x0a), DEL (0x7f) and C1 (0x80-0x9f). */
const CONTROL = /[\x00-\x08\x0b-\x1f\x7f-\x9f]/g;

export function escapeControls(text: string): string {
    return text.replace(CONTROL, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}

/** An io whose every write goes through escapeControls. */
export function terminalSafeIO(io: CliIO): CliIO {
    return {
        out: (text) => io.out(escapeControls(text)),
        err: (text) => io.err(escapeControls(text)),
        cwd: io.cwd,
        ...(io.outputClosed ? { outputClosed: io.outputClosed } : {}),
        ...(io.drained ? { drained: io.drained } : {}),
    };
}
