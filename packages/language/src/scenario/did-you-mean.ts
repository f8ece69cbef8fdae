/**
 * "Did you mean" for a misspelt name in a scenario (docs/simulation.md "Values and names"): the
 * closest known name by edit distance (letters swapped, missing, extra or wrong; case ignored),
 * only when it is close enough that it is likely the intended one.
 */

/** Optimal string alignment distance (Levenshtein + adjacent transpositions), case-insensitive. */
export function editDistance(a: string, b: string): number {
    const s = a.toLowerCase();
    const t = b.toLowerCase();
    const rows = s.length + 1;
    const cols = t.length + 1;
    const d: number[] = new Array(rows * cols).fill(0);
    for (let i = 0; i < rows; i++) d[i * cols] = i;
    for (let j = 0; j < cols; j++) d[j] = j;
    for (let i = 1; i < rows; i++) {
        for (let j = 1; j < cols; j++) {
            const cost = s[i - 1] === t[j - 1] ? 0 : 1;
            let v = Math.min(d[(i - 1) * cols + j]! + 1, d[i * cols + j - 1]! + 1, d[(i - 1) * cols + j - 1]! + cost);
            if (i > 1 && j > 1 && s[i - 1] === t[j - 2] && s[i - 2] === t[j - 1]) v = Math.min(v, d[(i - 2) * cols + j - 2]! + 1);
            d[i * cols + j] = v;
        }
    }
    return d[rows * cols - 1]!;
}

/** Names longer than this are not compared (a hostile scenario line cannot make this quadratic). */
const MAX_COMPARED_LENGTH = 64;

/** The known name closest to `name`, if it is within 1 edit (names up to 3 characters), 2 (up to 6) or 3. */
export function closestName(name: string, known: Iterable<string>): string | undefined {
    if (name.length > MAX_COMPARED_LENGTH) return undefined;
    const limit = name.length <= 3 ? 1 : name.length <= 6 ? 2 : 3;
    let best: string | undefined;
    let bestDistance = limit + 1;
    for (const candidate of known) {
        if (candidate === name || candidate.length > MAX_COMPARED_LENGTH) continue;
        if (Math.abs(candidate.length - name.length) > limit) continue;
        const distance = editDistance(name, candidate);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best;
}

/** `. Did you mean 'X'?` or the empty string. */
export function didYouMean(name: string, known: Iterable<string>): string {
    const best = closestName(name, known);
    return best === undefined ? '' : `. Did you mean '${best}'?`;
}
