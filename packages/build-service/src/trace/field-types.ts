/**
 * The JSON type of each key of a record's `fields` (`contract trace --format json`, `contract run
 * --trace`: docs/runtime-api.md "Trace records", the table of `fields`). A key has one type
 * whatever its value's size: a count, a port, a time in ns is always a JSON number written with
 * its exact digits (`"tick_ns":9123357357727918`, never a string once it passes 15 digits or 2^53),
 * a name or a value's text always a JSON string (`"value":"12"`). The reader (parse.ts,
 * text-lines.ts) keeps its own types — a number when a double holds it exactly, else its digits
 * as text —: this table is applied where a record is written as JSON (the CLI's record-json.ts).
 * Browser-safe.
 */
import { TRACE_KINDS } from './record-kinds.js';
import { SCHEDULER_LINES, SUPERVISOR_LINES, type LinePattern } from './text-lines.js';

export type FieldJsonType = 'number' | 'string';

/** Keys whose value is an integer: a JSON number, its exact digits. */
const NUMBER_KEYS = [
    'pid', 'priority', 'status', 'records', 'activation', 'id', 'sent', 'failed', 'replaced', 'kept_ns', 'to_port', 'latency_ns',
    'periodicity', 'waits', 'wait_ns', 'max_wait_ns', 'streak_ns', 'from_port', 'taken_ns', 'rules', 'handling_ns', 'cycle',
    'tick_ns', 'release_ns', 'release', 'response_ns', 'critical_delay_ns', 'late_us', 'critical_delay_us', 'skipped', 'missed',
    'periods', 'port', 'in_port', 'out_port', 'cpu_ns',
] as const;

/** Keys whose value is text (a name, a word, a value as a rule's cause writes it): a JSON string, digits or not. */
const STRING_KEYS = [
    'what', 'action', 'event', 'posingAs', 'schema', 'request', 'value', 'requester', 'active', 'state', 'modules', 'module', 'name',
    'to_module', 'function', 'rule', 'supervisor', 'type',
] as const;

const TYPES = new Map<string, FieldJsonType>([...NUMBER_KEYS.map((k) => [k, 'number'] as const), ...STRING_KEYS.map((k) => [k, 'string'] as const)]);

/** The JSON type of a `fields` key, or undefined for a key no record kind has. */
export function fieldJsonType(key: string): FieldJsonType | undefined {
    return TYPES.get(key);
}

/** The keys a line table's patterns give (`what` first, then `action` when a pattern fixes it, then the named parts). */
function lineKeys(patterns: readonly LinePattern[]): string[] {
    const keys = new Set<string>(['what']);
    if (patterns.some((p) => p.fixed)) keys.add('action');
    for (const p of patterns) for (const k of p.keys) keys.add(k);
    return [...keys];
}

/**
 * The `fields` keys a record of `kind` may have, in the reader's order: the detail's `key=value`
 * words the table names (detailKeys) for most kinds, the named parts of an engine's readable line
 * for `scheduler` and `supervisor`, `event` (and `posingAs`) for a `user` record. A key is left out
 * when the line does not hold it. `sup_rule` has none: its parts are top-level (`function`, `rule`,
 * `active`, `cause`, `causeEvent`).
 */
export function fieldKeysOf(kind: string): string[] {
    if (kind === 'scheduler') return lineKeys(SCHEDULER_LINES);
    if (kind === 'supervisor') return lineKeys(SUPERVISOR_LINES);
    if (kind === 'user') return ['event', 'posingAs'];
    return [...(TRACE_KINDS.find((k) => k.kind === kind)?.detailKeys ?? [])];
}

/** Every key any kind's `fields` may have (a test checks each has its JSON type). */
export function allFieldKeys(): string[] {
    return [...new Set(TRACE_KINDS.flatMap((k) => fieldKeysOf(k.kind)))];
}
