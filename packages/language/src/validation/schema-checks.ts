/**
 * docs/language-reference.md §4: schemas — unique names and parameters, block order and blocks forbidden in event
 * schemas, module kinds, the scheduling graph (only the schema's modules, acyclic), communications
 * (kinds, types, periodicity, one producer per input port) and the timing analysis warnings.
 */
import { type AstNode, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isDataCommunication, isModulesBlock, isRealtimeBlock, isSchedulingGraphBlock,
    type CactalAstType, type Communication, type Module, type Port, type Schema, type SchemaBlock
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { communicationsOf, criticalDelayNs, moduleInstancesOf, periodNs, precedencesOf, realtimePropertiesOf } from '../model/blocks.js';
import { formatNanoseconds } from '../model/time.js';
import { C_INT_MAX } from '../model/numbers.js';
import { sameType, typeName, typeOf } from '../model/types.js';
import { checkBlockOrder, type BlockOrder } from './block-order.js';
import { SchemaCodes } from './codes/schemas.js';
import { TypeCodes } from './codes/types.js';
import { SchedulerCodes } from './codes/scheduler.js';
import { ProjectElements } from './project-elements.js';
import { ProjectNames } from './project-index.js';
import { report, type ReportInfo } from './report.js';
import { criticalPath, precedenceCycle, schemaModules } from './timing-analysis.js';
import { writtenInt } from './value-checker.js';

const BLOCK_ORDER = ['realtime', 'modules', 'scheduling graph', 'communications'] as const;
type BlockName = (typeof BLOCK_ORDER)[number];
const REALTIME_PROPERTIES = ['PERIOD', 'CRITICAL_DELAY'];

function blockName(block: SchemaBlock): BlockName {
    if (isRealtimeBlock(block)) return 'realtime';
    if (isModulesBlock(block)) return 'modules';
    if (isSchedulingGraphBlock(block)) return 'scheduling graph';
    return 'communications';
}

function blockKeyword(block: SchemaBlock): string {
    return isSchedulingGraphBlock(block) ? 'scheduling' : blockName(block);
}

const SCHEMA_BLOCKS: BlockOrder<SchemaBlock, BlockName> = {
    order: BLOCK_ORDER, nameOf: blockName, keywordOf: blockKeyword,
    duplicate: SchemaCodes['schema-block-duplicate'], outOfOrder: SchemaCodes['schema-block-order']
};

export function schemaChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const names = new ProjectNames(services);
    const elements = new ProjectElements(services);
    return {
        Schema: [
            (schema, accept) => checkSchemaName(schema, names, accept),
            checkSchemaParameters,
            checkSchemaBlocks,
            checkSchemaModules,
            checkSchedulingGraph,
            checkCommunications,
            checkTiming,
            (schema, accept) => checkSchedulerExists(schema, elements, accept)
        ]
    };
}

/** Longest schema or supervision-function name: the runtime's request fields hold 63 characters and a NUL (CONTRACT_NAME_MAX, CONTRACT_FUNCTION_MAX). */
export const NAME_CHARS_MAX = 63;

function checkSchemaName(schema: Schema, names: ProjectNames, accept: ValidationAcceptor): void {
    if (!schema.name) return;
    if (schema.name.length > NAME_CHARS_MAX) {
        report(accept, SchemaCodes['schema-name-too-long'],
            `Schema name '${schema.name.slice(0, 20)}…' has ${schema.name.length} characters: at most ${NAME_CHARS_MAX} (the requests that activate a schema carry its name in 64 bytes).`,
            { node: schema, property: 'name' });
    }
    const same = names.byName(['Schema'], schema).get(schema.name);
    if (same.length <= 1) return;
    const where = names.otherLocations(schema, same.map((d) => d.documentUri));
    report(accept, SchemaCodes['schema-name-duplicate'],
        `Schema '${schema.name}' is defined more than once (also in ${where}); schema names are unique among all schemas, periodic and event.`,
        { node: schema, property: 'name' });
}

function checkSchemaParameters(schema: Schema, accept: ValidationAcceptor): void {
    const seen = new Set<string>();
    for (const p of schema.parameters) {
        if (!p.name) continue;
        if (seen.has(p.name)) {
            report(accept, SchemaCodes['schema-parameter-duplicate'],
                `Schema ${schema.name} already has a parameter '${p.name}': each parameter needs its own name (activations set them by name).`,
                { node: p, property: 'name' });
        }
        seen.add(p.name);
    }
}

function checkSchemaBlocks(schema: Schema, accept: ValidationAcceptor): void {
    for (const block of schema.blocks) {
        const name = blockName(block);
        if (schema.kind === 'event' && (name === 'realtime' || name === 'scheduling graph')) {
            report(accept, SchemaCodes['schema-event-forbidden-block'],
                `Event schema ${schema.name} is not scheduled: remove the '${name}' block, or declare it 'periodic schema' (with synchronous modules).`,
                { node: block, keyword: blockKeyword(block) });
        }
    }
    checkBlockOrder(`Schema ${schema.name}`, schema.blocks, SCHEMA_BLOCKS, accept);
    if (schema.kind !== 'periodic') return;

    const realtime = schema.blocks.filter(isRealtimeBlock);
    if (realtime.length === 0) {
        report(accept, SchemaCodes['schema-realtime-missing'],
            `Periodic schema ${schema.name} needs a 'realtime { PERIOD=<time>; CRITICAL_DELAY=<time>; }' block (e.g. PERIOD=10ms; CRITICAL_DELAY=10ms;).`,
            { node: schema, property: 'name' });
        return;
    }
    const given = new Set<string>();
    for (const p of realtimePropertiesOf(schema)) {
        if (!REALTIME_PROPERTIES.includes(p.name)) {
            report(accept, SchemaCodes['schema-realtime-property'],
                `Unknown realtime property '${p.name}': the realtime block gives PERIOD and CRITICAL_DELAY.`, { node: p, property: 'name' });
        } else if (given.has(p.name)) {
            report(accept, SchemaCodes['schema-realtime-property'], `${p.name} is given twice in schema ${schema.name}: keep one.`, { node: p, property: 'name' });
        }
        given.add(p.name);
    }
    const missing = REALTIME_PROPERTIES.filter((p) => !given.has(p));
    if (missing.length) {
        report(accept, SchemaCodes['schema-realtime-missing'],
            `The realtime block of periodic schema ${schema.name} must give ${missing.join(' and ')} (e.g. ${missing.map((m) => `${m}=10ms;`).join(' ')}).`,
            { node: realtime[0]!, keyword: 'realtime' });
    }
}

function checkSchemaModules(schema: Schema, accept: ValidationAcceptor): void {
    const seen = new Set<Module>();
    const wanted = schema.kind === 'periodic' ? 'synchronous' : 'asynchronous';
    for (const instance of moduleInstancesOf(schema)) {
        const module = instance.module?.ref;
        if (!module) continue;
        if (seen.has(module)) {
            report(accept, SchemaCodes['schema-module-duplicate'],
                `Module ${module.name} is already in schema ${schema.name}: each module appears once (merge its parameterisations).`,
                { node: instance, property: 'module' });
            continue;
        }
        seen.add(module);
        if (module.kind && module.kind !== wanted) {
            report(accept, SchemaCodes['schema-module-kind'],
                schema.kind === 'periodic'
                    ? `Module ${module.name} is asynchronous: a periodic schema assembles synchronous modules only (ORD schedules them); use it in an event schema.`
                    : `Module ${module.name} is synchronous: an event schema assembles asynchronous modules only; use it in a periodic schema.`,
                { node: instance, property: 'module' });
        }
    }
}

function checkSchedulingGraph(schema: Schema, accept: ValidationAcceptor): void {
    const modules = schemaModules(schema);
    for (const edge of precedencesOf(schema)) {
        for (const property of ['from', 'to'] as const) {
            const m = edge[property]?.ref;
            if (m && !modules.includes(m)) {
                report(accept, SchemaCodes['schema-foreign-module'],
                    `Module ${m.name} is not in the modules of schema ${schema.name} (${modules.map((x) => x.name).join(', ') || 'none'}): add it to the 'modules' block or remove this precedence.`,
                    { node: edge, property });
            }
        }
    }
    const cycle = precedenceCycle(schema);
    if (cycle) {
        const first = cycle[0]!;
        const second = cycle[1]!;
        const edge = precedencesOf(schema).find((e) => e.from?.ref === first && e.to?.ref === second);
        report(accept, SchemaCodes['schema-graph-cycle'],
            `The scheduling graph of ${schema.name} has a cycle: ${cycle.map((m) => m.name).join(' -> ')}. Precedences must be acyclic (each says which module runs first in a cycle).`,
            (edge ? { node: edge } : { node: schema, property: 'name' }) as ReportInfo<AstNode>);
    }
}

function portText(module: Module | undefined, port: Port | undefined, written: string | undefined): string {
    return `${module?.name ?? '?'}:${port?.index ?? written ?? '?'}`;
}

function checkCommunications(schema: Schema, accept: ValidationAcceptor): void {
    const modules = schemaModules(schema);
    const producers = new Map<Port, Communication>();
    for (const comm of communicationsOf(schema)) {
        const data = isDataCommunication(comm);
        const kind = data ? 'data' : 'event';
        if (schema.kind === 'periodic' && !data) {
            report(accept, SchemaCodes['schema-communication-kind'],
                `A periodic schema connects data ports ('A:o -> B:i * k'); event communications ('=*', '=>') belong in event schemas.`,
                { node: comm, property: 'mode' });
        } else if (schema.kind === 'event' && data) {
            report(accept, SchemaCodes['schema-communication-kind'],
                `An event schema connects event ports ('A:o =* B:i' continuous or 'A:o => B:i' one shot); data communications ('->') belong in periodic schemas.`,
                { node: comm, keyword: '->' });
        }
        const source = comm.source?.ref;
        const target = comm.target?.ref;
        for (const [property, m] of [['source', source], ['target', target]] as const) {
            if (m && !modules.includes(m)) {
                report(accept, SchemaCodes['schema-foreign-module'],
                    `Module ${m.name} is not in the modules of schema ${schema.name} (${modules.map((x) => x.name).join(', ') || 'none'}): add it to the 'modules' block.`,
                    { node: comm, property });
            }
        }
        const out = comm.sourcePort?.ref;
        const inp = comm.targetPort?.ref;
        if (out && inp) {
            const outType = typeOf(out.type);
            const inType = typeOf(inp.type);
            if (!sameType(outType, inType)) {
                report(accept, SchemaCodes['schema-communication-type'],
                    `Port ${portText(source, out, undefined)} is an output ${kind} port of type ${typeName(outType)}; ${portText(target, inp, undefined)} expects ${typeName(inType)}: connected ports carry the same type.`,
                    { node: comm, property: 'targetPort' });
            }
        }
        if (data && comm.periodicity !== undefined && (!Number.isInteger(comm.periodicity) || comm.periodicity < 1)) {
            report(accept, SchemaCodes['schema-periodicity'],
                `Periodicity ${comm.periodicity} is not allowed: it is an integer >= 1 (* 1: every activation of ${source?.name ?? 'the producer'}, * 2: every second one, ...).`,
                { node: comm, property: 'periodicity' });
        } else if (data && comm.periodicity !== undefined && comm.periodicity > C_INT_MAX) {
            report(accept, TypeCodes['number-out-of-range'],
                `Periodicity ${writtenInt(comm, 'periodicity')} is too large: a periodicity is a C int in the generated C and the runtime, at most ${C_INT_MAX}.`,
                { node: comm, property: 'periodicity' });
        }
        if (inp) {
            const previous = producers.get(inp);
            if (previous) {
                report(accept, SchemaCodes['schema-input-multiple-producers'],
                    `Input ${kind} port ${portText(target, inp, comm.targetPort?.$refText)} already has a producer in this schema (${portText(previous.source?.ref, previous.sourcePort?.ref, previous.sourcePort?.$refText)}): an input port has at most one producer.`,
                    { node: comm, property: 'targetPort' });
            } else {
                producers.set(inp, comm);
            }
        }
    }
}

function checkTiming(schema: Schema, accept: ValidationAcceptor): void {
    if (schema.kind !== 'periodic') return;
    const period = periodNs(schema);
    const delay = criticalDelayNs(schema);
    if (delay === undefined || delay <= 0) return;
    const delayProperty = realtimePropertiesOf(schema).find((p) => p.name === 'CRITICAL_DELAY');
    const where = (delayProperty ? { node: delayProperty, property: 'value' } : { node: schema, property: 'name' }) as ReportInfo<AstNode>;
    if (period !== undefined && period > 0 && delay > period) {
        report(accept, SchemaCodes['schema-timing-delay-exceeds-period'],
            `CRITICAL_DELAY (${formatNanoseconds(delay)}) exceeds PERIOD (${formatNanoseconds(period)}) in schema ${schema.name}: a late cycle would still run at the next tick (ORD skips that release) before its lateness is reported; use CRITICAL_DELAY <= PERIOD.`,
            where);
    }
    const path = criticalPath(schema);
    if (path && path.ns > delay) {
        report(accept, SchemaCodes['schema-timing-critical-path'],
            `The critical path of ${schema.name} takes ${formatNanoseconds(path.ns)} (${path.modules.map((m) => m.name).join(' -> ')}, summed C), more than CRITICAL_DELAY (${formatNanoseconds(delay)}): every cycle is expected to be late. Shorten the path (fewer precedences, smaller C) or raise CRITICAL_DELAY.`,
            where);
    }
}

function checkSchedulerExists(schema: Schema, elements: ProjectElements, accept: ValidationAcceptor): void {
    if (schema.kind !== 'periodic' || !schema.name) return;
    if (elements.schedulerConfigurations(schema).length > 0) return;
    report(accept, SchedulerCodes['scheduler-missing'],
        `The project has periodic schemas but no 'scheduler configuration': ORD would schedule nothing. Add a file with 'scheduler configuration { modules { ... } schemas { ${schema.name}; } }'.`,
        { node: schema, property: 'name' });
}

