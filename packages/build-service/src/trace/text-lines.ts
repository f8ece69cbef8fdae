/**
 * The engines' readable trace lines (`scheduler` and `supervisor` records, formatted by
 * ord_core.c and sup_core.c) -> typed fields: `what` plus the names the line holds. The first
 * pattern that matches wins; a supervisor line no pattern names is one of its actions or undos
 * (`subscribe MAA:2 =* :2`, `undo: unsubscribe MAA:2 :2`): `what` = `action`. docs/runtime-api.md
 * "Trace records" lists the `what` values (from these tables).
 */

export interface LinePattern {
    what: string;
    re: RegExp;
    /** Names of the capture groups, in order; an unmatched optional group is left out. */
    keys: readonly string[];
}

const ID = '([A-Za-z_]\\w*)';

export const SCHEDULER_LINES: readonly LinePattern[] = [
    { what: 'activate', re: new RegExp(`^activate ${ID}$`), keys: ['schema'] },
    { what: 'deactivate', re: new RegExp(`^deactivate ${ID}$`), keys: ['schema'] },
    { what: 'conflict', re: new RegExp(`^conflict: ${ID} shares a module with active ${ID} \\(ORD:1\\)$`), keys: ['schema', 'active'] },
    { what: 'refused', re: new RegExp(`^refused: unknown schema (.*)$`), keys: ['schema'] },
    { what: 'ignored', re: new RegExp(`^ignored: deactivate ${ID} \\(not this activation\\)$`), keys: ['schema'] },
    { what: 'deadline_miss', re: new RegExp(`^deadline miss: ${ID} \\(ORD:0\\)$`), keys: ['schema'] },
    { what: 'overrun', re: new RegExp(`^overrun: ${ID} cycle still (running|held)`), keys: ['schema', 'state'] },
    { what: 'missed_tick', re: new RegExp(`^missed tick of ${ID}$`), keys: ['schema'] },
    { what: 'held', re: new RegExp(`^cycle of ${ID} held: ${ID} still runs`), keys: ['schema', 'module'] },
    { what: 'resumed', re: new RegExp(`^cycle of ${ID} resumed$`), keys: ['schema'] },
    { what: 'late_ack', re: new RegExp(`^late ack: ${ID} finished release #(\\d+) of an earlier cycle of ${ID}`), keys: ['module', 'release', 'schema'] },
    { what: 'gave_up', re: new RegExp(`^gave up waiting for ${ID} release #(\\d+)`), keys: ['module', 'release'] },
    { what: 'stuck', re: new RegExp(`^stuck: ${ID} has not finished release #(\\d+) after (\\d+) periods`), keys: ['module', 'release', 'periods'] },
    { what: 'ignored', re: new RegExp(`^ignored: ${ID} finished outside a cycle`), keys: ['module'] },
    { what: 'warning', re: /^warning: /, keys: [] },
];

export const SUPERVISOR_LINES: readonly LinePattern[] = [
    { what: 'function_started', re: new RegExp(`^function ${ID}(?:\\(.*\\))? started$`), keys: ['function'] },
    { what: 'function_stopped', re: new RegExp(`^function ${ID} stopped$`), keys: ['function'] },
    { what: 'function_refused', re: new RegExp(`^refused: (?:function ${ID} already running|no function (.*))$`), keys: ['function', 'function'] },
    { what: 'rule', re: new RegExp(`^rule ${ID}\\.${ID} (active|inactive)$`), keys: ['function', 'rule', 'state'] },
    { what: 'refused', re: /^refused: /, keys: [] },
    { what: 'ignored', re: /^ignored: /, keys: [] },
    { what: 'kept', re: /^kept: /, keys: [] },
    { what: 'error', re: /^error: /, keys: [] },
    { what: 'warning', re: /^warning: /, keys: [] },
    // an event schema the supervisor runs itself: its activation and undo name it (`schema`)
    { what: 'action', re: new RegExp(`^activate schema ${ID}(?:\\(.*\\))? \\(event schema\\)$`), keys: ['schema'] },
    { what: 'action', re: new RegExp(`^undo: deactivate schema ${ID} \\(event schema\\)$`), keys: ['schema'] },
    { what: 'action', re: /^/, keys: [] },
];

/** `what` and the named parts of a line, numbers when digits (a scheduler line no pattern names:
 *  `what` = `other`). */
export function classifyLine(patterns: readonly LinePattern[], line: string): Record<string, string | number> {
    for (const p of patterns) {
        const m = p.re.exec(line);
        if (!m) continue;
        const out: Record<string, string | number> = { what: p.what };
        p.keys.forEach((key, i) => {
            const v = m[i + 1];
            if (v !== undefined) out[key] = /^\d{1,15}$/.test(v) ? Number(v) : v;
        });
        return out;
    }
    return { what: 'other' };
}

/** The `what` values of a table, once each, in order (for the doc). */
export function whatValues(patterns: readonly LinePattern[]): string[] {
    return [...new Set(patterns.map((p) => p.what))];
}
