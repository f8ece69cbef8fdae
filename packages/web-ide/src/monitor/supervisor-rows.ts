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
  /**
   * Whether the model has this supervisor: false for one only the trace names (the model has
   * others), undefined when the model names no supervisor (not read yet, or another project's logs).
   */
  inModel: boolean | undefined;
  /**
   * `function.rule` of the rules and `function` of the functions the trace names and the model
   * does not (renamed or removed since the run was recorded): all of them when the model names
   * supervisors but not this one; none when it names no supervisor (inModel undefined).
   */
  notInModel: Set<string>;
}

/**
 * `modules`: the model's modules that are no supervisor (name -> what it is: `synchronous module`):
 * a module's code may write supervisor records into its own log (docs/runtime-api.md "Whose
 * records, and their times"), so the trace's supervisors the model says are such a module are not
 * listed (notSupervisors says them once).
 */
export function supervisorRows(catalogue: SupervisorCatalogue, s: MonitorState, modules: ReadonlyMap<string, string> = new Map()): SupervisorRow[] {
  const names = [...new Set([...catalogue.keys(), ...s.supervisors.keys()])].filter((n) => catalogue.has(n) || !modules.has(n)).sort();
  return names.map((name) => {
    const st = s.supervisors.get(name);
    const model = catalogue.get(name);
    const fns = new Map<string, string[]>();
    for (const [fn, rules] of model ?? []) fns.set(fn, [...rules]);
    const notInModel = new Set<string>();
    // a supervisor the model does not have (renamed or removed since the run): all of it; a model
    // that names no supervisor (not read yet, another project's logs): nothing to compare with
    const traceOnly = (key: string): void => {
      if (catalogue.size) notInModel.add(key);
    };
    for (const r of st?.rules.values() ?? []) {
      const rules = fns.get(r.function);
      if (!rules) {
        fns.set(r.function, [r.rule]);
        traceOnly(r.function);
      } else if (rules.includes(r.rule)) continue;
      else rules.push(r.rule);
      traceOnly(`${r.function}.${r.rule}`);
    }
    for (const fn of st?.functions.keys() ?? []) {
      if (fns.has(fn)) continue;
      fns.set(fn, []);
      traceOnly(fn);
    }
    return { name, state: st, functions: fns, inModel: catalogue.size ? !!model : undefined, notInModel };
  });
}

/** The modules of the trace's supervisor records that the model says are no supervisor, each with what the model says it is. */
export function notSupervisors(catalogue: SupervisorCatalogue, s: MonitorState, modules: ReadonlyMap<string, string>): Array<{ name: string; is: string }> {
  return [...s.supervisors.keys()].filter((n) => !catalogue.has(n) && modules.has(n)).sort().map((name) => ({ name, is: modules.get(name)! }));
}

/** What the Monitor says once of a module the model says is no supervisor but whose log holds supervisor records. */
export function notSupervisorText(name: string, is: string): string {
  return `${name}: supervisor records in its log, not taken for a supervisor's: the model says ${name} is a ${is} (its code wrote them into its log?)`;
}
