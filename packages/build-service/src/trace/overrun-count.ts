/**
 * ORD's overruns, as its scheduler lines tell them. ORD skips a periodic release when the schema's
 * previous cycle still runs at the tick, and counts every skip (its `overruns`, what a scenario's
 * `expect overruns` checks), but it writes one line per cycle, not one per tick:
 * - `overrun: S cycle still running, release skipped` at the cycle's first skip;
 * - `overrun: S cycle ended after N skipped releases` when a cycle that skipped more than one ends
 *   (finished, restarted, deactivated, or ORD stopped at the end of the run; N counts the first too);
 * - `overrun: S cycle still held, restarted`: one more.
 * Summed over a run's lines, this is ORD's own count; while a cycle still overruns, its first
 * skip counts 1 until it ends (a live run, a simulation stepped to that time). Logs written before
 * 2026-12-05 told no count when a cycle was restarted or deactivated, or when ORD stopped.
 */

/** How many skipped releases a scheduler line's fields (`what`, `skipped`) add to ORD's overruns. */
export function skippedReleasesOf(fields: Readonly<Record<string, unknown>>): number {
    if (fields['what'] === 'overrun') return 1;
    if (fields['what'] !== 'overrun_ended') return 0;
    const n = fields['skipped'];
    return typeof n === 'number' && Number.isSafeInteger(n) && n > 1 ? n - 1 : 0;
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
