/**
 * The engines' readable trace lines (`scheduler` and `supervisor` records, formatted by
 * ord_core.c, sup_core.c and sup_main.c) -> typed fields: `what` plus the names the line holds.
 * The first pattern that matches wins; a line no pattern names is `what` = `other` (a line of
 * another engine version, or forged in a log folder: never taken for an action). A supervisor's
 * actions and undos (`subscribe MAA:2 =* :2`, `undo: unsubscribe MAA:2 :2`) are `what` = `action`,
 * each with what it names. docs/runtime-api.md "Trace records" lists the `what` values (from
 * these tables).
 */

export interface LinePattern {
    what: string;
    re: RegExp;
    /** Names of the capture groups, in order; an unmatched optional group is left out. */
    keys: readonly string[];
    /** Fields every line of the pattern has (a supervisor's `action` whose outcome has a record of its own). */
    fixed?: Readonly<Record<string, string>>;
}

const ID = '([A-Za-z_]\\w*)';
const SERVED = `(?: \\(activation #(\\d+)(?: from ${ID})?\\))?`;
/** `parameterize M:p NAME (N bytes) = V`, a supervisor's action or ORD's (engine_format_parameterize):
 *  the port's name after its number since 2026-12-04 (field `name`); older logs: none, and an older
 *  supervisor's line may end at `(N bytes)`. */
const PARAMETERIZE = new RegExp(`^parameterize ${ID}:(\\d+)(?: ${ID})? \\(\\d+ bytes\\)(?: = |$)`);

export const SCHEDULER_LINES: readonly LinePattern[] = [
    // each periodic release (its typed record is ord_release); first: the line ORD writes most
    { what: 'release', re: new RegExp(`^release ${ID} \\(${ID}\\)$`), keys: ['module', 'schema'] },
    // ` (activation #N from SUP)`: the activation served, as its requester numbered it (older logs: none)
    { what: 'activate', re: new RegExp(`^activate ${ID}${SERVED}$`), keys: ['schema', 'activation', 'requester'] },
    { what: 'deactivate', re: new RegExp(`^deactivate ${ID}${SERVED}$`), keys: ['schema', 'activation', 'requester'] },
    { what: 'conflict', re: new RegExp(`^conflict: ${ID} shares a module with active ${ID} \\(ORD:1\\)$`), keys: ['schema', 'active'] },
    { what: 'refused', re: new RegExp(`^refused: unknown schema (.*)$`), keys: ['schema'] },
    { what: 'ignored', re: new RegExp(`^ignored: deactivate ${ID} \\(not this activation\\)$`), keys: ['schema'] },
    // (older logs: no cycle)
    { what: 'deadline_miss', re: new RegExp(`^deadline miss: ${ID}(?: cycle (\\d+))? \\(ORD:0\\)$`), keys: ['schema', 'cycle'] },
    // ORD itself released the cycle at or past its CRITICAL_DELAY (a loaded machine): its miss, no ORD:0 (since 2026-12-07)
    { what: 'late_release', re: new RegExp(`^late release: ${ID} cycle (\\d+) released (\\d+) us after its tick, past CRITICAL_DELAY (\\d+) us`), keys: ['schema', 'cycle', 'late_us', 'critical_delay_us'] },
    // `overrun: S cycle still running (CTL, EST), release skipped`: the modules it still runs (logs before 2026-12-07 name none)
    { what: 'overrun', re: new RegExp(`^overrun: ${ID} cycle still (running|held)(?: \\((${ID}(?:, ${ID})*(?:, \\.\\.\\.)?)\\))?`), keys: ['schema', 'state', 'modules'] },
    { what: 'overrun_ended', re: new RegExp(`^overrun: ${ID} cycle ended after (\\d+) skipped releases$`), keys: ['schema', 'skipped'] },
    { what: 'missed_tick', re: new RegExp(`^missed tick of ${ID}(?: \\(cycle (\\d+)\\))?$`), keys: ['schema', 'cycle'] },
    { what: 'missed_ticks_ended', re: new RegExp(`^missed ticks: ${ID} cycle ended after (\\d+) missed ticks$`), keys: ['schema', 'missed'] },
    { what: 'held', re: new RegExp(`^cycle of ${ID} held: ${ID} still runs`), keys: ['schema', 'module'] },
    { what: 'resumed', re: new RegExp(`^cycle of ${ID} resumed$`), keys: ['schema'] },
    { what: 'late_ack', re: new RegExp(`^late ack: ${ID} finished release #(\\d+) of an earlier cycle of ${ID}`), keys: ['module', 'release', 'schema'] },
    { what: 'gave_up', re: new RegExp(`^gave up waiting for ${ID} release #(\\d+)`), keys: ['module', 'release'] },
    { what: 'stuck', re: new RegExp(`^stuck: ${ID} has not finished release #(\\d+) after (\\d+) periods`), keys: ['module', 'release', 'periods'] },
    { what: 'ignored', re: new RegExp(`^ignored: ${ID} finished outside a cycle`), keys: ['module'] },
    { what: 'unstuck', re: new RegExp(`^${ID} finished release #(\\d+) at last \\(reported stuck, ${ID}\\)$`), keys: ['module', 'release', 'schema'] },
    { what: 'warning', re: /^warning: /, keys: [] },
    // what it does at a schema's activation and deactivation (ord_main.c, since 2026-12-04; the simulator's words)
    { what: 'parameterize', re: PARAMETERIZE, keys: ['module', 'port', 'name'] },
    { what: 'connect', re: new RegExp(`^connect ${ID}:(\\d+) -> ${ID}:(\\d+) \\* (\\d+)$`), keys: ['module', 'port', 'to_module', 'to_port', 'periodicity'] },
    { what: 'disconnect', re: new RegExp(`^disconnect ${ID}:(\\d+) -> ${ID}:(\\d+)$`), keys: ['module', 'port', 'to_module', 'to_port'] },
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
    // the callee refused a function this supervisor activated: its undo will stop nothing
    { what: 'activation_refused', re: new RegExp(`^activation #(\\d+) of ${ID}\\.${ID} refused: `), keys: ['activation', 'supervisor', 'function'] },
    // its actions and undos (sup_main.c, sup_core.c), each with what it names; with parameters,
    // `(p = v, ...)` follows the schema or function name
    { what: 'action', re: new RegExp(`^activate schema ${ID}(?:\\(.*\\))? \\(activation #(\\d+), to ORD\\)$`), keys: ['schema', 'activation'] },
    { what: 'action', re: new RegExp(`^undo: deactivate schema ${ID} \\(activation #(\\d+), to ORD\\)$`), keys: ['schema', 'activation'] },
    // an event schema the supervisor runs itself
    { what: 'action', re: new RegExp(`^activate schema ${ID}(?:\\(.*\\))? \\(event schema\\)$`), keys: ['schema'] },
    { what: 'action', re: new RegExp(`^undo: deactivate schema ${ID} \\(event schema\\)$`), keys: ['schema'] },
    { what: 'action', re: new RegExp(`^activate supervisor ${ID}\\.${ID}(?:\\(.*\\))? \\(activation #(\\d+)\\)$`), keys: ['supervisor', 'function', 'activation'] },
    { what: 'action', re: new RegExp(`^undo: stop ${ID}\\.${ID} \\(activation #(\\d+)\\)$`), keys: ['supervisor', 'function', 'activation'] },
    // (older logs: no ` = value`)
    { what: 'action', re: PARAMETERIZE, keys: ['module', 'port', 'name'] },
    // (older logs: no activation number)
    { what: 'action', re: new RegExp(`^subscribe ${ID}:(\\d+) (?:=>|=\\*) :(\\d+)(?: \\(activation #(\\d+)\\))?$`), keys: ['module', 'port', 'in_port', 'activation'] },
    { what: 'action', re: new RegExp(`^undo: unsubscribe ${ID}:(\\d+) :(\\d+)(?: \\(activation #(\\d+)\\))?$`), keys: ['module', 'port', 'in_port', 'activation'] },
    { what: 'action', re: new RegExp(`^notify :(\\d+) \\((?:${ID}|\\?)\\)(?: = |$)`), keys: ['out_port', 'type'] },
    { what: 'action', re: new RegExp(`^compute ${ID}$`), keys: ['function'] },
    // the modules it starts (an event schema's, `activate resttime|critical module` on one not
    // running) and stops, the event flows of event schemas it connects and disconnects (module =
    // the source), the priority claims of `activate resttime|critical module` on a running module
    // and their undos (activation = the claim's number). Each has a record of what came of it
    // (module_hold, flow_hold, module_priority), which readers pair with the line: field `action`
    // names it. (Logs of older versions: none of these lines, only those records.) A simulation's
    // start of a module it made crash adds `: it has crashed, it does not start`.
    { what: 'action', re: new RegExp(`^start module ${ID} \\(priority (\\d+)\\)(?:: it has crashed, it does not start)?$`), keys: ['module', 'priority'], fixed: { action: 'start_module' } },
    { what: 'action', re: new RegExp(`^undo: stop module ${ID}$`), keys: ['module'], fixed: { action: 'stop_module' } },
    { what: 'action', re: new RegExp(`^connect ${ID}:(\\d+) (?:=>|=\\*) ${ID}:(\\d+)$`), keys: ['module', 'port', 'to_module', 'to_port'], fixed: { action: 'connect' } },
    { what: 'action', re: new RegExp(`^undo: disconnect ${ID}:(\\d+) (?:=>|=\\*) ${ID}:(\\d+)$`), keys: ['module', 'port', 'to_module', 'to_port'], fixed: { action: 'disconnect' } },
    { what: 'action', re: new RegExp(`^set priority of ${ID} to (\\d+) \\(claim #(\\d+)\\)$`), keys: ['module', 'priority', 'activation'], fixed: { action: 'claim_priority' } },
    { what: 'action', re: new RegExp(`^undo: release priority claim #(\\d+) on ${ID}$`), keys: ['activation', 'module'], fixed: { action: 'release_priority' } },
];

/** `what` and the named parts of a line, numbers when digits (a line no pattern names:
 *  `what` = `other`). */
export function classifyLine(patterns: readonly LinePattern[], line: string): Record<string, string | number> {
    for (const p of patterns) {
        const m = p.re.exec(line);
        if (!m) continue;
        const out: Record<string, string | number> = { what: p.what, ...p.fixed };
        p.keys.forEach((key, i) => {
            const v = m[i + 1];
            if (v !== undefined) out[key] = /^\d{1,15}$/.test(v) ? Number(v) : v;
        });
        return out;
    }
    return { what: 'other' };
}

/**
 * ORD's readable line typed (`what` and the names it holds, as a `scheduler` record's fields): the
 * one reading of ORD's lines, also for the simulator's log of them (releases, activations, misses).
 */
export function schedulerLineFields(line: string): Record<string, string | number> {
    return classifyLine(SCHEDULER_LINES, line);
}

/** The `what` values of a table, once each, in order (for the doc). */
export function whatValues(patterns: readonly LinePattern[]): string[] {
    return [...new Set(patterns.map((p) => p.what))];
}
