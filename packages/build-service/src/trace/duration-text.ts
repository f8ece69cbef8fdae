/**
 * A duration of the run as a reader reads it, in the unit that suits it: `100.312 ms`, `2.5 ms`,
 * `900 ns`, `35.4 µs`, `1.25 s` (at most 3 decimals, trailing zeros dropped). The words of
 * `contract trace`'s schema lines and of the IDE Monitor's response times.
 */
export function durationText(ns: number): string {
    if (ns >= 1e9) return `${+(ns / 1e9).toFixed(3)} s`;
    if (ns >= 1e6) return `${+(ns / 1e6).toFixed(3)} ms`;
    if (ns >= 1e3) return `${+(ns / 1e3).toFixed(1)} µs`;
    return `${Math.round(ns)} ns`;
}
