/**
 * The simulator's steps (docs/simulation.md §4) as the trace records a run writes
 * (docs/runtime-api.md "Trace records"), so that one model holds a live run, a replayed run and a
 * simulation: the IDE's Monitor folds them, `contract simulate --trace` writes them as JSON lines.
 * Browser-safe (`@contract-studio/simulator/trace`: the trace reader and types only). mono_ns is
 * the virtual time. A step record (runner/protocol.ts StepRecord) holds what happened since the
 * step before:
 * - `rules`: rule changes → `sup_rule` records (same cause text, parsed by the trace reader's parseCause);
 * - `log`: the engines' own trace lines, as a real run's `supervisor` and `scheduler` records hold
 *   them (read by the trace reader, parseRecordLine: `function F started`, `activate S`, `overrun: …`),
 *   and ORD's `release M (S)` → `ord_release` records (the cycle counted from 0 at each activation);
 * - `actions`: what the engines did → a supervisor's `supervisor` action record, in the words a
 *   run's log holds (actionAsLogged), each typed by the trace reader, with the peer a run writes
 *   (actionPeer: the module, supervisor or ORD it goes to); then, as a run writes them, the
 *   hold it takes or drops, when the harness does not write its holds itself (an older one: `start
 *   module M` → `module_hold` `hold taken (started it)`, `undo: stop module M` → `last hold dropped
 *   (stopped)`, `connect A:p =* B:i` / `undo: disconnect …` → `flow_hold` `hold taken` / `last hold
 *   dropped (disconnected)` on the flow's hold name; a newer one writes them as `records`, with what
 *   a run's engines decide when supervisors share a module or a flow), a priority
 *   claim's `module_priority`, and before an `activate schema` its START request to ORD
 *   (`request_received`: which rule activated a schema); ORD's `ORD:0 "S" (deadline miss)` →
 *   `ord_deadline_miss`; ORD's `parameterize …`, `connect A:p -> B:i * k`, `disconnect …` → the
 *   `scheduler` records a run's ORD writes (peer: the module; a flow's source); a crash → `module_exit`.
 * - `records`: the typed records the harness writes as a real run's CSV logs hold them (ORD's
 *   ord_release / ord_finished / ord_complete / ord_deadline_miss with their cycle and response
 *   times, each virtual module's run_started / run_finished and data_posted on each connected data
 *   flow, each event_received of a supervisor, with its taken_ns, rules and value as sup_main.c
 *   writes it: after the rule changes it made)
 *   → read by the trace reader as a CSV line. Without them (an older server), ORD's `release M (S)`
 *   lines and `ORD:0` actions stand for the releases and misses, cycles counted here.
 * The records are in time order and, at one virtual time, in the harness's order (each entry's `seq`):
 * ORD's deadline miss comes before the rule it made inactive, a supervisor's `event_received` after
 * the rule changes and actions its event made, as a run's log holds them (an older server's answer,
 * without seq: as listed above).
 * Without `log` (an older server), functions come from start/stop steps and `activate supervisor` /
 * `stop SUP.f` actions, and the schemas from each step's list of active schemas.
 * Not simulated, so not in the trace: data_received (virtual modules read no data) and the values posted.
 */
import { confirmingHold, csvField, parseCause, parseRecordLine, schedulerLineFields, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import type { ActionRecord, LogLine, RuleChange, SimTraceRecord } from '../runner/protocol.js';

/** What the conversion reads of a step: the runner's StepResult with its record's lists, or the IDE's answer of POST /api/simulate. */
export interface TraceStep {
    timeNs: number;
    /** The scenario line (`start SUP.f(...)`): an answer without engine lines takes the started and stopped functions from it. */
    source: string;
    ok: boolean;
    rules: RuleChange[];
    actions: ActionRecord[];
    /** The engines' trace lines (absent from an older server's answer). */
    log?: LogLine[];
    /** The harness's typed records (absent from an older server's answer). */
    records?: SimTraceRecord[];
    /** The active schemas after the step. */
    schemas?: string[];
}

/** The lists of a step that gives nothing (shared: the conversion only reads them). */
const NOTHING: never[] = Object.freeze([]) as unknown as never[];

/**
 * A runner's step as the conversion reads it (its record's lists). A step whose record was not kept
 * whole (`trimmed`: the runner's RECORD_BOUNDS) gives nothing: the trace is the scenario's up to the
 * steps kept whole, not a part of what happened after (rule changes without the releases that made them).
 */
export function traceStepOf(step: { timeNs: number; source: string; ok: boolean; trimmed?: string; record: { rules: RuleChange[]; actions: ActionRecord[]; log?: LogLine[]; records?: SimTraceRecord[]; schemas?: string[] } }): TraceStep {
    const r = step.record;
    if (step.trimmed) return { timeNs: step.timeNs, source: step.source, ok: step.ok, rules: NOTHING, actions: NOTHING, log: NOTHING, records: NOTHING };
    return { timeNs: step.timeNs, source: step.source, ok: step.ok, rules: r.rules, actions: r.actions, log: r.log, records: r.records, schemas: r.schemas };
}

function base(timeNs: number, module: string, detail: string, peer = '') {
    return { monoNs: String(Math.max(0, Math.floor(timeNs))), wallTime: '', module, peer, port: null, size: 0, detail };
}

function known(timeNs: number, module: string, kind: string, detail: string, fields: Record<string, string | number>, peer = ''): KnownRecord {
    return { ...base(timeNs, module, detail, peer), kind, fields };
}

/** An engine's trace line as the CSV record a real run writes (`kind`: supervisor or scheduler), read by the trace reader. */
export function engineLine(timeNs: number, who: string, kind: 'supervisor' | 'scheduler', line: string): TraceRecord {
    return parseRecordLine('simulation', 0, `${Math.max(0, Math.floor(timeNs))},,${who},${kind},,,0,${csvField(line)}`);
}

/** A typed record of the harness as the CSV line a real run writes, read by the trace reader. */
export function typedRecord(r: SimTraceRecord): TraceRecord {
    const port = Number.isInteger(r.port) && r.port! >= 0 ? String(r.port) : '';
    return parseRecordLine('simulation', 0, `${Math.max(0, Math.floor(r.timeNs))},,${csvField(r.module)},${csvField(r.kind)},${csvField(r.peer)},${port},0,${csvField(r.detail)}`);
}

const DEADLINE_MISS = /^ORD:0 "([A-Za-z_]\w*)" \(deadline miss\)/;
/** A simulated module that crashed is not started again: no hold taken (a run's start that cannot be sent takes none either). */
const NOT_STARTED = /: it has crashed, it does not start$/;
const SET_PRIORITY = /^set priority of ([A-Za-z_]\w*) to /;
const ACTIVATE_SCHEMA = /^activate schema ([A-Za-z_]\w*)[ (]/;
const ACTIVATE_SUPERVISOR = /^activate supervisor ([A-Za-z_]\w*)\.([A-Za-z_]\w*)[ (]/;
const STOP_FUNCTION = /^stop ([A-Za-z_]\w*)\.([A-Za-z_]\w*) /;
/**
 * Actions that undo an earlier one (counted `undone`, as the fold counts a logged `undo`/`un…`
 * line): the undo of an `activate schema` (deactivate, its flows' disconnect, its modules' stop), of
 * an `activate supervisor` (stop SUP.f), of a subscription, of a priority claim (release).
 */
const UNDO = /^(stop|deactivate|disconnect|unsubscribe|release)\b/;

/**
 * A harness action line as the runtime's log writes it (sup_main.c): every undo prefixed `undo: `
 * (`undo: stop module M`, `undo: disconnect A:p =* B:i`, `undo: release priority claim #N on M`).
 */
export function actionAsLogged(what: string): string {
    return UNDO.test(what) ? `undo: ${what}` : what;
}

/**
 * The peer a run's engine writes with an action's record (sup_main.c log_action, ord_main.c
 * b_set_param / b_connect / b_disconnect): the module it goes to (a flow's: its source module), the
 * supervisor of an `activate supervisor` or its `stop SUP.f`, ORD for an `activate schema …
 * (activation #N, to ORD)` and its undo; none for a notification or an event schema's own lines.
 */
export function actionPeer(fields: Readonly<Record<string, string | number>>, line: string): string {
    const module = fields['module'], supervisor = fields['supervisor'];
    if (typeof module === 'string' && module) return module;
    if (typeof supervisor === 'string' && supervisor) return supervisor;
    return /, to ORD\)$/.test(line) ? 'ORD' : '';
}

/** An engine's action line as the record a run writes: typed by the trace reader, with the peer it goes to. */
function withActionPeer(rec: TraceRecord, line: string): TraceRecord {
    if (rec.kind === 'unknown') return rec;
    const k = rec as KnownRecord;
    return { ...k, peer: actionPeer(k.fields ?? {}, line) };
}

/** A supervisor's action as the `supervisor` record a run writes, typed by the trace reader (a line it does not know, the simulator's own: an action all the same). */
function actionRecord(timeNs: number, who: string, what: string): TraceRecord {
    const line = actionAsLogged(what);
    const rec = engineLine(timeNs, who, 'supervisor', line);
    if (rec.kind === 'unknown') return known(timeNs, who, 'supervisor', line, { what: 'action' });
    const k = withActionPeer(rec, line) as KnownRecord;
    return k.fields['what'] === 'action' ? k : { ...k, fields: { what: 'action' } };
}

/**
 * The trace of one simulation, in time order; its first record (`sim_start`, time 0: the Monitor's
 * cursor starts there) names `scenario` when given.
 */
export function stepsToTrace(steps: TraceStep[], scenario?: string): TraceRecord[] {
    const out: TraceRecord[] = [known(0, 'SIM', 'sim_start', scenario ? `simulation start: ${scenario.replace(/[\r\n]+/g, ' ')}` : 'simulation start', {})];
    /** Per record of out: the harness's seq of the entry it comes from (-1: none, an older server's or the step's own). */
    const seqs: number[] = [-1];
    let cur = -1;
    const push = (rec: TraceRecord) => { out.push(rec); seqs.push(cur); };
    const withLog = steps.some((s) => Array.isArray(s.log));
    const withRecords = steps.some((s) => Array.isArray(s.records));
    /** The hold kinds the harness writes itself (sim_world.c, as a run's engines: shared, kept, left running, ended); the others told from the action. */
    const harnessHolds = new Set(steps.flatMap((s) => (s.records ?? []).map((r) => r.kind)).filter((k) => k === 'module_hold' || k === 'flow_hold'));
    /**
     * Per periodic schema: its cycle's number (from 0 at each activation) and the modules released in
     * it (a cycle releases each module once, at its precedence's times: a module released again starts the next).
     */
    const cycles = new Map<string, { cycle: number; released: Set<string> }>();
    let schemas = new Set<string>();
    for (const s of steps) {
        cur = -1;
        for (const r of s.rules) {
            cur = r.seq ?? -1;
            const rec: RuleRecord = {
                ...base(r.timeNs, r.supervisor, `${r.function}.${r.rule} ${r.active ? 'active' : 'inactive'} cause=${r.cause}`),
                kind: 'sup_rule', function: r.function, rule: r.rule, active: r.active, cause: r.cause, causeEvent: parseCause(r.cause),
            };
            push(rec);
        }
        for (const r of s.records ?? []) {
            cur = r.seq ?? -1;
            const rec = typedRecord(r);
            if (rec.kind !== 'unknown') push(rec);
        }
        for (const l of s.log ?? []) {
            cur = l.seq ?? -1;
            if (l.who === 'ORD') {
                // ORD's line read as the trace reader reads it (`release M (S)`, `activate S (activation #N from SUP)`)
                const ord = schedulerLineFields(l.line);
                if (ord['what'] === 'release' && withRecords) continue; // the typed ord_release stands for it
                if (ord['what'] === 'release') {
                    const module = String(ord['module']), schema = String(ord['schema']);
                    let c = cycles.get(schema);
                    if (!c || c.released.has(module)) cycles.set(schema, (c = { cycle: (c?.cycle ?? -1) + 1, released: new Set() }));
                    c.released.add(module);
                    const cycle = c.cycle;
                    push(known(l.timeNs, 'ORD', 'ord_release', `schema=${schema} cycle=${cycle} tick_ns=${l.timeNs} release_ns=${l.timeNs}`,
                        { schema, cycle, tick_ns: l.timeNs, release_ns: l.timeNs }, module));
                    continue;
                }
                if (ord['what'] === 'activate') cycles.delete(String(ord['schema']));
                const rec = engineLine(l.timeNs, 'ORD', 'scheduler', l.line);
                if (rec.kind !== 'unknown') push(rec);
            } else {
                const rec = engineLine(l.timeNs, l.who, 'supervisor', l.line);
                // a supervisor's actions come from `actions` (counted once)
                if (rec.kind !== 'unknown' && (rec as KnownRecord).fields?.['what'] !== 'action') push(rec);
            }
        }
        for (const a of s.actions) {
            cur = a.seq ?? -1;
            const t = a.timeNs;
            if (a.who === 'ORD') {
                const miss = withRecords ? null : DEADLINE_MISS.exec(a.what); // else the typed ord_deadline_miss
                if (miss) {
                    const schema = miss[1]!;
                    const cycle = cycles.get(schema)?.cycle ?? -1;
                    push(known(t, 'ORD', 'ord_deadline_miss', `schema=${schema} cycle=${cycle}`, { schema, cycle }));
                }
                // ORD's parameters and data flows at an activation: the `scheduler` records a run's ORD writes (same words)
                const rec = engineLine(t, 'ORD', 'scheduler', a.what);
                if (rec.kind !== 'unknown' && (rec as KnownRecord).fields?.['what'] !== 'other') push(withActionPeer(rec, a.what));
                continue;
            }
            if (a.who === 'sim') continue;
            if (a.what === 'crashed') {
                push(known(t, a.who, 'module_exit', 'crashed (simulated)', {}));
                continue;
            }
            let m: RegExpExecArray | null;
            if ((m = ACTIVATE_SCHEMA.exec(a.what))) push(known(t, 'ORD', 'request_received', `START ${m[1]!}`, {}, a.who));
            const action = actionRecord(t, a.who, a.what);
            push(action);
            // what a run writes right after the line: the hold taken or dropped (module, event flow), the priority
            const told = action.kind === 'supervisor' && !NOT_STARTED.test(a.what) ? confirmingHold((action as KnownRecord).fields) : undefined;
            const hold = told && harnessHolds.has(told.kind) ? undefined : told;
            if (hold) push(known(t, a.who, hold.kind, hold.detail, {}, hold.peer));
            else if ((m = SET_PRIORITY.exec(a.what))) push(known(t, a.who, 'module_priority', a.what, {}, m[1]!));
            if (!withLog && (m = ACTIVATE_SUPERVISOR.exec(a.what) ?? STOP_FUNCTION.exec(a.what))) {
                const what = a.what.startsWith('stop') ? 'function_stopped' : 'function_started';
                push(known(t, m[1]!, 'supervisor', `function ${m[2]!} ${what === 'function_started' ? 'started' : 'stopped'}`, { what, function: m[2]! }));
            }
        }
        cur = -1;
        if (!withLog) {
            const m = /^(start|stop)\s+([A-Za-z_]\w*)\.([A-Za-z_]\w*)/.exec(s.source);
            if (m && s.ok) {
                const what = m[1] === 'start' ? 'function_started' : 'function_stopped';
                push(known(s.timeNs, m[2]!, 'supervisor', `${what} function=${m[3]}`, { what, function: m[3]! }));
            }
            const now = new Set(s.schemas ?? []);
            for (const sc of now) if (!schemas.has(sc)) push(known(s.timeNs, 'ORD', 'scheduler', `activate ${sc}`, { what: 'activate', schema: sc }));
            for (const sc of schemas) if (!now.has(sc)) push(known(s.timeNs, 'ORD', 'scheduler', `deactivate ${sc}`, { what: 'deactivate', schema: sc }));
            schemas = now;
        }
    }
    // records in time order, as a run's trace (a step's record holds what happened up to it); at one
    // time in the harness's order (a deadline miss before the rule it made inactive), else as listed
    const ordered = seqs.every((q, i) => i === 0 || q >= 0);
    return out.map((r, i) => ({ r, i, q: seqs[i]! })).sort((a, b) => time(a.r) - time(b.r) || (ordered ? a.q - b.q : 0) || a.i - b.i).map((x) => x.r);
}

function time(r: TraceRecord): number {
    return r.kind === 'unknown' ? 0 : Number((r as KnownRecord).monoNs);
}
