/**
 * The simulator's steps (docs/simulation.md §4) as the trace records the Monitor folds
 * (docs/runtime-api.md "Trace records"), so that one view shows a live run, a replayed run and a
 * simulation: rule changes become `sup_rule` records (same cause text, parsed by the trace
 * reader's parseCause), the active schemas' changes `scheduler` activate/deactivate records,
 * `start`/`stop` steps `supervisor` function_started/stopped records. mono_ns is the virtual time.
 */
import { parseCause, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import type { SimulateStep } from '../../server/api-types.js';

function base(timeNs: number, module: string, detail: string) {
  return { monoNs: String(Math.max(0, Math.floor(timeNs))), wallTime: '', module, peer: '', port: null, size: 0, detail };
}

function known(timeNs: number, module: string, kind: string, detail: string, fields: Record<string, string | number>): KnownRecord {
  return { ...base(timeNs, module, detail), kind, fields };
}

export function stepsToTrace(steps: SimulateStep[]): TraceRecord[] {
  // the first record is time 0 of the Monitor's cursor: the simulation's start
  const out: TraceRecord[] = [known(0, 'SIM', 'sim_start', 'simulation start', {})];
  let schemas = new Set<string>();
  for (const s of steps) {
    for (const r of s.rules) {
      const rec: RuleRecord = {
        ...base(r.timeNs, r.supervisor, `${r.function}.${r.rule} ${r.active ? 'active' : 'inactive'} cause=${r.cause}`),
        kind: 'sup_rule', function: r.function, rule: r.rule, active: r.active, cause: r.cause, causeEvent: parseCause(r.cause),
      };
      out.push(rec);
    }
    const m = /^(start|stop)\s+([A-Za-z_]\w*)\.([A-Za-z_]\w*)/.exec(s.source);
    if (m && s.ok) {
      const what = m[1] === 'start' ? 'function_started' : 'function_stopped';
      out.push(known(s.timeNs, m[2]!, 'supervisor', `${what} function=${m[3]}`, { what, function: m[3]! }));
    }
    const now = new Set(s.schemas);
    for (const sc of now) if (!schemas.has(sc)) out.push(known(s.timeNs, 'ORD', 'scheduler', `activate schema=${sc}`, { what: 'activate', schema: sc }));
    for (const sc of schemas) if (!now.has(sc)) out.push(known(s.timeNs, 'ORD', 'scheduler', `deactivate schema=${sc}`, { what: 'deactivate', schema: sc }));
    schemas = now;
  }
  // records in time order, as a run's trace (a step's record holds what happened up to it)
  return out.map((r, i) => ({ r, i })).sort((a, b) => Number((a.r as KnownRecord).monoNs) - Number((b.r as KnownRecord).monoNs) || a.i - b.i).map((x) => x.r);
}
