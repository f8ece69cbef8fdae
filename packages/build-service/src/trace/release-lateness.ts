/**
 * How late ORD released a periodic schema's cycles (`release_ns - tick_ns` of each cycle's first
 * `ord_release`), kept in bounded memory for a run of any length: a histogram of 64 bins a decade
 * from 1 µs (a lateness under 1 µs counts in the first bin, one of 1000 s or more in the last), with
 * the largest lateness of each bin. `contract trace` tells p50, p99 and max in its schema lines.
 */
import { quantileBin } from '@contract-studio/conventions';
import { durationText } from './duration-text.js';

const BINS_PER_DECADE = 64;
const FROM_NS = 1_000;
const DECADES = 12;
const BINS = BINS_PER_DECADE * DECADES;

export class ReleaseLateness {
    private readonly bins = new Uint32Array(BINS);
    /** The largest lateness counted in each bin: a quantile is told as a value the run had. */
    private readonly binMax = new Float64Array(BINS);
    private n = 0;
    private maxNs = 0;

    /** One cycle's first release, `lateNs` after its tick (negative or not finite: not counted). */
    add(lateNs: number): void {
        if (!Number.isFinite(lateNs) || lateNs < 0) return;
        const i = lateNs < FROM_NS ? 0 : Math.min(BINS - 1, Math.floor(Math.log10(lateNs / FROM_NS) * BINS_PER_DECADE));
        this.bins[i]!++;
        if (lateNs > this.binMax[i]!) this.binMax[i] = lateNs;
        this.n++;
        if (lateNs > this.maxNs) this.maxNs = lateNs;
    }

    get count(): number {
        return this.n;
    }

    /**
     * The q-quantile (0 < q < 1), as the largest lateness of its bin: a value of the run, at most
     * 3.7 % above the quantile (a bin is 1/64 of a decade), at most 1 µs above it under 1 µs.
     */
    quantileNs(q: number): number {
        const i = quantileBin(this.bins, this.n, q);
        return i < 0 ? this.maxNs : this.binMax[i]!;
    }

    /**
     * `release lateness p50 23.1 µs, p99 965 µs, max 8.8 ms`; '' when no cycle was released, or none
     * late (a simulation releases each cycle at its tick, in virtual time).
     */
    text(): string {
        if (!this.n || this.maxNs <= 0) return '';
        return `release lateness p50 ${durationText(this.quantileNs(0.5))}, p99 ${durationText(this.quantileNs(0.99))}, max ${durationText(this.maxNs)}`;
    }
}
