/**
 * docs/language-reference.md §6, actions: every reference resolved (linking) and type-checked — `activate schema`
 * and `activate supervisor` arguments, `activate resttime|critical module` on asynchronous
 * modules, `subscribe` port types, `notify` assignments set once. (`parameterize` is checked with
 * schema parameterisations; `compute` and test functions with the function prototypes.)
 */
import type { ValidationAcceptor, ValidationChecks } from 'langium';
import type {
    ActivateModule, ActivateSchema, ActivateSupervisor, CactalAstType, Notify, Subscribe
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { sameType, typeName, typeOf, variableRefText } from '../model/types.js';
import { SupervisorCodes } from './codes/supervisors.js';
import { report } from './report.js';
import { checkValue } from './value-checker.js';

export function supervisorActionChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    return {
        ActivateSchema: checkActivateSchema,
        ActivateSupervisor: checkActivateSupervisor,
        ActivateModule: checkActivateModule,
        Subscribe: checkSubscribe,
        Notify: checkNotify
    };
}


function reportDuplicate(seen: Set<string>, name: string, node: Parameters<typeof report>[3]['node'], owner: string, accept: ValidationAcceptor): void {
    if (seen.has(name)) {
        report(accept, SupervisorCodes['supervisor-argument-duplicate'], `'${name}' is already set in this ${owner}: set each one once.`, { node });
    }
    seen.add(name);
}

function checkActivateSchema(action: ActivateSchema, accept: ValidationAcceptor): void {
    const schema = action.schema?.ref;
    const seen = new Set<string>();
    for (const a of action.assignments) {
        const parameter = a.parameter?.ref;
        if (!parameter) continue;
        reportDuplicate(seen, parameter.name, a, `activation of ${schema?.name ?? 'the schema'}`, accept);
        if (a.value) checkValue(a.value, typeOf(parameter.type), accept, { allowVariables: true, what: `parameter '${parameter.name}' of schema ${schema?.name ?? '?'}` });
    }
}

function checkActivateSupervisor(action: ActivateSupervisor, accept: ValidationAcceptor): void {
    const fn = action.function?.ref;
    const seen = new Set<string>();
    for (const a of action.assignments) {
        const parameter = a.parameter?.ref;
        if (!parameter) continue;
        reportDuplicate(seen, parameter.name, a, `activation of ${action.supervisor?.ref?.name ?? '?'}.${fn?.name ?? '?'}`, accept);
        if (a.value) checkValue(a.value, typeOf(parameter.type), accept, { allowVariables: true, what: `parameter '${parameter.name}' of ${action.supervisor?.ref?.name ?? '?'}.${fn?.name ?? '?'}` });
    }
}

function checkActivateModule(action: ActivateModule, accept: ValidationAcceptor): void {
    const module = action.module?.ref;
    if (!module || module.kind !== 'synchronous') return;
    report(accept, SupervisorCodes['supervisor-module-not-async'],
        `Module ${module.name} is synchronous: 'activate ${action.priority ?? 'resttime'} module' starts an asynchronous module; a synchronous module runs through a periodic schema (activate schema ...).`,
        { node: action, property: 'module' });
}

function checkSubscribe(action: Subscribe, accept: ValidationAcceptor): void {
    const source = action.sourcePort?.ref;
    const target = action.targetPort?.ref;
    if (!source || !target) return;
    const out = typeOf(source.type);
    const inp = typeOf(target.type);
    if (sameType(out, inp)) return;
    report(accept, SupervisorCodes['supervisor-subscribe-type'],
        `Port ${action.source?.ref?.name ?? '?'}:${source.index} is an output event port of type ${typeName(out)}; input event port :${target.index} (${target.name}) expects ${typeName(inp)}: subscribe it to an input port of type ${typeName(out)}.`,
        { node: action, property: 'targetPort' });
}

function checkNotify(action: Notify, accept: ValidationAcceptor): void {
    const seen = new Set<string>();
    for (const a of action.assignments) {
        if (!a.target) continue;
        reportDuplicate(seen, variableRefText(a.target), a, 'notify', accept);
    }
}

