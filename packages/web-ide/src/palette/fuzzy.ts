/**
 * Fuzzy matching as quick-open boxes do it: every character of the query appears in order in the
 * candidate (case-insensitive). Matches at word starts (after `/`, `.`, `-`, `_`, a space or a
 * lower→upper case change), consecutive matches and matches in the file name score higher.
 */
export interface FuzzyMatch {
  score: number;
  /** Indexes of the matched characters in the candidate (to highlight them). */
  positions: number[];
}

const isBoundary = (text: string, i: number) =>
  i === 0 || '/._- :'.includes(text[i - 1]!) || (text[i - 1] === text[i - 1]!.toLowerCase() && text[i] !== text[i]!.toLowerCase());

export function fuzzyMatch(query: string, candidate: string): FuzzyMatch | undefined {
  const q = query.replace(/\s+/g, '').toLowerCase();
  if (!q) return { score: 0, positions: [] };
  const lower = candidate.toLowerCase();
  const nameStart = candidate.lastIndexOf('/') + 1;
  // greedy from the left, then each match moved to a later word start when one is free before the next match
  const positions: number[] = [];
  let from = 0;
  for (const ch of q) {
    const at = lower.indexOf(ch, from);
    if (at < 0) return undefined;
    positions.push(at);
    from = at + 1;
  }
  for (let k = positions.length - 1; k >= 0; k--) {
    const limit = k + 1 < positions.length ? positions[k + 1]! : lower.length;
    for (let i = limit - 1; i > positions[k]!; i--) {
      if (lower[i] === q[k] && isBoundary(candidate, i) && !isBoundary(candidate, positions[k]!)) {
        positions[k] = i;
        break;
      }
    }
  }
  let score = 0;
  positions.forEach((p, k) => {
    score += 1;
    if (isBoundary(candidate, p)) score += 4;
    if (k > 0 && positions[k - 1] === p - 1) score += 3;
    if (p >= nameStart) score += 2;
  });
  score -= candidate.length * 0.01; // shorter candidates first among equals
  return { score, positions };
}

/** Candidates matching `query`, best first (stable for equal scores). */
export function fuzzyFilter<T>(query: string, items: readonly T[], text: (item: T) => string): Array<{ item: T; match: FuzzyMatch }> {
  const out: Array<{ item: T; match: FuzzyMatch; i: number }> = [];
  items.forEach((item, i) => {
    const match = fuzzyMatch(query, text(item));
    if (match) out.push({ item, match, i });
  });
  return out.sort((a, b) => b.match.score - a.match.score || a.i - b.i).map(({ item, match }) => ({ item, match }));
}
