/**
 * gcc's text format `file:line[:col]: severity: message [-Woption]` (the fallback when a line is
 * not JSON), read from a sandbox's output. That output is untrusted and parsed on the service's
 * event loop: a backtracking regular expression for this format (lazy file, lazy message, optional
 * option) takes seconds on a crafted line, during which the service answers nobody. So this is a
 * hand-written scanner, linear in the line's length, on no more than
 * SERVICE_BOUNDS.parsedLineChars characters (docs/sandbox.md, "Limits"). It never throws.
 */
import { SERVICE_BOUNDS } from '../limits.js';
import { located, severityOf, type DiagnosticContext, type GccDiagnostic } from './gcc-diagnostics.js';

const KINDS = ['fatal error', 'error', 'warning', 'note'] as const;

/** Line and column numbers longer than this are not gcc's (and would not be exact numbers). */
const MAX_DIGITS = 9;

/** The characters JavaScript's `\s` matches (gcc only writes spaces, but the format allows any). */
function isSpace(code: number): boolean {
  return (
    code === 0x20 || (code >= 0x09 && code <= 0x0d) || code === 0xa0 || code === 0x1680 || (code >= 0x2000 && code <= 0x200a) ||
    code === 0x2028 || code === 0x2029 || code === 0x202f || code === 0x205f || code === 0x3000 || code === 0xfeff
  );
}

function isDigit(code: number): boolean {
  return code >= 0x30 && code <= 0x39;
}

/** End of the run of digits starting at i (i when there is none). */
export function digitsEnd(s: string, i: number): number {
  let j = i;
  while (j < s.length && isDigit(s.charCodeAt(j))) j++;
  return j;
}

function spacesEnd(s: string, i: number): number {
  let j = i;
  while (j < s.length && isSpace(s.charCodeAt(j))) j++;
  return j;
}

interface Head {
  lineNo: string;
  col: string | undefined;
  kind: (typeof KINDS)[number];
  /** Where the message starts. */
  rest: number;
}

/**
 * Matches `:line[:col]:<spaces>kind:<spaces>` at the colon `c`. The work is bounded by the digit
 * and space runs right after `c`, and each such run follows at most two colons, so trying every
 * colon of a line stays linear.
 */
function headAt(s: string, c: number): Head | null {
  const lineEnd = digitsEnd(s, c + 1);
  if (lineEnd === c + 1 || s.charCodeAt(lineEnd) !== 0x3a) return null;
  let afterNumbers = lineEnd + 1;
  let col: string | undefined;
  const colEnd = digitsEnd(s, afterNumbers);
  if (colEnd > afterNumbers && s.charCodeAt(colEnd) === 0x3a) {
    col = s.slice(afterNumbers, colEnd);
    afterNumbers = colEnd + 1;
  }
  const kindStart = spacesEnd(s, afterNumbers);
  if (kindStart === afterNumbers) return null;
  for (const kind of KINDS) {
    if (!s.startsWith(kind, kindStart) || s.charCodeAt(kindStart + kind.length) !== 0x3a) continue;
    const afterColon = kindStart + kind.length + 1;
    const rest = spacesEnd(s, afterColon);
    if (rest === afterColon) return null;
    return { lineNo: s.slice(c + 1, lineEnd), col, kind, rest };
  }
  return null;
}

/**
 * Splits a trailing ` [-Woption]` off a message: the earliest `[-W` that follows white space and
 * is followed by no `]` but the last character (what gcc prints after the message).
 */
function splitOption(message: string): { message: string; option?: string } {
  if (!message.endsWith(']')) return { message };
  const from = message.lastIndexOf(']', message.length - 2) + 1;
  for (let q = message.indexOf('[-W', Math.max(from, 1)); q !== -1; q = message.indexOf('[-W', q + 1)) {
    if (q + 3 > message.length - 2) break; // "-W" needs at least one more character
    if (!isSpace(message.charCodeAt(q - 1))) continue;
    let start = q - 1;
    while (start > 0 && isSpace(message.charCodeAt(start - 1))) start--;
    return { message: message.slice(0, start), option: message.slice(q + 1, -1) };
  }
  return { message };
}

/** `text` cut to `max` characters with a marker saying how many were left out. */
export function cutText(text: string, max: number): string {
  return text.length <= max ? text : `${text.slice(0, max)} [… ${text.length - max} characters cut]`;
}

/** Parses gcc's text format `file:line[:col]: severity: message [-Woption]` (fallback). */
export function parseGccTextLine(line: string, ctx: DiagnosticContext): GccDiagnostic | null {
  const cut = line.length > SERVICE_BOUNDS.parsedLineChars ? line.length - SERVICE_BOUNDS.parsedLineChars : 0;
  const s = cut ? line.slice(0, SERVICE_BOUNDS.parsedLineChars) : line;
  // the file name is the shortest prefix (at least one character) followed by a valid head
  let head: Head | null = null;
  let c = s.indexOf(':', 1);
  for (; c !== -1; c = s.indexOf(':', c + 1)) {
    head = headAt(s, c);
    if (head) break;
  }
  if (!head || c === -1) return null;
  const file = s.slice(0, c);
  if (file.includes(' ') && !file.includes('/')) return null;
  if (head.lineNo.length > MAX_DIGITS || (head.col?.length ?? 0) > MAX_DIGITS) return null;
  const { message, option } = cut ? { message: s.slice(head.rest) } : splitOption(s.slice(head.rest));
  const max = SERVICE_BOUNDS.diagnosticTextChars;
  return located(
    {
      severity: severityOf(head.kind),
      message: cut ? `${cutText(message, max)} [… ${cut} characters cut]` : cutText(message, max),
      ...(option ? { option: cutText(option, max) } : {}),
      line: Number(head.lineNo),
      column: head.col ? Number(head.col) : null,
      children: [],
    },
    cutText(file, max),
    ctx,
  );
}
