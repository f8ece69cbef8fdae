/**
 * Timing figures of a periodic schema, shown on hover: utilisation (sum of the modules' C over the
 * PERIOD) and the critical path (the longest chain of summed C through the precedence graph).
 * Pure functions of the AST; browser-safe.
 */
import type { Module, Schema } from '../generated/ast.js';
import { computeTimeNs, moduleInstancesOf, periodNs, precedencesOf } from '../model/blocks.js';

export interface SchemaTiming {
    /** Sum of the C of the schema's modules (ns); modules without a valid C count 0 and are listed. */
    totalComputeNs: number;
    periodNs?: number;
    /** totalComputeNs / periodNs, when the period is known and positive. */
    utilisation?: number;
    /** Longest path of summed C through the precedence graph (ns); undefined when the graph has a cycle. */
    criticalPathNs?: number;
    /** Module names along that path, in order. */
    criticalPath: string[];
    /** Modules of the schema without a valid `C`. */
    missingC: string[];
}

/** Computes the timing figures of a schema from its modules, precedences and realtime block. */
export function schemaTiming(schema: Schema): SchemaTiming {
    const modules: Module[] = [];
    for (const instance of moduleInstancesOf(schema)) {
        const module = instance.module?.ref;
        if (module && !modules.includes(module)) modules.push(module);
    }
    const cost = new Map<Module, number>();
    const missingC: string[] = [];
    for (const module of modules) {
        const c = computeTimeNs(module);
        if (c === undefined) missingC.push(module.name);
        cost.set(module, c ?? 0);
    }
    const totalComputeNs = [...cost.values()].reduce((a, b) => a + b, 0);
    const period = periodNs(schema);
    const utilisation = period !== undefined && period > 0 ? totalComputeNs / period : undefined;

    const successors = new Map<Module, Module[]>(modules.map((m) => [m, []]));
    for (const edge of precedencesOf(schema)) {
        const from = edge.from?.ref;
        const to = edge.to?.ref;
        if (from && to && successors.has(from) && successors.has(to)) successors.get(from)!.push(to);
    }
    const path = longestPath(modules, successors, cost);
    return {
        totalComputeNs,
        periodNs: period,
        utilisation,
        criticalPathNs: path?.length,
        criticalPath: path?.nodes.map((m) => m.name) ?? [],
        missingC
    };
}

/** Longest node-weighted path in a DAG (memoised DFS); undefined when a cycle is found. */
export function longestPath<N>(nodes: N[], successors: Map<N, N[]>, weight: Map<N, number>): { length: number; nodes: N[] } | undefined {
    const best = new Map<N, { length: number; next?: N }>();
    const onStack = new Set<N>();
    let cyclic = false;
    const visit = (node: N): number => {
        const known = best.get(node);
        if (known) return known.length;
        if (onStack.has(node)) { cyclic = true; return 0; }
        onStack.add(node);
        let tail = 0;
        let next: N | undefined;
        for (const succ of successors.get(node) ?? []) {
            const length = visit(succ);
            if (length > tail || next === undefined) { tail = length; next = succ; }
        }
        onStack.delete(node);
        const entry = { length: (weight.get(node) ?? 0) + tail, next };
        best.set(node, entry);
        return entry.length;
    };
    let start: N | undefined;
    let length = 0;
    for (const node of nodes) {
        const l = visit(node);
        if (start === undefined || l > length) { start = node; length = l; }
    }
    if (cyclic) return undefined;
    const path: N[] = [];
    for (let n = start; n !== undefined; n = best.get(n)?.next) path.push(n);
    return { length, nodes: path };
}
