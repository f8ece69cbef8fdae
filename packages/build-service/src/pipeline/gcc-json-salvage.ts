/**
 * What is left of a gcc JSON diagnostics line that was cut (the output bounds: outputBytesPerStream,
 * gccJsonLineBytes): the text up to the last diagnostic that is complete, closed as JSON. gcc writes
 * one array per compilation, and gcc 12 nests a compilation's preprocessor diagnostics (`#warning`,
 * `#error`) and what follows them in the first one's `children`: a cut line is one unfinished
 * diagnostic holding hundreds of finished ones, the real error among them. A diagnostic is an object
 * of the top-level array or of a `children` array; the cut is made after the last one that closed,
 * every container still open is then closed, so the complete diagnostics parse (the open ones keep
 * the fields they had: gcc writes `kind` and `locations` first). One linear pass and one more to the
 * cut, no regular expression; the result is checked against the schema like any other line.
 */

/** Containers deeper than this are no gcc output: nothing is salvaged. */
const MAX_DEPTH = 64;

/** The JSON text of the complete diagnostics at the start of a cut line, or null when there is none. */
export function completeDiagnosticsPrefix(line: string): string | null {
  const end = lastDiagnosticEnd(line);
  if (end === null) return null;
  const closers = openContainers(line, end);
  if (closers === null) return null;
  // a "children" array or an object left with a trailing key: close what is open, innermost first
  return line.slice(0, end) + closers.reverse().map((c) => (c === '[' ? ']' : '}')).join('');
}

/** One scan's state: the open containers, each array marked when it holds diagnostics. */
interface Scan {
  stack: string[];
  /** For each open container: an array of diagnostics (the top level, or a `children` value). */
  holdsDiagnostics: boolean[];
  /** The top-level array closed: the line is whole. */
  closedTop: boolean;
}

/**
 * The index just past the last diagnostic object that closed in `line`; null when there is none,
 * when the brackets do not match, or when the line is not cut (its array closes: a whole line of
 * the wrong shape stays text).
 */
function lastDiagnosticEnd(line: string): number | null {
  let last: number | null = null;
  const state = scan(line, line.length, (i, closedObjectInDiagnostics) => {
    if (closedObjectInDiagnostics) last = i + 1;
  });
  return state && state.stack.length > 0 && !state.closedTop ? last : null;
}

/** The containers open at `end` (outermost first), or null when the text is not JSON-like there. */
function openContainers(line: string, end: number): string[] | null {
  const state = scan(line, end, () => {});
  return state ? state.stack : null;
}

/**
 * Walks `line` up to `end` (strings and escapes skipped), calling `closed` at every `}` with whether
 * that object was an element of an array of diagnostics. Null when the brackets do not match or go
 * deeper than MAX_DEPTH.
 */
function scan(line: string, end: number, closed: (i: number, diagnostic: boolean) => void): Scan | null {
  const state: Scan = { stack: [], holdsDiagnostics: [], closedTop: false };
  let inString = false;
  let stringStart = 0;
  let lastString = '';
  let key = '';
  for (let i = 0; i < end; i++) {
    const c = line.charCodeAt(i);
    if (inString) {
      if (c === 0x5c) i++; // backslash: the next character is escaped
      else if (c === 0x22) {
        inString = false;
        lastString = line.slice(stringStart, Math.min(i, stringStart + 16));
      }
      continue;
    }
    if (c === 0x22) {
      inString = true;
      stringStart = i + 1;
    } else if (c === 0x3a) {
      key = lastString; // `"key":`
    } else if (c === 0x5b || c === 0x7b) {
      if (state.stack.length >= MAX_DEPTH) return null;
      const top = state.stack.length === 0;
      state.holdsDiagnostics.push(c === 0x5b && (top || key === 'children'));
      state.stack.push(c === 0x5b ? '[' : '{');
      key = '';
    } else if (c === 0x5d || c === 0x7d) {
      const open = state.stack.pop();
      state.holdsDiagnostics.pop();
      if (open !== (c === 0x5d ? '[' : '{')) return null;
      if (c === 0x7d) closed(i, state.holdsDiagnostics[state.holdsDiagnostics.length - 1] === true);
      if (state.stack.length === 0) state.closedTop = true;
      key = '';
    } else if (c === 0x2c) {
      key = '';
    }
  }
  return state;
}
