/**
 * What the Monitor's supervisor list shows: every supervisor of the model (document symbols) and
 * of the trace, each function of either, and every rule of each function. Names come from the
 * model and from the logs (hostile): they key Maps only, so a function named `constructor` or a
 * rule `__proto__` is listed like any other.
 */
import type { MonitorState, SupervisorState } from './monitor-state.js';

/** Supervisor -> function -> its rule labels, from the model (document symbols). */
export type SupervisorCatalogue = Map<string, Map<string, string[]>>;

export interface SupervisorRow {
  name: string;
  state: SupervisorState | undefined;
  /** Function -> its rules, the model's order first, then those only the trace names. */
  functions: Map<string, string[]>;
}

export function supervisorRows(catalogue: SupervisorCatalogue, s: MonitorState): SupervisorRow[] {
  const names = [...new Set([...catalogue.keys(), ...s.supervisors.keys()])].sort();
  return names.map((name) => {
    const st = s.supervisors.get(name);
    const fns = new Map<string, string[]>();
    for (const [fn, rules] of catalogue.get(name) ?? []) fns.set(fn, [...rules]);
    for (const r of st?.rules.values() ?? []) {
      const rules = fns.get(r.function);
      if (!rules) fns.set(r.function, [r.rule]);
      else if (!rules.includes(r.rule)) rules.push(r.rule);
    }
    for (const fn of st?.functions.keys() ?? []) if (!fns.has(fn)) fns.set(fn, []);
    return { name, state: st, functions: fns };
  });
}
