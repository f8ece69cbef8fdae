/**
 * Which schemas are active in a monitor state. Periodic schemas are ORD's: its `activate` /
 * `deactivate` lines. Event schemas are run by the supervisor itself (docs/engines.md: an
 * `activate schema` of an event schema starts its modules and connects its event flows, each a
 * hold logged as `module_hold`): one is active while a supervisor holds every module of it.
 */
import type { MonitorState } from './monitor-state.js';

export interface SchemaInfo {
  name: string;
  kind: string;
  modules: string[];
}

export interface ActiveSchema {
  name: string;
  kind: string;
  /**
   * `SUP.F.R` that activated it, when the trace tells: a periodic schema's, the rule whose action
   * asked ORD for the activation ORD serves; an event schema's, the rule whose action activated it
   * (else, a log of an older version, a supervisor holding every module of it).
   */
  by?: string;
}

export function activeSchemas(s: MonitorState, catalogue: readonly SchemaInfo[]): ActiveSchema[] {
  const out: ActiveSchema[] = [];
  const known = new Set(catalogue.map((c) => c.name));
  const holder = (module: string): string | undefined => {
    for (const [name, sv] of s.supervisors) {
      const rule = sv.heldModules.get(module);
      if (rule !== undefined) return rule ? `${name}.${rule}` : name;
    }
    return undefined;
  };
  // the rule whose action activated event schema `schema` (`activate schema S() (event schema)`, not undone yet)
  const activator = (schema: string): string | undefined => {
    for (const [name, sv] of s.supervisors) {
      const rule = sv.eventSchemas?.get(schema);
      if (rule !== undefined) return rule ? `${name}.${rule}` : name;
    }
    return undefined;
  };
  // a log of an older version, without that line: a supervisor that holds every module of it
  // (another may hold one of them for a schema of its own, or have started it)
  const holderOfAll = (modules: readonly string[]): string | undefined => {
    for (const [name, sv] of s.supervisors) {
      if (!modules.every((m) => sv.heldModules.has(m))) continue;
      const rule = sv.heldModules.get(modules[0]!);
      return rule ? `${name}.${rule}` : name;
    }
    return undefined;
  };
  for (const c of catalogue) {
    if (c.kind === 'periodic') {
      const a = s.schemas.get(c.name);
      if (a?.active) out.push(a.by ? { name: c.name, kind: c.kind, by: a.by } : { name: c.name, kind: c.kind });
    } else if (c.modules.length && c.modules.every((m) => holder(m) !== undefined)) {
      const by = activator(c.name) ?? holderOfAll(c.modules) ?? holder(c.modules[0]!);
      out.push(by ? { name: c.name, kind: c.kind, by } : { name: c.name, kind: c.kind });
    }
  }
  // schemas ORD activated that the model does not list (a stale model): still shown
  for (const [name, a] of s.schemas) {
    if (!known.has(name) && a.active) out.push(a.by ? { name, kind: 'periodic', by: a.by } : { name, kind: 'periodic' });
  }
  return out;
}

/**
 * Of the active schemas, the one that became active last (the Monitor's diagram shows it,
 * docs/watching-a-run.md): a periodic schema's activation by ORD, an event schema's by the rule
 * that holds its modules (when it became active); the later in the list between equal times.
 * Undefined when none is active.
 */
export function lastActivated(s: MonitorState, active: readonly ActiveSchema[]): string | undefined {
  let last: { name: string; t: number } | undefined;
  for (const a of active) {
    const t = activatedAt(s, a);
    if (!last || t >= last.t) last = { name: a.name, t };
  }
  return last?.name;
}

function activatedAt(s: MonitorState, a: ActiveSchema): number {
  const periodic = s.schemas.get(a.name);
  if (periodic?.active) return periodic.since;
  // an event schema: `by` is `SUP.F.R` (the rule holding its modules) or `SUP`
  const dot = a.by?.indexOf('.') ?? -1;
  const rule = dot > 0 ? s.supervisors.get(a.by!.slice(0, dot))?.rules.get(a.by!.slice(dot + 1)) : undefined;
  return rule?.active ? rule.since : -Infinity;
}
