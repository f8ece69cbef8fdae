/**
 * A periodic schema activation that ORD is certain to refuse (docs/language-reference.md, "Schema
 * conflicts ORD is certain to refuse"). ORD refuses to
 * activate a periodic schema that shares a module with an active one and emits `ORD:1`
 * (docs/engines.md, "ORD"); when one rule, or rules that become active together (one starts on
 * `started` of the other, or both on the same event), activate such schemas, the second activation
 * is refused every time. Rules of different functions or activated at unrelated times are not
 * decidable statically and are not reported.
 */
import { isActivateSchema, type ActivateSchema, type CactalAstType, type Rule, type Schema, type SupervisionFunction } from '../generated/ast.js';
import type { ValidationAcceptor, ValidationChecks } from 'langium';
import type { CactalServices } from '../cactal-module.js';
import { rulesOf } from '../model/blocks.js';
import { activeTogether, groupOf, sharedModules } from '../model/schema-conflicts.js';
import { SupervisorCodes } from './codes/supervisors.js';
import { report } from './report.js';

export function schemaConflictChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    return { SupervisionFunction: checkSchemaConflicts };
}

interface Activation {
    rule: Rule;
    action: ActivateSchema;
    schema: Schema;
}

function activationsOf(rule: Rule): Activation[] {
    return rule.actions.filter(isActivateSchema).flatMap((action) => {
        const schema = action.schema?.ref;
        return schema && schema.kind === 'periodic' ? [{ rule, action, schema }] : [];
    });
}

function checkSchemaConflicts(fn: SupervisionFunction, accept: ValidationAcceptor): void {
    const links = activeTogether(fn);
    const rules = rulesOf(fn);
    const declared = new Map(rules.map((r, i) => [r, i]));
    const seen = new Set<Rule>();
    for (const rule of rules) {
        if (seen.has(rule)) continue;
        const group = groupOf(rule, links);
        for (const r of group.keys()) seen.add(r);
        // declaration order, each rule's actions in written order (sorting the group, not filtering every rule: linear in the rules)
        const activations = [...group.keys()].sort((a, b) => (declared.get(a) ?? 0) - (declared.get(b) ?? 0)).flatMap(activationsOf);
        for (let k = 1; k < activations.length; k++) {
            const later = activations[k]!;
            for (const earlier of activations.slice(0, k)) {
                const modules = sharedModules(later.schema, earlier.schema);
                if (modules.length === 0) continue;
                report(accept, SupervisorCodes['supervisor-schema-conflict'], conflictMessage(earlier, later, modules.map((m) => m.name), links),
                    { node: later.action, property: 'schema', data: { conflictsWith: earlier.schema.name, modules: modules.map((m) => m.name) } });
                break;
            }
        }
    }
}

function conflictMessage(earlier: Activation, later: Activation, modules: string[], links: ReturnType<typeof activeTogether>): string {
    const shared = `${modules.length === 1 ? 'module' : 'modules'} ${modules.join(', ')}`;
    const refusal = 'ORD refuses an activation while a schema sharing a module is active and emits ORD:1 (docs/engines.md)';
    const fix = 'Activate them in rules that are never active together (e.g. start the second rule on endof of the first).';
    const same = earlier.schema === later.schema;
    if (earlier.rule === later.rule) {
        return same
            ? `Rule ${later.rule.name} activates periodic schema ${later.schema.name} twice: ${refusal}, so the second activation is always refused. Activate it once.`
            : `Rule ${later.rule.name} activates periodic schemas ${earlier.schema.name} and ${later.schema.name}, which share ${shared}: ${refusal}, so ${later.schema.name} is always refused. ${fix}`;
    }
    const why = groupOf(earlier.rule, links).get(later.rule)?.join(', then ') ?? '';
    const what = same ? `periodic schema ${later.schema.name} is also activated by rule ${earlier.rule.name}`
        : `periodic schema ${later.schema.name} shares ${shared} with ${earlier.schema.name}, activated by rule ${earlier.rule.name}`;
    return `In rule ${later.rule.name}, ${what}, and the two rules are active together (${why}): ${refusal}, so the second activation is always refused. ${fix}`;
}
