/**
 * Steps -> the harness's input lines, and its output records (runtime/sim/sim_protocol.h).
 * The records' shape is the JSON output of `contract simulate --format json` per step, meant for
 * reuse by the IDE's Simulate panel.
 */
import type { ScenarioValue, Step } from '../scenario/index.js';
import type { ResolvedLocal } from '../scenario/index.js';

/** `seq`: the harness's order of rules, actions, log lines and records over the session (at one virtual time, a cause comes before its effects). */
export interface RuleChange {
    timeNs: number;
    seq?: number;
    supervisor: string;
    function: string;
    rule: string;
    active: boolean;
    /** As in the `sup_rule` records of a real run: `MAA:2 value="disconnected"`, `elapsed=1000000ns`, `endof(SECOND)`... */
    cause: string;
}

export interface ActionRecord {
    timeNs: number;
    seq?: number;
    /** The engine (supervisor name, `ORD`) or the module that acted. */
    who: string;
    what: string;
}

export interface LogLine {
    timeNs: number;
    seq?: number;
    who: string;
    line: string;
}

/**
 * A typed trace record, as a real run's CSV log of `module` holds it (docs/runtime-api.md "Trace
 * records"): ORD's ord_release / ord_finished / ord_complete / ord_deadline_miss, a virtual
 * module's run_started / run_finished for each release, a supervisor's event_received.
 */
export interface SimTraceRecord {
    timeNs: number;
    seq?: number;
    module: string;
    kind: string;
    peer: string;
    port?: number;
    detail: string;
}

export interface LocalValue {
    supervisor: string;
    function: string;
    name: string;
    type: string;
    /** Numbers and strings as Cactal values; datatypes as their type's print_ writes them. */
    value: string;
}

/** One record of the harness: what happened up to and at one step. */
export interface StepRecord {
    line: number;
    timeNs: number;
    verb: string;
    ok: boolean;
    /** Events: how many supervisors and asynchronous modules (through a connected event flow) received it. */
    delivered?: number;
    error?: string;
    expected?: string;
    actual?: string;
    rules: RuleChange[];
    actions: ActionRecord[];
    log: LogLine[];
    records: SimTraceRecord[];
    schemas?: string[];
    locals?: LocalValue[];
    /** What user functions (tests, computes) printed. */
    output?: string;
    dropped?: number;
    end?: boolean;
    eventsProcessed?: number;
    /** End record: the harness's own wall time from its start to the end (reading its input included). */
    wallNs?: number;
}

const VALUE_ESCAPES: Record<string, string> = { '\n': '\\n', '\t': '\\t', '\r': '\\r', '\b': '\\b', '\f': '\\f', '\0': '\\0' };

/** A value in the text form the types' get_ functions read (tools.h): no raw tab or newline. */
export function valueText(v: ScenarioValue): string {
    switch (v.kind) {
        case 'int':
        case 'real':
        case 'bool':
        case 'enum': // `Mode.AUTO`: get_Mode (common/SharedMode.h) reads it
            return v.text;
        case 'string':
            // the escapes the runtime's string reader decodes (engine_values.c prim_string_get): no raw tab, newline or NUL on the harness's line
            return `"${v.value.replace(/[\\"\n\t\r\b\f\0]/g, (c) => VALUE_ESCAPES[c] ?? `\\${c}`)}"`;
        case 'struct':
            return `{${v.elements.map(valueText).join(',')}}`;
    }
}

function clean(s: string): string {
    return s.replace(/[\t\r\n]/g, ' ');
}

/** The input line of one step, or undefined for a step the harness does not need. */
export function stepLine(step: Step, index: number, locals: Map<number, ResolvedLocal>): string {
    const head = `${step.atNs}\t${step.span.line}\t`;
    switch (step.kind) {
        case 'start':
            return head + ['start', step.supervisor.text, step.function.text, step.args.map((a) => `${a.name.text}=${valueText(a.value)}`).join(',')].join('\t');
        case 'stop':
            return head + ['stop', step.supervisor.text, step.function.text].join('\t');
        case 'event':
            return head + ['event', step.module.text, String(step.port), step.value ? valueText(step.value) : ''].join('\t');
        case 'crash':
            return head + ['crash', step.module.text].join('\t');
        case 'finish':
            return step.afterNs === undefined ? head + ['finish', step.module.text].join('\t')
                : head + ['finish-after', step.module.text, String(step.afterNs), step.once ? 'once' : 'always'].join('\t');
        case 'exec':
            return head + ['exec', step.module.text, String(step.execNs), step.once ? 'once' : 'always'].join('\t');
        case 'expect': {
            const e = step.expectation;
            switch (e.kind) {
                case 'rule': return head + ['expect-rule', e.supervisor.text, e.function.text, e.rule.text, e.active ? '1' : '0'].join('\t');
                case 'function': return head + ['expect-function', e.supervisor.text, e.function.text, e.running ? '1' : '0'].join('\t');
                case 'schema': return head + ['expect-schema', e.schema.text, e.active ? '1' : '0'].join('\t');
                case 'module': return head + ['expect-module', e.module.text, e.running ? '1' : '0'].join('\t');
                case 'count': return head + ['expect-count', e.schema.text, e.what === 'overruns' ? 'overruns' : 'deadline-misses', String(e.count)].join('\t');
                case 'local': {
                    const owner = locals.get(index) ?? { supervisor: e.supervisor?.text ?? '', function: e.function?.text ?? '' };
                    return head + ['expect-local', owner.supervisor, owner.function, e.local.text, clean(valueText(e.value))].join('\t');
                }
            }
        }
    }
}
