/**
 * A duration in nanoseconds as a Cactal time literal (docs/language-reference.md §3): the coarsest
 * unit that writes it whole (`2s`, `1500ms`, `250us`, `1234ns`). The language's hovers and
 * checks, the simulator's scenario times and the trace's rule causes write times with it.
 */
export function formatNanoseconds(ns: number): string {
    if (ns !== 0 && ns % 1_000_000_000 === 0) return `${ns / 1_000_000_000}s`;
    if (ns !== 0 && ns % 1_000_000 === 0) return `${ns / 1_000_000}ms`;
    if (ns !== 0 && ns % 1_000 === 0) return `${ns / 1_000}us`;
    return `${ns}ns`;
}
