/**
 * How near a written word is to a known one, for every "Did you mean": a misspelt keyword
 * (parser/error-messages.ts, and the parser's repair of it, parser/keyword-repair.ts), an unknown
 * name in a .contract file (validation/unresolved-messages.ts) and in a scenario
 * (scenario/did-you-mean.ts). One distance for all: letters swapped, missing, extra or wrong each
 * count as one edit (`rulse`, `rlues` and `rulez` are all one edit from `rules`).
 */

/**
 * Optimal string alignment distance (restricted Damerau-Levenshtein: Levenshtein plus the swap of
 * two adjacent letters as one edit), case-insensitive. With `max`, any distance above it is
 * returned as `max + 1`, without computing it in full.
 */
export function editDistance(a: string, b: string, max = Number.POSITIVE_INFINITY): number {
    const s = a.toLowerCase();
    const t = b.toLowerCase();
    if (Math.abs(s.length - t.length) > max) return max + 1;
    const cols = t.length + 1;
    // three rows: the transposition looks two rows back
    let before: number[] = [];
    let prev: number[] = Array.from({ length: cols }, (_, j) => j);
    for (let i = 1; i <= s.length; i++) {
        const row: number[] = [i];
        let best = i;
        for (let j = 1; j < cols; j++) {
            const cost = s[i - 1] === t[j - 1] ? 0 : 1;
            let v = Math.min(prev[j]! + 1, row[j - 1]! + 1, prev[j - 1]! + cost);
            if (i > 1 && j > 1 && s[i - 1] === t[j - 2] && s[i - 2] === t[j - 1]) v = Math.min(v, before[j - 2]! + 1);
            row[j] = v;
            best = Math.min(best, v);
        }
        // no row after one whose every cell is above max has a cell at or below it
        // (a swap reaches two rows back, to a cell at least max, and adds one)
        if (best > max) return max + 1;
        before = prev;
        prev = row;
    }
    return Math.min(prev[t.length]!, max + 1);
}

/** Names longer than this are not compared (a hostile line cannot make this quadratic). */
const MAX_COMPARED_LENGTH = 64;

/**
 * The known name closest to `name` (case ignored), if it is within 1 edit (names up to 3
 * characters), 2 (up to 6) or 3: the rule for the names of a model (modules, rules, fields,
 * variables, ...). The first of the closest, in the order of `known`.
 */
export function closestName(name: string, known: Iterable<string>): string | undefined {
    if (name.length > MAX_COMPARED_LENGTH) return undefined;
    const limit = name.length <= 3 ? 1 : name.length <= 6 ? 2 : 3;
    let best: string | undefined;
    let bestDistance = limit + 1;
    for (const candidate of known) {
        if (candidate === name || candidate.length > MAX_COMPARED_LENGTH) continue;
        const distance = editDistance(name, candidate, limit);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best;
}

/**
 * The words of `words` that `image` is a near miss of, closest first: the stricter rule for
 * keywords (a word of 3 to 6 letters within 1 edit, a longer one within 2), as a name read where
 * a keyword was expected is more often a name than a misspelling.
 */
export function nearKeywords(image: string | undefined, words: readonly string[]): string[] {
    if (!image || !/^[A-Za-z_]\w{2,}$/.test(image)) return [];
    const max = image.length >= 7 ? 2 : 1;
    return words.filter((w) => w !== image).map((w) => ({ w, d: editDistance(image, w, max) })).filter((x) => x.d <= max)
        .sort((x, y) => x.d - y.d).map((x) => x.w);
}
