/**
 * ORD's overruns and missed ticks, as its scheduler lines tell them. ORD skips a periodic release
 * when the schema's previous cycle still runs at the tick, and counts every skip (its `overruns`, what a scenario's
 * `expect overruns` checks), but it writes one line per cycle, not one per tick:
 * - `overrun: S cycle still running, release skipped` at the cycle's first skip;
 * - `overrun: S cycle ended after N skipped releases` when a cycle that skipped more than one ends
 *   (finished, restarted, deactivated, or ORD stopped at the end of the run; N counts the first too);
 * - `overrun: S cycle still held, restarted`: one more.
 * Summed over a run's lines, this is ORD's own count; while a cycle still overruns, its first
 * skip counts 1 until it ends (a live run, a simulation stepped to that time). Logs written before
 * 2026-12-05 told no count when a cycle was restarted or deactivated, or when ORD stopped.
 *
 * Missed ticks (ORD itself woke after a later tick was due: it skips the overtaken one) are told
 * the same way: `missed tick of S (cycle k)` for each when no cycle runs, the first of a running
 * cycle's, and `missed ticks: S cycle ended after N missed ticks` when that cycle ends (N counts the
 * first too; logs written before 2026-12-05 have no such line).
 */

/** A cycle's count told at its end, less its first (told when it happened); 0 for a forged or unread count. */
function afterTheFirst(n: unknown): number {
    return typeof n === 'number' && Number.isSafeInteger(n) && n > 1 ? n - 1 : 0;
}

/** How many skipped releases a scheduler line's fields (`what`, `skipped`) add to ORD's overruns. */
export function skippedReleasesOf(fields: Readonly<Record<string, unknown>>): number {
    if (fields['what'] === 'overrun') return 1;
    return fields['what'] === 'overrun_ended' ? afterTheFirst(fields['skipped']) : 0;
}

/**
 * Whether the line leaves the schema's current cycle overrunning (true), ends an overrun (false:
 * its count was told, or the held cycle restarted), or says nothing of it (undefined). A cycle
 * that completes or is deactivated also ends it.
 */
export function overrunningAfter(fields: Readonly<Record<string, unknown>>): boolean | undefined {
    if (fields['what'] === 'overrun') return fields['state'] === 'running';
    if (fields['what'] === 'overrun_ended') return false;
    return undefined;
}

/** How many ticks ORD missed that a scheduler line's fields (`what`, `missed`) add to its count. */
export function missedTicksOf(fields: Readonly<Record<string, unknown>>): number {
    if (fields['what'] === 'missed_tick') return 1;
    return fields['what'] === 'missed_ticks_ended' ? afterTheFirst(fields['missed']) : 0;
}
