/**
 * The typed records of a run's trace (docs/runtime-api.md "Trace records"). Every CSV record
 * becomes one TraceRecord; what the reader could not understand is kept as `unknown`.
 */

/** What every record holds (the CSV columns). */
export interface TraceRecordBase {
    /** CLOCK_MONOTONIC ns as written (decimal string: exact beyond 2^53). */
    monoNs: string;
    wallTime: string;
    /** The module whose log holds the record. */
    module: string;
    peer: string;
    port: number | null;
    size: number;
    detail: string;
    /**
     * The record is its log's last line and that line has no line end (the runtime writes every
     * record whole, with its newline): its writer was killed or stopped inside it, or is still
     * writing it, so its last field may be cut. Read as the line holds it; `contract trace` says so.
     */
    cut?: true;
}

/** A rule of a supervisor function became active or inactive, and why. */
export interface RuleRecord extends TraceRecordBase {
    kind: 'sup_rule';
    function: string;
    rule: string;
    active: boolean;
    /** The cause as logged: `MAA:2 value="disconnected"`, `elapsed=1000000ns`, `stop`... */
    cause: string;
    causeEvent: RuleCause;
}

export type RuleCause =
    | { kind: 'event'; module: string; port: number; value: string }
    | { kind: 'started' | 'endof'; rule: string }
    | { kind: 'duration'; rule: string; ns: number }
    | { kind: 'elapsed'; ns: number }
    | { kind: 'stop' }
    | { kind: 'other'; text: string };

/** Any other kind of the table: `fields` holds its detail's `key=value` words (numbers when digits). */
export interface KnownRecord extends TraceRecordBase {
    kind: string;
    fields: Record<string, string | number>;
}

/** A line the reader could not read: kept, with why. */
export interface UnknownRecord {
    kind: 'unknown';
    /** The log file and 1-based line number. */
    file: string;
    line: number;
    reason: string;
    /** The line, cut at 200 characters. */
    text: string;
}

export type TraceRecord = RuleRecord | KnownRecord | UnknownRecord;

export function isRule(r: TraceRecord): r is RuleRecord {
    return r.kind === 'sup_rule' && 'causeEvent' in r;
}

export function isUnknown(r: TraceRecord): r is UnknownRecord {
    return r.kind === 'unknown' && 'reason' in r;
}

/**
 * A trace's counts as `contract trace` and the IDE's Monitor say them: its records are the
 * readable ones; a line that is no record (`unknown`) is counted apart, as an unreadable line.
 */
export interface RecordCounts {
    records: number;
    unreadable: number;
}

/** Counts `r` in `c`: a record, or an unreadable line. */
export function countRecord(c: RecordCounts, r: TraceRecord): void {
    if (r.kind === 'unknown') c.unreadable++;
    else c.records++;
}
