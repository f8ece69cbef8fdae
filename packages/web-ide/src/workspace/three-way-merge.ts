import { diff3Merge } from 'node-diff3';

/** The result of merging two edits of one base text. */
export type MergeResult =
  | { clean: true; text: string }
  /** `marked`: both sides of each conflict between `<<<<<<< yours` / `=======` / `>>>>>>> on disk`. */
  | { clean: false; conflicts: number; marked: string };

type Block = { ok: string[] } | { conflict: { a: string[]; o: string[]; b: string[] } };

/** Lines with their line ends, so that joining gives the text back byte for byte. */
const lines = (t: string): string[] => t.split(/(?<=\n)/);
/** Words, runs of blanks, line ends and single other characters: joined, the text again. */
const tokens = (t: string): string[] => t.match(/\w+|[^\S\n]+|\n|[^\w\s]/g) ?? [];

function merge3(mine: string[], base: string[], theirs: string[]): Block[] {
  return diff3Merge(mine, base, theirs, { excludeFalseConflicts: true }) as Block[];
}

/**
 * Three-way merge of the tab's text (`mine`) and the disk's (`theirs`), both edited from `base`
 * (node-diff3). Line by line first; a block where both sides changed the same or neighbouring
 * lines is merged again word by word, so that edits of two adjacent lines (` // A` after `MSD;`,
 * ` // B` after `MSC;` on the line before) merge, while two edits of the same words conflict.
 * Used when a save is refused as stale and when the watcher reports a change under unsaved edits
 * (docs/ide.md, "Saves, versions and merges").
 */
export function threeWayMerge(base: string, mine: string, theirs: string): MergeResult {
  if (mine === theirs || theirs === base) return { clean: true, text: mine };
  if (mine === base) return { clean: true, text: theirs };
  let text = '';
  let marked = '';
  let conflicts = 0;
  for (const block of merge3(lines(mine), lines(base), lines(theirs))) {
    if ('ok' in block) {
      const t = block.ok.join('');
      text += t;
      marked += t;
      continue;
    }
    const { a, o, b } = block.conflict;
    const fine = merge3(tokens(a.join('')), tokens(o.join('')), tokens(b.join('')));
    if (fine.every((f) => 'ok' in f)) {
      const t = fine.map((f) => ('ok' in f ? f.ok.join('') : '')).join('');
      text += t;
      marked += t;
      continue;
    }
    conflicts++;
    const side = (s: string[]) => { const t = s.join(''); return t === '' || t.endsWith('\n') ? t : `${t}\n`; };
    marked += `<<<<<<< yours\n${side(a)}=======\n${side(b)}>>>>>>> on disk\n`;
  }
  return conflicts ? { clean: false, conflicts, marked } : { clean: true, text };
}

/**
 * The first conflict marker line left in a text (`<<<<<<<`, `=======` or `>>>>>>>` at the start of
 * a line, as git and threeWayMerge's `marked` write them), with its 1-based line number, or
 * undefined. "Save the right side as edited here" refuses a text that still has one (docs/ide.md, "Saves,
 * versions and merges"). A line of exactly seven `=` counts; `==========` or `// =======` does not.
 */
export function findConflictMarker(text: string): { line: number; marker: string } | undefined {
  const all = text.split('\n');
  for (let i = 0; i < all.length; i++) {
    const l = all[i]!.replace(/\r$/, '');
    if (/^(<{7}|>{7})( |$)/.test(l) || /^={7}\s*$/.test(l)) return { line: i + 1, marker: l.length > 40 ? `${l.slice(0, 40)}…` : l };
  }
  return undefined;
}
