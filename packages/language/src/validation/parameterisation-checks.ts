/**
 * docs/language-reference.md §4 and §6: module parameterisations `(value :N, ...)`, in a schema's `modules` block
 * and in a supervisor's `parameterize M(...)`: the port exists (linking), each port is set once,
 * and the value fits the parameter's type (constants, or schema parameters / supervisor locals and
 * event-port variables with field paths).
 */
import type { ValidationAcceptor, ValidationChecks } from 'langium';
import type { CactalAstType, ModuleInstance, Parameter, Parameterize, ParameterSetting } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { typeOf } from '../model/types.js';
import { SchemaCodes } from './codes/schemas.js';
import { report } from './report.js';
import { checkValue } from './value-checker.js';

export function parameterisationChecks(_services: CactalServices): ValidationChecks<CactalAstType> {
    return {
        ParameterSetting: checkSettingValue,
        ModuleInstance: checkSettingsUnique,
        Parameterize: checkSettingsUnique
    };
}

function checkSettingValue(setting: ParameterSetting, accept: ValidationAcceptor): void {
    const parameter = setting.port?.ref;
    if (!parameter || !setting.value) return;
    const module = setting.$container?.module?.ref;
    checkValue(setting.value, typeOf(parameter.type), accept, {
        allowVariables: true,
        what: `parameter port :${parameter.index} '${parameter.name}'${module ? ` of ${module.name}` : ''}`
    });
}

function checkSettingsUnique(owner: ModuleInstance | Parameterize, accept: ValidationAcceptor): void {
    const seen = new Set<Parameter>();
    for (const setting of owner.parameters) {
        const parameter = setting.port?.ref;
        if (!parameter) continue;
        if (seen.has(parameter)) {
            report(accept, SchemaCodes['parameterisation-port-duplicate'],
                `Parameter port :${parameter.index} '${parameter.name}' of ${owner.module?.ref?.name ?? '?'} is already set in this parameterisation: set each port once.`,
                { node: setting, property: 'port' });
        }
        seen.add(parameter);
    }
}
