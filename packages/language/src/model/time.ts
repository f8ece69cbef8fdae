/** Time literals (`500us`, `1.5ms`, `1s`) and their value in nanoseconds. */

const UNIT_NS: Record<string, number> = { ns: 1, us: 1_000, ms: 1_000_000, s: 1_000_000_000 };

/** The parts of a time literal, or undefined when the text is not one. */
export function parseTime(text: string): { amount: number; unit: 'ns' | 'us' | 'ms' | 's' } | undefined {
    const match = /^(-?[0-9]+(?:\.[0-9]+)?)(ns|us|ms|s)$/.exec(text.trim());
    if (!match) return undefined;
    return { amount: Number(match[1]), unit: match[2] as 'ns' | 'us' | 'ms' | 's' };
}

/** Nanoseconds of a time literal (`'500us'` -> 500000), rounded to the nanosecond; NaN if malformed. */
export function timeToNanoseconds(text: string): number {
    const parsed = parseTime(text);
    if (!parsed) return Number.NaN;
    return Math.round(parsed.amount * UNIT_NS[parsed.unit]!);
}

/** Readable form of a duration in nanoseconds (shared with the trace and the simulator). */
export { formatNanoseconds } from '@contract-studio/conventions';
