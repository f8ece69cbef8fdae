/**
 * Git's merge conflict markers in a text (a generated file, a `.contract` file, the manifest): the
 * lines of an unresolved conflict, which the generator, the language and the IDE refuse to read as
 * code (docs/getting-started.md "Keeping a project in git"). A marker is a line that begins with
 * `<<<<<<<`, `|||||||` (diff3's base), `=======` or `>>>>>>>`, followed by a blank or the end of the
 * line (git writes `<<<<<<< HEAD`, `=======`, `>>>>>>> eng-b`). A lone `=======` line (a C comment's
 * rule) is no conflict: a text holds markers only when one of them opens or closes a conflict.
 */

export type ConflictMarkerKind = 'ours' | 'base' | 'separator' | 'theirs';

export interface ConflictMarker {
  /** 1-based line of the marker. */
  line: number;
  /** Offset of the line's first character in the text. */
  offset: number;
  /** Length of the marker line, its line ending excluded. */
  length: number;
  kind: ConflictMarkerKind;
}

const MARKER_LINE = /^(<{7}|\|{7}|={7}|>{7})(?=[ \t\r]|$)/gm;

const KIND: Record<string, ConflictMarkerKind> = { '<': 'ours', '|': 'base', '=': 'separator', '>': 'theirs' };

/** The conflict marker lines of `text`, in order; none when no line opens or closes a conflict. */
export function conflictMarkers(text: string): ConflictMarker[] {
  // a cheap test first: most texts hold none of the four runs
  if (!text.includes('<<<<<<<') && !text.includes('>>>>>>>')) return [];
  const found: ConflictMarker[] = [];
  let line = 1;
  let counted = 0;
  for (const m of text.matchAll(MARKER_LINE)) {
    for (let i = text.indexOf('\n', counted); i >= 0 && i < m.index; i = text.indexOf('\n', i + 1)) line++;
    counted = m.index;
    const eol = text.indexOf('\n', m.index);
    const end = eol < 0 ? text.length : eol > m.index && text.charCodeAt(eol - 1) === 13 ? eol - 1 : eol;
    found.push({ line, offset: m.index, length: end - m.index, kind: KIND[m[1]![0]!]! });
  }
  return found.some((m) => m.kind === 'ours' || m.kind === 'theirs') ? found : [];
}

/** The lines of `markers` as a message says them: `251, 255, 259` (at most 8, then `...`). */
export function conflictMarkerLines(markers: readonly ConflictMarker[]): string {
  const lines = markers.slice(0, 8).map((m) => String(m.line));
  return `${lines.join(', ')}${markers.length > 8 ? ', ...' : ''}`;
}
