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

/** C0 except \t (0x09) and \n (0x0a), DEL (0x7f), C1 (0x80-0x9f), the line and paragraph separators and the bidi embeddings, overrides and isolates (U+202A-202E, U+2066-2069: they reorder what follows on the terminal's line). */
const CONTROL = /[\x00-\x08\x0b-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g;

export function escapeControls(text: string): string {
    return text.replace(CONTROL, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}

/**
 * Control characters, line and paragraph separators and bidirectional overrides: what may not
 * stand raw in a name printed inside a message (a newline would start a line of its own).
 */
const NAME_UNSAFE = /[\x00-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g;

/**
 * A name that comes from a project or a sandbox (a file name, a module's output file, a path
 * typed into a model) as it is printed inside a CLI message: every character that could start a
 * line of its own or move the text (newline, tab, CR, every other C0/C1 control, DEL, U+2028/9,
 * bidi overrides) is written `\uXXXX`. A file named `x\nok: run finished` cannot forge a status
 * line. The one helper every command uses for such names (README "Terminal output").
 */
export function safeName(name: string): string {
    return name.replace(NAME_UNSAFE, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
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
