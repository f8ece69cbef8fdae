/**
 * What is always written as its escape: every control but tab and newline, DEL, C1, the marks,
 * separators, overrides and isolates, and the characters of no width (U+200B–U+200D, the word
 * joiner U+2060, the BOM U+FEFF), which make two different values look the same.
 */
const ALWAYS_ESCAPED = '\\x00-\\x08\\x0b-\\x1f\\x7f-\\x9f\\u061c\\u200b-\\u200f\\u2028\\u2029\\u202a-\\u202e\\u2060\\u2066-\\u2069\\ufeff';

export interface VisibleTextOptions {
  /**
   * Write a tab `\u0009` too: where the text is a name inside a message, whose columns a tab would
   * shift (the CLI's names). A line shown on its own (an output line, a log line) keeps its tabs.
   */
  escapeTab?: boolean;
  /** Keep newlines: the text is many lines, each shown as one (all the CLI prints). */
  keepNewlines?: boolean;
}

const patterns = new Map<string, RegExp>();

function escapedPattern(options: VisibleTextOptions): RegExp {
  const key = `${options.escapeTab ? 't' : ''}${options.keepNewlines ? '' : 'n'}`;
  let pattern = patterns.get(key);
  if (!pattern) {
    pattern = new RegExp(`[${ALWAYS_ESCAPED}${options.escapeTab ? '\\t' : ''}${options.keepNewlines ? '' : '\\n'}]`, 'g');
    patterns.set(key, pattern);
  }
  return pattern;
}

/**
 * Text that came from a sandboxed program, a log folder or a project (a module's output line, a
 * log's file name, a project file's name), shown as it reads, one line: the IDE's Build & Run
 * lines, Explorer names and Monitor run labels, the build service's job text log (GET
 * /api/jobs/:id/log), and the names inside the CLI's messages (its safeName). A line break would
 * begin a line that reads as the service's or the CLI's, and an ESC or CSI would act on the
 * terminal of whoever reads it: a bidirectional override or isolate (U+202A–U+202E, U+2066–U+2069),
 * a directional mark (U+200E, U+200F, U+061C), a line or paragraph separator, a character of no
 * width (U+200B–U+200D, U+2060, U+FEFF) and any control character but a tab are written `\u202e`
 * and so on. Shown raw, `…\u202e BIDI evil` read "live IDIB", a log name with one reversed the
 * rest of the Monitor's run label, and `"go\u200b"` looked like `"go"`.
 */
export function visibleText(text: string, options: VisibleTextOptions = {}): string {
  return text.replace(escapedPattern(options), (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}
