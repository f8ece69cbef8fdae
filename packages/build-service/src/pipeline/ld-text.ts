/**
 * GNU ld's errors (a link that fails: a function the user's code calls that nobody defines, one
 * defined twice), read from untrusted build output as gcc's own diagnostics are (gcc-text.ts): a
 * hand-written scan, linear in the line's length, on no more than SERVICE_BOUNDS.parsedLineChars
 * characters, that never throws. gcc hands the link to ld, whose lines have a format of their own:
 *
 *   /usr/bin/ld: module.o: in function `_init_module':          (what the next errors are in)
 *   /work/…/module.c:242: undefined reference to `calibrate_arm'   (file:line from the debug info)
 *   /usr/bin/ld: /work/…/module.c:250: undefined reference to `calibrate_arm'
 *   /usr/bin/ld: b.o:/work/…/d.h:1: multiple definition of `g'; a.o:/work/…/d.h:1: first defined here
 *   /usr/bin/ld: module.o:module.c:(.text+0x16): undefined reference to `x'   (no debug info: no line)
 *   /usr/bin/ld: cannot find -lfoo: No such file or directory
 *   /usr/bin/ld: warning: …
 *
 * The file and line come from the objects' debug information (`-g`): a build without it gives no
 * line, and the error is told without a place.
 */
import { SERVICE_BOUNDS } from '../limits.js';
import { located, type DiagnosticContext, type GccDiagnostic } from './gcc-diagnostics.js';
import { cutText, digitsEnd } from './gcc-text.js';
import { withOrphanHint } from './orphan-hints.js';

/** What one line of ld's output says. */
export type LinkerLine =
  | { kind: 'function'; name: string }
  | { kind: 'diagnostic'; diagnostic: GccDiagnostic };

/** The errors whose place (`file:line: `) ld writes before them. */
const PLACED_MESSAGES = ['undefined reference to ', 'multiple definition of '] as const;
const FIRST_DEFINED = ': first defined here';
/** A program name longer than this is not ld's. */
const MAX_PROGRAM_CHARS = 256;
const MAX_DIGITS = 9;

/** `/usr/bin/ld: `, `ld: `, `x86_64-linux-gnu-ld.bfd: `: the length of the prefix, 0 when there is none. */
function programPrefix(s: string): number {
  const c = s.indexOf(': ');
  if (c <= 0 || c > MAX_PROGRAM_CHARS) return 0;
  const program = s.slice(0, c);
  if (program.includes(' ')) return 0;
  const base = program.slice(program.lastIndexOf('/') + 1);
  const dot = base.indexOf('.');
  const name = dot === -1 ? base : base.slice(0, dot);
  return name === 'ld' || name.endsWith('-ld') ? c + 2 : 0;
}

/** `[obj:]file:line` -> its file and line; `[obj:]file:(.text+0x16)` -> its file, no line. */
export function place(loc: string): { file: string; line: number | null } | null {
  const c = loc.lastIndexOf(':');
  if (c <= 0) return null;
  const tail = loc.slice(c + 1);
  let file = loc.slice(0, c);
  // an object or archive member before the source file (`a.o:`, `lib.a(x.o):`)
  const inner = file.lastIndexOf(':');
  if (inner !== -1) file = file.slice(inner + 1);
  if (!file) return null;
  if (tail.startsWith('(') && tail.endsWith(')')) return { file, line: null };
  if (!tail || tail.length > MAX_DIGITS || digitsEnd(tail, 0) !== tail.length) return null;
  return { file, line: Number(tail) };
}

function diagnosticAt(severity: GccDiagnostic['severity'], message: string, loc: string, ctx: DiagnosticContext): GccDiagnostic {
  const max = SERVICE_BOUNDS.diagnosticTextChars;
  // a function defined only in an orphans copy of the project: where it went (orphan-hints.ts)
  message = withOrphanHint(cutText(message, max), ctx.orphanedDefinitions);
  const p = place(loc);
  if (!p || p.line === null) {
    // no line (no debug info): the place as ld wrote it, in the message
    const where = p ? ` (in ${cutText(p.file, max)})` : '';
    return { severity, message: `${message}${where}`, file: null, line: null, column: null, protectedRegion: null, children: [] };
  }
  return located({ severity, message, line: p.line, column: null, children: [] }, cutText(p.file, max), ctx);
}

/**
 * Reads one line of a link's output; null when it is not ld's (gcc's own lines, make's, a
 * program's). `function`: the function the errors that follow are in.
 */
export function parseLinkerLine(line: string, ctx: DiagnosticContext): LinkerLine | null {
  const s = line.length > SERVICE_BOUNDS.parsedLineChars ? line.slice(0, SERVICE_BOUNDS.parsedLineChars) : line;
  const prefix = programPrefix(s);
  const rest = s.slice(prefix);
  if (prefix && rest.endsWith("':")) {
    const at = rest.lastIndexOf(': in function `');
    if (at !== -1) return { kind: 'function', name: cutText(rest.slice(at + 15, -2), SERVICE_BOUNDS.diagnosticTextChars) };
  }
  for (const message of PLACED_MESSAGES) {
    const at = rest.indexOf(`: ${message}`);
    if (at <= 0) continue;
    let text = rest.slice(at + 2);
    let children: GccDiagnostic[] = [];
    if (message === 'multiple definition of ' && text.endsWith(FIRST_DEFINED)) {
      const semi = text.indexOf('; ');
      if (semi !== -1) {
        children = [diagnosticAt('note', 'first defined here', text.slice(semi + 2, -FIRST_DEFINED.length), ctx)];
        text = text.slice(0, semi);
      }
    }
    const d = diagnosticAt('error', text, rest.slice(0, at), ctx);
    return { kind: 'diagnostic', diagnostic: { ...d, children } };
  }
  if (!prefix || !rest) return null;
  // ld's other lines (cannot find -lx, final link failed, warnings): told without a place
  const warning = rest.startsWith('warning: ');
  const message = warning ? rest.slice('warning: '.length) : rest;
  return { kind: 'diagnostic', diagnostic: diagnosticAt(warning ? 'warning' : 'error', message, '', ctx) };
}

/** `d` with the function ld said it is in (`in function` line before it), for an undefined reference. */
function inFunction(d: GccDiagnostic, fn: string | undefined): GccDiagnostic {
  if (!fn || !d.message.startsWith('undefined reference to ')) return d;
  return { ...d, message: `${d.message} (in function ${fn})` };
}

/**
 * Reads a link's errors line after line, as the build's router and the simulator's link do: ld
 * names the function of the next errors once, on its `in function` line (forgotten at a line that
 * is not ld's), and tells a reference again for every use of it, so each error is told once (the
 * first `max` remembered: hostile output keeps no more).
 */
export class LinkErrorReader {
  /** The function ld said the next errors are in. */
  private fn: string | undefined;
  private readonly told = new Set<string>();

  constructor(private readonly max = SERVICE_BOUNDS.diagnosticsPerJob) {}

  /** The error of one line (parseLinkerLine's reading; null: not ld's) with the function it is in; null for other lines. */
  read(line: LinkerLine | null): GccDiagnostic | null {
    if (!line) this.fn = undefined;
    else if (line.kind === 'function') this.fn = line.name;
    else return inFunction(line.diagnostic, this.fn);
    return null;
  }

  /** Whether the error `key` (its rendering as told) is new: false when it was told before. */
  first(key: string): boolean {
    if (this.told.has(key)) return false;
    if (this.told.size < this.max) this.told.add(key);
    return true;
  }
}
