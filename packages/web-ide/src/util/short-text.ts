/**
 * Text shortened for a place one line long (an entry of a list), at a word boundary: `text` itself
 * when it has at most `max` characters, else its first words that fit in `max - 1` and `…` (a first
 * word longer than half of that is cut inside). The place gives the whole text as its tooltip and
 * accessible name.
 */
export function shortAtWord(text: string, max: number): string {
  if (text.length <= max) return text;
  let head = text.slice(0, max - 1);
  // never half a character: a pair of UTF-16 surrogates stays whole or goes
  if (/[\ud800-\udbff]$/.test(head)) head = head.slice(0, -1);
  const space = head.search(/\s\S*$/);
  if (space > max / 2 && !/\s/.test(text[head.length] ?? ' ') ) head = head.slice(0, space);
  return `${head.trimEnd().replace(/[\s,;:·(]+$/, '')}…`;
}
