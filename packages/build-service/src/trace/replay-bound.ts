/**
 * The trace records a job's event log keeps for replay (a page that attaches later, or reloads,
 * gets them first, then the live ones): the service's `traceLinesKept` bound (limits.ts), here so
 * that the browser, which cannot import limits.ts (node:os), says the same number.
 */
export const TRACE_LINES_KEPT = 50_000;
