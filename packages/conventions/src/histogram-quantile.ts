/**
 * The q-quantile of values kept as a histogram (counts per bin, bins in the values' order), read
 * as the bin that holds it: the first bin at which the counts so far reach its rank, ceil(q * total)
 * (the nearest-rank quantile: the value of that rank among the values sorted). Both readers of how
 * late ORD released a schema's cycles use it, each telling the bin its own way: `contract trace`
 * (64 bins a decade, the largest value counted in the bin) and the Monitor (8 a decade, in its
 * state: the bin's upper bound).
 */

/** The bin holding the q-quantile (0 < q < 1) of `total` values counted in `counts`; -1 when the counts do not reach its rank (fewer than `total`). */
export function quantileBin(counts: ArrayLike<number>, total: number, q: number): number {
    const rank = Math.ceil(q * total);
    let seen = 0;
    for (let i = 0; i < counts.length; i++) {
        seen += counts[i]!;
        if (seen >= rank) return i;
    }
    return -1;
}
