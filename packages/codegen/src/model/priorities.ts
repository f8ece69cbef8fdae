import type { Architecture } from './architecture.js';

/**
 * Fixed priorities (1..99, higher = more urgent), docs/codegen.md "Priorities" / report §2:
 *   supervisors          99 - depth in the `activate supervisor` hierarchy (top = 99), never below 91
 *   ORD                  90
 *   critical async       85   (a module some supervisor activates with `activate critical module`)
 *   synchronous          84 down to 41, rate-monotonic: rank of the shortest PERIOD among the
 *                        periodic schemas using the module (shortest period = 84); 40 if unused
 *   interaction async    30   (asynchronous modules of event schemas, and the default for async)
 *   resttime async       10   (a module only ever activated with `activate resttime module`)
 */
export const PRIORITY = {
    supervisorTop: 99,
    supervisorFloor: 91,
    ord: 90,
    critical: 85,
    synchronousTop: 84,
    synchronousFloor: 41,
    synchronousUnused: 40,
    interaction: 30,
    resttime: 10,
} as const;

export interface Priorities {
    ord: number;
    /** module or supervisor name -> priority */
    of: Map<string, number>;
}

/** Depth of each supervisor in the activation DAG (longest path from a top supervisor). */
function supervisorDepths(arch: Architecture): Map<string, number> {
    const callees = new Map<string, Set<string>>();
    for (const s of arch.supervisors) {
        const set = new Set<string>();
        for (const f of s.functions) for (const r of f.rules) for (const a of r.actions) if (a.kind === 'supervisor' && a.supervisor !== s.name) set.add(a.supervisor);
        callees.set(s.name, set);
    }
    const depth = new Map<string, number>();
    for (const s of arch.supervisors) depth.set(s.name, 0);
    // relax along edges; the hierarchy is acyclic (validated), the bound guards against bad input
    for (let round = 0; round < arch.supervisors.length; round++) {
        let changed = false;
        for (const [caller, set] of callees) {
            for (const callee of set) {
                const d = (depth.get(caller) ?? 0) + 1;
                if (depth.has(callee) && d > depth.get(callee)! && d <= arch.supervisors.length) {
                    depth.set(callee, d);
                    changed = true;
                }
            }
        }
        if (!changed) break;
    }
    return depth;
}

export function computePriorities(arch: Architecture): Priorities {
    const of = new Map<string, number>();
    for (const [name, d] of supervisorDepths(arch)) of.set(name, Math.max(PRIORITY.supervisorFloor, PRIORITY.supervisorTop - d));

    const shortestPeriod = new Map<string, number>();
    for (const s of arch.schemas) {
        if (s.kind !== 'periodic' || s.periodNs === undefined) continue;
        for (const m of s.modules) {
            const p = shortestPeriod.get(m.module);
            if (p === undefined || s.periodNs < p) shortestPeriod.set(m.module, s.periodNs);
        }
    }
    const periods = [...new Set(shortestPeriod.values())].sort((a, b) => a - b);

    const critical = new Set<string>();
    const resttime = new Set<string>();
    for (const s of arch.supervisors) for (const f of s.functions) for (const r of f.rules) for (const a of r.actions) {
        if (a.kind === 'critical') critical.add(a.module);
        if (a.kind === 'resttime') resttime.add(a.module);
    }
    const inEventSchema = new Set(arch.schemas.filter((s) => s.kind === 'event').flatMap((s) => s.modules.map((m) => m.module)));

    for (const m of arch.modules) {
        if (m.kind === 'synchronous') {
            const p = shortestPeriod.get(m.name);
            of.set(m.name, p === undefined ? PRIORITY.synchronousUnused : Math.max(PRIORITY.synchronousFloor, PRIORITY.synchronousTop - periods.indexOf(p)));
        } else if (critical.has(m.name)) {
            of.set(m.name, PRIORITY.critical);
        } else if (resttime.has(m.name) && !inEventSchema.has(m.name)) {
            of.set(m.name, PRIORITY.resttime);
        } else {
            of.set(m.name, PRIORITY.interaction);
        }
    }
    return { ord: PRIORITY.ord, of };
}
