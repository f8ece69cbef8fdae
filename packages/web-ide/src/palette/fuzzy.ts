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

/** Bonuses of one matched character (see the header). */
const MATCH = 1;
const WORD_START = 4;
const CONSECUTIVE = 3;
const IN_NAME = 2;

/**
 * The best-scoring way to find the query's characters in order in the candidate (dynamic
 * programming over query × candidate: a greedy leftmost match took `CTL_mod/module.c`'s c and t
 * from `src-gen` and ranked `LOC_mod/module.c` first), or undefined when they are not all there.
 */
export function fuzzyMatch(query: string, candidate: string): FuzzyMatch | undefined {
  const q = query.replace(/\s+/g, '').toLowerCase();
  if (!q) return { score: 0, positions: [] };
  const lower = candidate.toLowerCase();
  const n = lower.length;
  const m = q.length;
  // most candidates of a long query lack one of its characters: a left-to-right scan says so before any table
  for (let k = 0, at = -1; k < m; k++) if ((at = lower.indexOf(q[k]!, at + 1)) < 0) return undefined;
  const nameStart = candidate.lastIndexOf('/') + 1;
  // a character's own score at each position, once (the table below asks for it per query character)
  const charScore = new Float64Array(n);
  for (let i = 0; i < n; i++) charScore[i] = MATCH + (isBoundary(candidate, i) ? WORD_START : 0) + (i >= nameStart ? IN_NAME : 0);
  // best[k * n + i]: the best score of q[0..k] with q[k] at i (-Infinity: impossible); from[]: where q[k-1] was
  const best = new Float64Array(m * n).fill(-Infinity);
  const from = new Int32Array(m * n).fill(-1);
  for (let i = 0; i < n; i++) if (lower[i] === q[0]) best[i] = charScore[i]!;
  for (let k = 1; k < m; k++) {
    // the best of row k-1 at positions before i-1, and where it is
    let prefixBest = -Infinity;
    let prefixAt = -1;
    const row = k * n;
    const prev = (k - 1) * n;
    for (let i = k; i < n; i++) {
      if (i >= 2 && best[prev + i - 2]! > prefixBest) {
        prefixBest = best[prev + i - 2]!;
        prefixAt = i - 2;
      }
      if (lower[i] !== q[k]) continue;
      const adjacent = best[prev + i - 1]! + CONSECUTIVE;
      const apart = prefixBest;
      if (adjacent === -Infinity && apart === -Infinity) continue;
      const takeAdjacent = adjacent >= apart;
      best[row + i] = charScore[i]! + (takeAdjacent ? adjacent : apart);
      from[row + i] = takeAdjacent ? i - 1 : prefixAt;
    }
  }
  let end = -1;
  const last = (m - 1) * n;
  for (let i = 0; i < n; i++) if (best[last + i]! > (end < 0 ? -Infinity : best[last + end]!)) end = i;
  if (end < 0) return undefined;
  const positions = new Array<number>(m);
  for (let k = m - 1, i = end; k >= 0; i = from[k * n + i]!, k--) positions[k] = i;
  const score = best[last + end]! - candidate.length * 0.01; // shorter candidates first among equals
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
