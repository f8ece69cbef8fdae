/**
 * The shapes of a trace's records, to compare a real run's with a simulation's
 * (differential.bwrap.test.ts): per record kind and writer, which fields its records carry and in
 * which order, so that a field one side writes and the other does not (the supervisors'
 * `event_received` before the simulator wrote `taken_ns`, `rules` and `value`) fails a test.
 *
 * A record's group: its kind, for a `supervisor` or `scheduler` line the `what` the reader typed
 * it as (each such line has its own fields), and who wrote it: a supervisor, ORD or a module (a
 * supervisor's `event_received` has fields a module's has not). Its shape: the field names the
 * reader took out of its detail, in the detail's order, then `port` and `peer` when it has them.
 * A rule change's shape is the kind of its cause (`event`, `elapsed`...) with the cause's fields.
 */
import { isRule, type KnownRecord, type TraceRecord } from '@contract-studio/build-service/trace';

/** Group -> the shapes its records have (each once). */
export type RecordShapes = Map<string, Set<string>>;

function writer(module: string, supervisors: ReadonlySet<string>): string {
    if (supervisors.has(module)) return 'supervisor';
    return module === 'ORD' ? 'ORD' : 'module';
}

/** The shapes of `records` grouped by kind (and `what`) and writer; `supervisors`: the project's. */
export function recordShapes(records: readonly TraceRecord[], supervisors: ReadonlySet<string>): RecordShapes {
    const shapes: RecordShapes = new Map();
    const add = (group: string, shape: string) => {
        let s = shapes.get(group);
        if (!s) shapes.set(group, (s = new Set()));
        s.add(shape);
    };
    for (const r of records) {
        if (r.kind === 'unknown') continue;
        const by = writer((r as KnownRecord).module, supervisors);
        if (isRule(r)) {
            const { kind, ...cause } = r.causeEvent;
            add(`sup_rule by ${by}`, [`cause:${kind}`, ...Object.keys(cause)].join(' '));
            continue;
        }
        const k = r as KnownRecord;
        const what = k.fields['what'];
        const group = `${k.kind}${typeof what === 'string' ? `/${what}` : ''} by ${by}`;
        const fields = Object.keys(k.fields).filter((f) => f !== 'what');
        add(group, [...fields, ...(k.port !== null ? ['port'] : []), ...(k.peer ? ['peer'] : [])].join(' ') || '(no fields)');
    }
    return shapes;
}

/** Per group both sides write: the shapes only the simulation has, and the union of field names each side has when they differ. */
export interface ShapeDifference {
    group: string;
    /** Shapes the simulation writes and the real run never does. */
    onlySimulated: string[];
    /** Field names (of all the group's shapes) one side has and the other never. */
    fieldsOnlyReal: string[];
    fieldsOnlySimulated: string[];
}

const fieldNames = (shapes: Set<string>): Set<string> => new Set([...shapes].flatMap((s) => s.split(' ')));

/** The differences of the groups both `real` and `simulated` write; groups only one side writes are not compared. */
export function shapeDifferences(real: RecordShapes, simulated: RecordShapes): ShapeDifference[] {
    const out: ShapeDifference[] = [];
    for (const [group, sim] of [...simulated].sort(([a], [b]) => a.localeCompare(b))) {
        const run = real.get(group);
        if (!run) continue;
        const onlySimulated = [...sim].filter((s) => !run.has(s));
        const r = fieldNames(run), s = fieldNames(sim);
        const fieldsOnlyReal = [...r].filter((f) => !s.has(f));
        const fieldsOnlySimulated = [...s].filter((f) => !r.has(f));
        if (onlySimulated.length || fieldsOnlyReal.length || fieldsOnlySimulated.length) out.push({ group, onlySimulated, fieldsOnlyReal, fieldsOnlySimulated });
    }
    return out;
}

/** The groups both sides write (what the comparison covered). */
export function commonGroups(real: RecordShapes, simulated: RecordShapes): string[] {
    return [...simulated.keys()].filter((g) => real.has(g)).sort();
}
