/**
 * How late ORD released a periodic schema's cycles (`release_ns - tick_ns` of each cycle's first
 * `ord_release`), kept in bounded memory for a run of any length (duration-quantiles.ts).
 * `contract trace` tells p50, p99 and max in its schema lines.
 */
import { DurationQuantiles } from './duration-quantiles.js';
import { durationText } from './duration-text.js';

export class ReleaseLateness extends DurationQuantiles {
    /**
     * `release lateness p50 23.1 µs, p99 965 µs, max 8.8 ms`; '' when no cycle was released, or none
     * late (a simulation releases each cycle at its tick, in virtual time).
     */
    text(): string {
        if (!this.count || this.maxNs <= 0) return '';
        return `release lateness p50 ${durationText(this.quantileNs(0.5))}, p99 ${durationText(this.quantileNs(0.99))}, max ${durationText(this.maxNs)}`;
    }
}
