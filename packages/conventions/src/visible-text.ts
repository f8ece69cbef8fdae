/**
 * Text that came from a sandboxed program or a log folder (a module's output line, a log's file
 * name), shown as it reads, one line: the IDE's Build & Run lines, Explorer names and Monitor run
 * labels, and the build service's job text log (GET /api/jobs/:id/log), where a line break would
 * begin a line that reads as the service's and an ESC or CSI would act on the terminal of whoever
 * reads it with curl: a bidirectional override or isolate (U+202A–U+202E, U+2066–U+2069), a
 * directional mark, a line or paragraph separator and any control character but a tab are written
 * `\u202e` and so on, as the CLI writes them. Shown raw, `…\u202e BIDI evil`
 * read "live IDIB", and a log name with one reversed the rest of the Monitor's run label.
 */
const INVISIBLE_OR_REORDERING = /[\x00-\x08\x0a-\x1f\x7f-\x9f\u061c\u200e\u200f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g;

export function visibleText(text: string): string {
  return text.replace(INVISIBLE_OR_REORDERING, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}
