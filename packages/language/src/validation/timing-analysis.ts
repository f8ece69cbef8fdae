/**
 * Timing analysis of periodic schemas (docs/language-reference.md §4, beyond the report): utilisation (sum of C /
 * PERIOD), the critical path (longest path of summed C through the precedence graph) and
 * precedence cycles. Pure functions over the AST, shared by validation and hover.
 */
import type { Module, Schema } from '../generated/ast.js';
import { computeTimeNs, criticalDelayNs, moduleInstancesOf, periodNs, precedencesOf } from '../model/blocks.js';

/** The resolved modules of a schema's `modules` block, each once, in written order. */
export function schemaModules(schema: Schema): Module[] {
    const modules: Module[] = [];
    for (const instance of moduleInstancesOf(schema)) {
        const m = instance.module?.ref;
        if (m && !modules.includes(m)) modules.push(m);
    }
    return modules;
}

/** Precedence edges between modules of the schema (edges naming other modules are ignored). */
function edgesOf(schema: Schema, modules: Module[]): Map<Module, Module[]> {
    const edges = new Map<Module, Module[]>(modules.map((m) => [m, []]));
    for (const p of precedencesOf(schema)) {
        const from = p.from?.ref;
        const to = p.to?.ref;
        if (!from || !to || !edges.has(from) || !edges.has(to)) continue;
        const next = edges.get(from)!;
        if (!next.includes(to)) next.push(to);
    }
    return edges;
}

/**
 * A cycle of the scheduling graph as the list of its modules, first repeated at the end
 * (`[MSA, MSB, MSA]`), or undefined when the graph is acyclic. Edges to modules that are not in
 * the schema are ignored (they are reported separately).
 */
export function precedenceCycle(schema: Schema): Module[] | undefined {
    const modules = schemaModules(schema);
    const edges = edgesOf(schema, modules);
    const state = new Map<Module, 'visiting' | 'done'>();
    const stack: Module[] = [];
    const visit = (m: Module): Module[] | undefined => {
        state.set(m, 'visiting');
        stack.push(m);
        for (const next of edges.get(m) ?? []) {
            if (state.get(next) === 'visiting') return [...stack.slice(stack.indexOf(next)), next];
            if (!state.has(next)) {
                const found = visit(next);
                if (found) return found;
            }
        }
        stack.pop();
        state.set(m, 'done');
        return undefined;
    };
    for (const m of modules) {
        if (!state.has(m)) {
            const found = visit(m);
            if (found) return found;
        }
    }
    return undefined;
}

export interface CriticalPath {
    /** Modules along the path, in execution order. */
    modules: Module[];
    /** Sum of their C, in nanoseconds. */
    ns: number;
}

/**
 * The longest path of summed C through the precedence graph (a module without precedences is a
 * path of its own; a module without a valid C counts 0). Undefined for an empty schema or a
 * cyclic graph.
 */
export function criticalPath(schema: Schema): CriticalPath | undefined {
    const modules = schemaModules(schema);
    if (modules.length === 0 || precedenceCycle(schema)) return undefined;
    const edges = edgesOf(schema, modules);
    const cost = (m: Module) => computeTimeNs(m) ?? 0;
    // longest path starting at each module (memoised DFS: the graph is acyclic)
    const best = new Map<Module, CriticalPath>();
    const longestFrom = (m: Module): CriticalPath => {
        const known = best.get(m);
        if (known) return known;
        let tail: CriticalPath = { modules: [], ns: 0 };
        for (const next of edges.get(m) ?? []) {
            const candidate = longestFrom(next);
            if (candidate.ns > tail.ns || tail.modules.length === 0) tail = candidate;
        }
        const path = { modules: [m, ...tail.modules], ns: cost(m) + tail.ns };
        best.set(m, path);
        return path;
    };
    let result: CriticalPath | undefined;
    for (const m of modules) {
        const p = longestFrom(m);
        if (!result || p.ns > result.ns) result = p;
    }
    return result;
}

/** Sum of the C of the schema's modules, in nanoseconds. */
export function totalComputeNs(schema: Schema): number {
    return schemaModules(schema).reduce((sum, m) => sum + (computeTimeNs(m) ?? 0), 0);
}

/** Utilisation of a periodic schema: sum of C / PERIOD (undefined without a valid PERIOD). */
export function schemaUtilisation(schema: Schema): number | undefined {
    const period = periodNs(schema);
    if (period === undefined || period <= 0) return undefined;
    return totalComputeNs(schema) / period;
}

/** Utilisation of schemas running together: the sum of their utilisations (schemas without PERIOD count 0). */
export function combinedUtilisation(schemas: Schema[]): number {
    return schemas.reduce((sum, s) => sum + (schemaUtilisation(s) ?? 0), 0);
}

/** Every timing figure of a schema, for hover and reports. */
export interface SchemaTiming {
    periodNs?: number;
    criticalDelayNs?: number;
    totalComputeNs: number;
    utilisation?: number;
    criticalPath?: CriticalPath;
}

export function schemaTiming(schema: Schema): SchemaTiming {
    return {
        periodNs: periodNs(schema),
        criticalDelayNs: criticalDelayNs(schema),
        totalComputeNs: totalComputeNs(schema),
        utilisation: schemaUtilisation(schema),
        criticalPath: criticalPath(schema)
    };
}
