/**
 * "Did you mean" for a name typed on the command line (a command, `--start SUP.function`): the
 * closest known name by edit distance (letters swapped, missing, extra or wrong; case ignored),
 * only when it is close enough to be the intended one. The same rule as the scenario checker's
 * (packages/language src/scenario/did-you-mean.ts), kept here so that a command that does not load
 * the language does not load it for this.
 */

/** Optimal string alignment distance (Levenshtein + adjacent transpositions), case-insensitive. */
export function editDistance(a: string, b: string): number {
    const s = a.toLowerCase();
    const t = b.toLowerCase();
    const cols = t.length + 1;
    const d: number[] = new Array((s.length + 1) * cols).fill(0);
    for (let i = 0; i <= s.length; i++) d[i * cols] = i;
    for (let j = 0; j < cols; j++) d[j] = j;
    for (let i = 1; i <= s.length; i++) {
        for (let j = 1; j < cols; j++) {
            const cost = s[i - 1] === t[j - 1] ? 0 : 1;
            let v = Math.min(d[(i - 1) * cols + j]! + 1, d[i * cols + j - 1]! + 1, d[(i - 1) * cols + j - 1]! + cost);
            if (i > 1 && j > 1 && s[i - 1] === t[j - 2] && s[i - 2] === t[j - 1]) v = Math.min(v, d[(i - 2) * cols + j - 2]! + 1);
            d[i * cols + j] = v;
        }
    }
    return d[d.length - 1]!;
}

/** The known name closest to `name`, if it is within 1 edit (names up to 3 characters), 2 (up to 6) or 3. */
export function closestName(name: string, known: Iterable<string>): string | undefined {
    if (name.length > 64) return undefined;
    const limit = name.length <= 3 ? 1 : name.length <= 6 ? 2 : 3;
    let best: string | undefined;
    let bestDistance = limit + 1;
    for (const candidate of known) {
        if (candidate === name || Math.abs(candidate.length - name.length) > limit) continue;
        const distance = editDistance(name, candidate);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best;
}
