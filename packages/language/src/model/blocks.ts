/**
 * Block accessors: modules, schemas and scheduler configurations keep their blocks in the order
 * written (`blocks`), so that out-of-order blocks parse and validation can name the right order.
 * These helpers give the content regardless of order (all blocks of one kind merged).
 */
import type { Reference } from 'langium';
import {
    isCommunicationsBlock, isDataFlowsBlock, isEventFlowsBlock, isModule, isModulesBlock, isParametersBlock,
    isRealtimeBlock, isSchedulerModules, isSchedulerSchemas, isSchedulingBlock, isSchedulingGraphBlock,
    type Communication, type LocalVariable, type Module, type ModuleInstance, type Parameter, type Port,
    type Precedence, type Rule, type SchedulerConfiguration, type Schema, type SupervisionFunction,
    type Supervisor, type TimeProperty
} from '../generated/ast.js';
import { timeToNanoseconds } from './time.js';

export function parametersOf(module: Module): Parameter[] {
    return module.blocks.filter(isParametersBlock).flatMap((b) => b.parameters);
}

export function dataPortsOf(module: Module): Port[] {
    return module.blocks.filter(isDataFlowsBlock).flatMap((b) => b.ports);
}

/** Event ports of a module or a supervisor. */
export function eventPortsOf(owner: Module | Supervisor): Port[] {
    if (isModule(owner)) return owner.blocks.filter(isEventFlowsBlock).flatMap((b) => b.ports);
    return owner.eventFlows.flatMap((b) => b.ports);
}

export function schedulingPropertiesOf(module: Module): TimeProperty[] {
    return module.blocks.filter(isSchedulingBlock).flatMap((b) => b.properties);
}

/** The nominal execution time `C` of a synchronous module, in nanoseconds (undefined if absent/malformed). */
export function computeTimeNs(module: Module): number | undefined {
    const c = schedulingPropertiesOf(module).find((p) => p.name === 'C');
    const ns = c?.value ? timeToNanoseconds(c.value.text) : Number.NaN;
    return Number.isFinite(ns) ? ns : undefined;
}

export function realtimePropertiesOf(schema: Schema): TimeProperty[] {
    return schema.blocks.filter(isRealtimeBlock).flatMap((b) => b.properties);
}

function realtimeNs(schema: Schema, name: string): number | undefined {
    const p = realtimePropertiesOf(schema).find((q) => q.name === name);
    const ns = p?.value ? timeToNanoseconds(p.value.text) : Number.NaN;
    return Number.isFinite(ns) ? ns : undefined;
}

/** `PERIOD` of a periodic schema in nanoseconds. */
export function periodNs(schema: Schema): number | undefined {
    return realtimeNs(schema, 'PERIOD');
}

/** `CRITICAL_DELAY` of a periodic schema in nanoseconds. */
export function criticalDelayNs(schema: Schema): number | undefined {
    return realtimeNs(schema, 'CRITICAL_DELAY');
}

export function moduleInstancesOf(schema: Schema): ModuleInstance[] {
    return schema.blocks.filter(isModulesBlock).flatMap((b) => b.instances);
}

export function precedencesOf(schema: Schema): Precedence[] {
    return schema.blocks.filter(isSchedulingGraphBlock).flatMap((b) => b.edges);
}

export function communicationsOf(schema: Schema): Communication[] {
    return schema.blocks.filter(isCommunicationsBlock).flatMap((b) => b.communications);
}

export function scheduledModulesOf(config: SchedulerConfiguration): Array<Reference<Module>> {
    return config.blocks.filter(isSchedulerModules).flatMap((b) => b.modules);
}

export function scheduledSchemasOf(config: SchedulerConfiguration): Array<Reference<Schema>> {
    return config.blocks.filter(isSchedulerSchemas).flatMap((b) => b.schemas);
}

export function localsOf(fn: SupervisionFunction): LocalVariable[] {
    return fn.locals.flatMap((b) => b.variables);
}

export function rulesOf(fn: SupervisionFunction): Rule[] {
    return fn.rules.flatMap((b) => b.rules);
}
