/**
 * The supervisors of the workspace model, their functions and rules, with where each rule is
 * written: read from the language server's document symbols (packages/language document symbol
 * provider: a supervisor is a Class with detail `supervisor`, its functions Methods, their rules
 * Keys with detail `rule`). The monitor lists every rule (also those never active yet) and
 * opens a rule's definition from it.
 */
import type * as lsp from 'vscode-languageserver-protocol';
import type { SupervisorCatalogue } from './supervisor-rows.js';

const CLASS = 5;
const METHOD = 6;
const KEY = 20;
/** A module's detail (`synchronous module, C=2 ms`): what it is. */
const MODULE_DETAIL = /^([a-z]+ module)\b/;

export interface RuleLocation {
  uri: string;
  range: lsp.Range;
}

export interface SupervisorSymbols {
  catalogue: SupervisorCatalogue;
  /** Keyed `SUP.F.R` (and `SUP.F` for a function). */
  locations: Map<string, RuleLocation>;
  /** `SUP.F` -> its parameters as the outline shows them: `(TypeA consigne)` (the Simulate panel's hint). */
  signatures: Map<string, string>;
  /** The model's modules (a Class whose detail says `... module`) -> what each is (`synchronous module`): no supervisor. */
  modules: Map<string, string>;
}

export async function readSupervisorSymbols(uris: string[], symbols: (uri: string) => Promise<lsp.DocumentSymbol[] | null>): Promise<SupervisorSymbols> {
  const catalogue: SupervisorCatalogue = new Map();
  const locations = new Map<string, RuleLocation>();
  const signatures = new Map<string, string>();
  const modules = new Map<string, string>();
  for (const uri of uris) {
    const list = (await symbols(uri).catch(() => null)) ?? [];
    for (const sup of list) {
      const module = sup.kind === CLASS ? MODULE_DETAIL.exec(sup.detail ?? '') : null;
      if (module) modules.set(sup.name, module[1]!);
      if (sup.kind !== CLASS || sup.detail !== 'supervisor') continue;
      let fns = catalogue.get(sup.name);
      if (!fns) catalogue.set(sup.name, (fns = new Map()));
      for (const fn of sup.children ?? []) {
        if (fn.kind !== METHOD) continue;
        let rules = fns.get(fn.name);
        if (!rules) fns.set(fn.name, (rules = []));
        locations.set(`${sup.name}.${fn.name}`, { uri, range: fn.selectionRange });
        signatures.set(`${sup.name}.${fn.name}`, (fn.detail ?? '').slice(0, 500));
        for (const r of fn.children ?? []) {
          if (r.kind !== KEY || r.detail !== 'rule') continue;
          if (!rules.includes(r.name)) rules.push(r.name);
          locations.set(`${sup.name}.${fn.name}.${r.name}`, { uri, range: r.selectionRange });
        }
      }
    }
  }
  return { catalogue, locations, signatures, modules };
}
