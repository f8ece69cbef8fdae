/**
 * Quantiles of durations in bounded memory, for a run of any length: a histogram of 64 bins a
 * decade from 1 µs (a duration under 1 µs counts in the first bin, one of 1000 s or more in the
 * last), with the largest duration of each bin, so that a quantile is told as a value the run had
 * (at most 3.7 % above the quantile: a bin is 1/64 of a decade; at most 1 µs above it under 1 µs).
 * ORD's release lateness (release-lateness.ts) and an asynchronous module's event handling
 * (event-handling.ts) are told with it.
 */
import { quantileBin } from '@contract-studio/conventions';

const BINS_PER_DECADE = 64;
const FROM_NS = 1_000;
const DECADES = 12;
const BINS = BINS_PER_DECADE * DECADES;

export class DurationQuantiles {
    private readonly bins = new Uint32Array(BINS);
    /** The largest duration counted in each bin. */
    private readonly binMax = new Float64Array(BINS);
    private n = 0;
    private max = 0;

    /** One duration (negative or not finite: not counted). */
    add(ns: number): void {
        if (!Number.isFinite(ns) || ns < 0) return;
        const i = ns < FROM_NS ? 0 : Math.min(BINS - 1, Math.floor(Math.log10(ns / FROM_NS) * BINS_PER_DECADE));
        this.bins[i]!++;
        if (ns > this.binMax[i]!) this.binMax[i] = ns;
        this.n++;
        if (ns > this.max) this.max = ns;
    }

    get count(): number {
        return this.n;
    }

    /** The longest duration counted (0: none). */
    get maxNs(): number {
        return this.max;
    }

    /** The q-quantile (0 < q < 1), as the largest duration of its bin. */
    quantileNs(q: number): number {
        const i = quantileBin(this.bins, this.n, q);
        return i < 0 ? this.max : this.binMax[i]!;
    }
}
