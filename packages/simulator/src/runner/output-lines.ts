/**
 * What the user's functions printed during a step (a step record's `output`: a compute or test
 * function's printf, a type's print_), as the text report shows it under the step
 * (docs/simulation.md §3): one line of the report per line printed, marked `output|`. It is the
 * project's C that wrote it, so it is made safe for a terminal as the CLI makes module output safe
 * (packages/cli README "Terminal output": every control character but tab written `\uXXXX`, so an
 * escape sequence shows as text and a bare CR cannot overwrite the report's line) and bounded
 * (long lines cut, a few lines a step: `--format json` keeps the step's whole output).
 */
import { visibleText } from '@contract-studio/conventions';

export interface OutputBounds {
    /** Characters of one printed line shown; the rest is counted. */
    lineChars: number;
    /** Printed lines shown per step; the others are counted. */
    linesPerStep: number;
}

export const OUTPUT_BOUNDS: OutputBounds = { lineChars: 240, linesPerStep: 20 };

/** C0 but tab, DEL, C1, the separators, marks, bidi embeddings, overrides and isolates, the characters of no width: the CLI's rule (conventions' visibleText). */
function escaped(text: string): string {
    return visibleText(text);
}

/** The report's lines for `output` (none when nothing was printed), each starting with `indent` then `output| `. */
export function outputLines(output: string | undefined, indent: string, bounds: OutputBounds = OUTPUT_BOUNDS): string[] {
    if (!output) return [];
    // a printf's own line end (also CRLF) ends a line; the last line end opens no empty line
    const lines = output.replace(/\r?\n$/, '').split(/\r?\n/);
    const out: string[] = [];
    for (const line of lines.slice(0, bounds.linesPerStep)) {
        // cut before escaping: the bound is on what was printed, and an escape is never split
        let keep = Math.min(line.length, bounds.lineChars);
        if (keep < line.length && /[\ud800-\udbff]/.test(line.charAt(keep - 1))) keep--; // not half a character
        const cut = keep < line.length ? ` [… ${line.length - keep} characters cut]` : '';
        out.push(`${indent}output| ${escaped(line.slice(0, keep))}${cut}`);
    }
    const more = lines.length - bounds.linesPerStep;
    if (more > 0) out.push(`${indent}output| … ${more} more line${more === 1 ? '' : 's'} (--format json has the step's whole output)`);
    return out;
}
