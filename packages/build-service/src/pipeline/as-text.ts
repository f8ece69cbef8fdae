/**
 * The assembler's errors (GNU as, which gcc runs on what it compiled: an `__asm__` statement of a
 * protected region with a wrong instruction), read from untrusted build output as gcc's and ld's
 * are (gcc-text.ts, ld-text.ts): linear, bounded to SERVICE_BOUNDS.parsedLineChars, never throws.
 *
 *   module.c: Assembler messages:                                   (no diagnostic)
 *   module.c:242: Error: no such instruction: `gripper_open'      (the C line gcc marked)
 *   /tmp/ccQ2.s:25: Error: …                                       (an assembly file of gcc's own)
 *
 * A line of gcc's temporary assembly file names nothing of the user's: told without a place.
 */
import { SERVICE_BOUNDS } from '../limits.js';
import { located, relativeToRoot, type DiagnosticContext, type GccDiagnostic } from './gcc-diagnostics.js';
import { cutText } from './gcc-text.js';
import { place } from './ld-text.js';

const KINDS = [
  { text: ': Error: ', severity: 'error' },
  { text: ': Warning: ', severity: 'warning' },
] as const;

/** One assembler error or warning, or null when the line is not the assembler's. */
export function parseAssemblerLine(line: string, ctx: DiagnosticContext): GccDiagnostic | null {
  const s = line.length > SERVICE_BOUNDS.parsedLineChars ? line.slice(0, SERVICE_BOUNDS.parsedLineChars) : line;
  for (const kind of KINDS) {
    const at = s.indexOf(kind.text);
    if (at <= 0) continue;
    const p = place(s.slice(0, at));
    if (!p || p.line === null) return null;
    const max = SERVICE_BOUNDS.diagnosticTextChars;
    const message = cutText(s.slice(at + kind.text.length), max);
    if (p.file.endsWith('.s') && relativeToRoot(p.file, ctx) === null) {
      return { severity: kind.severity, message: `${message} (in the assembly gcc made, line ${p.line})`, file: null, line: null, column: null, protectedRegion: null, children: [] };
    }
    return located({ severity: kind.severity, message, line: p.line, column: null, children: [] }, cutText(p.file, max), ctx);
  }
  return null;
}
