/**
 * Terminal-safe output. Text that reaches the user's terminal may come from a sandbox (module and
 * make output, gcc messages) or from a project (file names, identifiers); a control character in it
 * would be interpreted by the terminal (OSC retitles it, CSI clears it or moves the cursor, a bare CR
 * overwrites the line, C1 \x9b is an 8-bit CSI; a bidi override or a directional mark reorders it). Every
 * such character except tab and newline is therefore written as a visible `\uXXXX` escape, by the
 * conventions' visibleText, the IDE's rule too (packages/cli/README.md, "Terminal output").
 *
 * The same spelling is a JSON string escape: `--format json` output, where JSON.stringify has already
 * escaped C0 but leaves DEL and C1 raw, stays valid JSON that parses back to the raw text.
 */
import { visibleText } from '@contract-studio/conventions';
import type { CliIO } from './command.js';

/**
 * Everything the CLI prints: the conventions' visibleText, its newlines kept (every other control
 * character but a tab, DEL, C1, U+2028/9, the bidi embeddings, overrides and isolates and the
 * directional marks, which reorder what follows on the terminal's line, are written `\uXXXX`).
 */
export function escapeControls(text: string): string {
    return visibleText(text, { keepNewlines: true });
}

/**
 * A name that comes from a project or a sandbox (a file name, a module's output file, a path
 * typed into a model) as it is printed inside a CLI message: every character that could start a
 * line of its own, shift it or reorder it (newline, tab, CR, every other C0/C1 control, DEL,
 * U+2028/9, the bidi overrides and isolates and the directional marks U+200E, U+200F, U+061C) is
 * written `\uXXXX`. A file named `x\nok: run finished` cannot forge a status line. The one helper
 * every command uses for such names (README "Terminal output"): the conventions' visibleText, the
 * IDE's and the job log's rule, with tabs escaped too.
 */
export function safeName(name: string): string {
    return visibleText(name, { escapeTab: true });
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
