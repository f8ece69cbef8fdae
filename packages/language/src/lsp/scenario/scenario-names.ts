/**
 * What a scenario can name in a project (docs/simulation.md "Values and names"), for completion
 * and hover: supervisors, modules, schemas by name, and the string values the rules compare an
 * event port with (`MAA:2<connection_status == "disconnected">` -> "disconnected" for `MAA:2`).
 */
import { AstUtils } from 'langium';
import {
    isEqualityTest, isModule, isModuleEvent, isSchema, isStringLiteral, isSupervisor,
    type Model, type Module, type Schema, type Supervisor,
} from '../../generated/ast.js';

export interface ScenarioNames {
    supervisors: Map<string, Supervisor>;
    modules: Map<string, Module>;
    schemas: Map<string, Schema>;
    models: Model[];
}

export function scenarioNames(models: Model[]): ScenarioNames {
    const names: ScenarioNames = { supervisors: new Map(), modules: new Map(), schemas: new Map(), models };
    // files in URI order, so that completion lists do not depend on the order documents were loaded in
    const ordered = [...models].sort((a, b) => {
        const ua = a.$document?.uri.toString() ?? '', ub = b.$document?.uri.toString() ?? '';
        return ua < ub ? -1 : ua > ub ? 1 : 0;
    });
    for (const m of ordered) {
        for (const e of m.elements) {
            if (isSupervisor(e)) names.supervisors.set(e.name, e);
            else if (isModule(e)) names.modules.set(e.name, e);
            else if (isSchema(e)) names.schemas.set(e.name, e);
        }
    }
    return names;
}

/** At most this many values are offered for one port (a generated project could compare many). */
const MAX_VALUES = 50;

/**
 * The string literals the supervisors' rules compare the events of `source:port` with, in the
 * order they are written. Only `==`/`!=` tests of a precondition or postcondition on that port.
 */
export function stringValuesOf(names: ScenarioNames, source: string, port: number): string[] {
    const out = new Set<string>();
    for (const sup of names.supervisors.values()) {
        for (const event of AstUtils.streamAllContents(sup).filter(isModuleEvent)) {
            if (event.source?.$refText !== source || event.port?.$refText !== String(port)) continue;
            for (const clause of event.tests) {
                for (const test of clause.tests) {
                    if (!isEqualityTest(test)) continue;
                    for (const side of [test.left, test.right]) if (isStringLiteral(side) && out.size < MAX_VALUES) out.add(side.value);
                }
            }
        }
    }
    return [...out];
}
