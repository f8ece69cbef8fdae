/**
 * docs/language-reference.md §5: the scheduler configuration — one per project, synchronous modules and periodic
 * schemas only, every module of a listed schema listed, every periodic schema a supervisor
 * activates listed, and the combined utilisation of the listed schemas.
 */
import { type Reference, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isSchedulerModules, isSchedulerSchemas,
    type ActivateSchema, type CactalAstType, type Module, type SchedulerConfiguration, type Schema
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { scheduledModulesOf, scheduledSchemasOf } from '../model/blocks.js';
import { SchedulerCodes } from './codes/scheduler.js';
import { ProjectElements } from './project-elements.js';
import { report } from './report.js';
import { combinedUtilisation, schemaModules, schemaUtilisation } from './timing-analysis.js';

export function schedulerChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const elements = new ProjectElements(services);
    return {
        SchedulerConfiguration: [
            (config, accept) => checkUnique(config, elements, accept),
            checkDuplicateEntries,
            checkListedModules,
            checkListedSchemas,
            checkUtilisation
        ],
        ActivateSchema: (action, accept) => checkActivatedSchemaListed(action, elements, accept)
    };
}

function checkUnique(config: SchedulerConfiguration, elements: ProjectElements, accept: ValidationAcceptor): void {
    const all = elements.schedulerConfigurations(config);
    if (all.length <= 1) return;
    const where = elements.otherLocations(config, all.map((c) => c.uri));
    report(accept, SchedulerCodes['scheduler-duplicate'],
        `The project already has a scheduler configuration (also in ${where}); there is one per project: merge their modules and schemas.`,
        { node: config, keyword: 'scheduler' });
}

/** Reports the second and later listing of the same module or schema. */
function checkDuplicateEntries(config: SchedulerConfiguration, accept: ValidationAcceptor): void {
    const seen = new Set<Module | Schema>();
    for (const block of config.blocks) {
        const refs: Array<Reference<Module | Schema>> = isSchedulerModules(block) ? block.modules : block.schemas;
        refs.forEach((ref, index) => {
            const target = ref.ref;
            if (!target) return;
            if (seen.has(target)) {
                report(accept, SchedulerCodes['scheduler-entry-duplicate'],
                    `${target.name} is already listed in the scheduler configuration: list it once.`,
                    { node: block, property: (isSchedulerModules(block) ? 'modules' : 'schemas') as never, index });
            }
            seen.add(target);
        });
    }
}

function checkListedModules(config: SchedulerConfiguration, accept: ValidationAcceptor): void {
    for (const block of config.blocks.filter(isSchedulerModules)) {
        block.modules.forEach((ref, index) => {
            const module = ref.ref;
            if (module && module.kind === 'asynchronous') {
                report(accept, SchedulerCodes['scheduler-module-kind'],
                    `Module ${module.name} is asynchronous: the scheduler configuration lists synchronous modules only (asynchronous modules are not scheduled by ORD).`,
                    { node: block, property: 'modules', index });
            }
        });
    }
}

function checkListedSchemas(config: SchedulerConfiguration, accept: ValidationAcceptor): void {
    // by name: a listed module whose name does not resolve (its file not imported) has its own
    // error, and is listed all the same (no second error saying it is not)
    const listedModules = new Set(scheduledModulesOf(config).map((r) => r.ref?.name ?? r.$refText));
    for (const block of config.blocks.filter(isSchedulerSchemas)) {
        block.schemas.forEach((ref, index) => {
            const schema = ref.ref;
            if (!schema) return;
            if (schema.kind === 'event') {
                report(accept, SchedulerCodes['scheduler-schema-kind'],
                    `Schema ${schema.name} is an event schema: the scheduler configuration lists periodic schemas only (supervisors run event schemas themselves).`,
                    { node: block, property: 'schemas', index });
                return;
            }
            const missing = schemaModules(schema).filter((m) => !listedModules.has(m.name));
            if (missing.length) {
                report(accept, SchedulerCodes['scheduler-module-unlisted'],
                    `Schema ${schema.name} uses ${missing.map((m) => m.name).join(', ')}, which ${missing.length === 1 ? 'is' : 'are'} not listed in the 'modules' block of the scheduler configuration: list every module of a listed schema.`,
                    { node: block, property: 'schemas', index, data: { modules: missing.map((m) => m.name) } });
            }
        });
    }
}

function checkUtilisation(config: SchedulerConfiguration, accept: ValidationAcceptor): void {
    const schemas = [...new Set(scheduledSchemasOf(config).map((r) => r.ref).filter((s): s is Schema => s?.kind === 'periodic'))];
    const total = combinedUtilisation(schemas);
    if (total <= 1) return;
    const parts = schemas
        .map((s) => ({ name: s.name, u: schemaUtilisation(s) ?? 0 }))
        .filter((p) => p.u > 0)
        .sort((a, b) => b.u - a.u)
        .slice(0, 5)
        .map((p) => `${p.name} ${p.u.toFixed(2)}`);
    report(accept, SchedulerCodes['scheduler-utilisation'],
        `The listed schemas together use ${total.toFixed(2)} of the processor (sum of C / PERIOD: ${parts.join(', ')}${schemas.length > 5 ? ', ...' : ''}), more than 1: they cannot all run in time if active at once.`,
        { node: config, keyword: 'scheduler' });
}

function checkActivatedSchemaListed(action: ActivateSchema, elements: ProjectElements, accept: ValidationAcceptor): void {
    const schema = action.schema?.ref;
    if (!schema || schema.kind !== 'periodic') return;
    const configs = elements.schedulerConfigurations(action);
    if (configs.some((c) => scheduledSchemasOf(c.node).some((r) => r.ref === schema))) return;
    report(accept, SchedulerCodes['scheduler-schema-unlisted'],
        configs.length === 0
            ? `Periodic schema ${schema.name} is activated here, but the project has no scheduler configuration: add 'scheduler configuration { modules { ... } schemas { ${schema.name}; } }'.`
            : `Periodic schema ${schema.name} is activated here but not listed in the scheduler configuration: add it to its 'schemas' block (ORD only schedules listed schemas).`,
        { node: action, property: 'schema', data: { schema: schema.name } });
}
