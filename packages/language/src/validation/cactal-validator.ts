/**
 * Registers all Cactal validation checks. Each area keeps its checks in its own file
 * (`<area>-checks.ts`, exporting `function <area>Checks(services): ValidationChecks<CactalAstType>`)
 * and its codes in `codes/<area>.ts`; add new areas to the list below.
 */
import type { ValidationChecks } from 'langium';
import type { CactalAstType } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { importChecks } from './import-checks.js';
import { typeChecks } from './type-checks.js';
import { moduleChecks } from './module-checks.js';
import { identifierChecks } from './identifier-checks.js';
import { schemaChecks } from './schema-checks.js';
import { parameterisationChecks } from './parameterisation-checks.js';
import { schedulerChecks } from './scheduler-checks.js';
import { supervisorChecks } from './supervisor-checks.js';
import { supervisorRuleChecks } from './supervisor-rule-checks.js';
import { supervisorActionChecks } from './supervisor-action-checks.js';
import { schemaConflictChecks } from './schema-conflict-checks.js';
import { architectureChecks } from './architecture-checks.js';

export type CheckFactory = (services: CactalServices) => ValidationChecks<CactalAstType>;

/** The check sets, one per area. */
export const CHECK_FACTORIES: CheckFactory[] = [importChecks, typeChecks, moduleChecks, identifierChecks,
    schemaChecks, parameterisationChecks, schedulerChecks, supervisorChecks, supervisorRuleChecks, supervisorActionChecks,
    schemaConflictChecks, architectureChecks];

export function registerValidationChecks(services: CactalServices): void {
    const registry = services.validation.ValidationRegistry;
    for (const factory of CHECK_FACTORIES) {
        registry.register(factory(services));
    }
}
