/**
 * docs/language-reference.md §6, actions: every reference resolved (linking) and type-checked — `activate schema`
 * and `activate supervisor` arguments, `activate resttime|critical module` on asynchronous
 * modules, `subscribe` port types, `notify` assignments set once. (`parameterize` is checked with
 * schema parameterisations; `compute` and test functions with the function prototypes.)
 */
import { GrammarUtils, type ValidationAcceptor, type ValidationChecks } from 'langium';
import type {
    ActivateModule, ActivateSchema, ActivateSupervisor, CactalAstType, Notify, Rule, Subscribe
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
        Notify: checkNotify,
        Rule: checkActionSeparators
    };
}

/**
 * `subscribe A:2 =* :2 subscribe B:0 =* :1`: the grammar reads two actions without their ';'
 * (each starts with its keyword), so that a missing one is this one error, with its fix (insert
 * it), rather than the parser's recovery and its follow-on errors.
 */
function checkActionSeparators(rule: Rule, accept: ValidationAcceptor): void {
    if (rule.actions.length < 2 || !rule.$cstNode) return;
    // the separators in text order, walked once with the actions (a rule of 40,000 actions stays linear)
    const separators = GrammarUtils.findNodesForKeyword(rule.$cstNode, ';').map((n) => n.offset);
    let k = 0;
    for (let i = 1; i < rule.actions.length; i++) {
        const before = rule.actions[i - 1]!.$cstNode, next = rule.actions[i]!.$cstNode;
        if (!before || !next) continue;
        while (k < separators.length && separators[k]! < before.end) k++;
        if (k < separators.length && separators[k]! < next.offset) continue;
        const word = next.text.split(/\s/, 1)[0];
        report(accept, SupervisorCodes['supervisor-action-separator'],
            `Two actions are separated by ';': one is missing before '${word}'.`,
            { node: rule.actions[i]!, data: { insertAt: before.range.end } });
    }
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

