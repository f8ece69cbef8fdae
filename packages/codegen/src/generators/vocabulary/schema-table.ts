import type { Schema } from '../../model/architecture.js';
import { variableBlock } from './layouts.js';
import type { TableBuilder } from './table-builder.js';
import { assignments, type Resolver } from './value-refs.js';

/** Emits the ContractSchema of `schema` once per vocabulary.c; returns `&schema_<name>`. */
export function schemaTable(b: TableBuilder, schema: Schema, emitted: Map<string, string>): string {
    const known = emitted.get(schema.name);
    if (known) return known;
    const S = schema.name;
    const params = variableBlock(b, `schema_${S}_params`, schema.parameters);
    const resolve: Resolver = (name) => {
        const i = schema.parameters.findIndex((p) => p.name === name);
        return i < 0 ? undefined : { kind: 'CONTRACT_REF_PARAM', index: i, type: schema.parameters[i]!.type };
    };
    const moduleNames = schema.modules.map((m) => m.module);
    const modules = schema.modules.map((m) => {
        const module = b.index.modules.get(m.module);
        const settings = m.settings.flatMap((s) => {
            const port = module?.parameters.find((p) => p.index === s.port);
            if (!port) return [];
            const parts = assignments(b, 0, port.type, [], s.value, resolve);
            const arr = b.array(`schema_${S}_${m.module}_p${s.port}`, 'ContractAssign', parts);
            return [`{${s.port}, ${b.typeRef(port.type)}, ${parts.length}, ${arr}, "${port.name}"}`];
        });
        const arr = b.array(`schema_${S}_${m.module}_settings`, 'ContractParamSetting', settings);
        return `{"${m.module}", ${settings.length}, ${arr}}`;
    });
    const precedences = schema.precedences
        .map((p) => [moduleNames.indexOf(p.before), moduleNames.indexOf(p.after)])
        .filter(([x, y]) => x! >= 0 && y! >= 0)
        .map(([x, y]) => `{${x}, ${y}}`);
    const data = schema.dataFlows.map((f) => `{"${f.source}", ${f.sourcePort}, "${f.target}", ${f.targetPort}, ${f.periodicity}}`);
    const events = schema.eventFlows.map((f) => `{"${f.source}", ${f.sourcePort}, "${f.target}", ${f.targetPort}, ${f.oneShot ? 'CONTRACT_ONESHOT' : 'CONTRACT_CONTINUOUS'}}`);
    const mods = b.array(`schema_${S}_modules`, 'ContractSchemaModule', modules);
    const prec = b.array(`schema_${S}_precedences`, 'ContractPrecedence', precedences);
    const df = b.array(`schema_${S}_data_flows`, 'ContractDataFlow', data);
    const ef = b.array(`schema_${S}_event_flows`, 'ContractEventFlow', events);
    const name = b.unique(`schema_${S}`);
    b.define(`static const ContractSchema ${name} = {\n    "${S}", ${schema.kind === 'periodic' ? 'CONTRACT_SCHEMA_PERIODIC' : 'CONTRACT_SCHEMA_EVENT'}, ${schema.periodNs ?? 0}, ${schema.criticalDelayNs ?? 0},\n    ${params.count}, ${params.array}, ${params.size},\n    ${modules.length}, ${mods}, ${precedences.length}, ${prec}, ${data.length}, ${df}, ${events.length}, ${ef}};`);
    emitted.set(S, `&${name}`);
    return `&${name}`;
}

