/**
 * Parses the runtime's per-module CSV logs (docs/runtime-api.md: columns
 * `mono_ns,wall_time,module,event,peer,port,size,detail`) into activations: each `run_started`
 * paired with the module's next `run_finished` (fields split by the trace reader's splitCsvLine). Pure: used by
 * the timeline view and tests.
 */
import { LogClocks, parseRecordLine, splitCsvLine, type KnownRecord } from '@contract-studio/build-service/trace';

export interface Activation {
  module: string;
  /** Monotonic start/end in ns; end undefined if the log stops while running. */
  start: number;
  end?: number;
  detail: string;
}

/** ORD's readable line of a schema activated or deactivated (`activate S (activation #N from SUP)`). */
const ENGINE_SCHEMA = /^(activate|deactivate) [A-Za-z_]\w*(?: \(|$)/;
/** A supervisor's readable line of a function started or stopped (`function F(p = v) started`, `function F stopped`). */
const ENGINE_FUNCTION = /^function [A-Za-z_]\w*(?:\(.*\))? (started|stopped)$/s;

/**
 * `file`: the log's name (a line of another module than the one it names is no record of that
 * module's). Each line the bars use is read by the trace reader (parseRecordLine, with each
 * module's time check, log-clock.ts): a line it does not read as a record, or whose time it does
 * not believe, makes no bar; `unreadable` (when given) counts them.
 */
export function activationsFromCsv(text: string, file = '', unreadable?: { n: number }): Activation[] {
  const lines = text.split(/\r?\n/).filter((l) => l.length > 0);
  if (!lines.length) return [];
  const header = splitCsvLine(lines[0]!);
  const col = (name: string) => header.indexOf(name);
  const [iMono, iModule, iEvent] = [col('mono_ns'), col('module'), col('event')];
  if (iMono < 0 || iModule < 0 || iEvent < 0) throw new Error('not a ContrACT CSV log (missing mono_ns/module/event columns)');
  const open = new Map<string, Activation>();
  const out: Activation[] = [];
  // ORD and the supervisors serve several activations at once (every schema, every function): one
  // STOP ends one of them, not the module's activity, so their run records are not their bars; a
  // bar of theirs lasts while at least one schema is active (ORD's `scheduler` activate/deactivate
  // lines) or one function runs (a supervisor's `function F() started` / `stopped`)
  const engines = new Map<string, number>(); // engine module -> what it serves now
  const engineLine = (module: string, t: number, up: boolean, detail: string) => {
    const n = engines.get(module) ?? 0;
    const next = Math.max(0, n + (up ? 1 : -1));
    engines.set(module, next);
    if (n === 0 && next === 1) {
      const a: Activation = { module, start: t, detail };
      open.set(module, a);
      out.push(a);
    } else if (n > 0 && next === 0) {
      const a = open.get(module);
      if (a && a.end === undefined) a.end = t;
    }
  };
  // only run_started / run_finished lines, and the engines' activate/deactivate and function lines,
  // matter (a 1 kHz run's logs are most of a million lines): with the event column between two
  // others, such a line holds `,run_started,`, `,run_finished,`, `,scheduler,` or `,supervisor,`
  const inside = iEvent > 0 && iEvent < header.length - 1;
  const clocks = new LogClocks();
  for (let n = 1; n < lines.length; n++) {
    const l = lines[n]!;
    if (inside && !l.includes(',run_started,') && !l.includes(',run_finished,') && !l.includes(',scheduler,') && !l.includes(',supervisor,')) continue;
    const r = parseRecordLine(file, n + 1, l, clocks.of(recordModule(l)));
    if (r.kind === 'unknown') {
      if (unreadable) unreadable.n++;
      continue;
    }
    const k = r as KnownRecord;
    const t = Number(k.monoNs);
    const module = k.module;
    const event = k.kind;
    if (event === 'scheduler' || event === 'supervisor') {
      const detail = k.detail;
      if (!engines.has(module)) {
        engines.set(module, 0);
        // its run records so far were no bars of its own
        open.delete(module);
        for (let i = out.length - 1; i >= 0; i--) if (out[i]!.module === module) out.splice(i, 1);
      }
      const m = event === 'scheduler' ? ENGINE_SCHEMA.exec(detail) : ENGINE_FUNCTION.exec(detail);
      if (m) engineLine(module, t, m[1] === 'activate' || m[1] === 'started', detail);
      continue;
    }
    if (engines.has(module)) continue;
    if (event === 'run_started') {
      const a: Activation = { module, start: t, detail: k.detail };
      const prev = open.get(module);
      if (prev && prev.end === undefined) prev.end = t;
      open.set(module, a);
      out.push(a);
    } else if (event === 'run_finished') {
      const a = open.get(module);
      if (a && a.end === undefined) a.end = t;
    }
  }
  return out.sort((a, b) => a.start - b.start);
}

/**
 * The period guess: the median gap between consecutive activations of the most active module
 * (ns), and that module (a run with loops of several periods has its grid drawn at its period).
 */
export function inferPeriodOf(acts: Activation[]): { ns: number; module: string } | undefined {
  const byModule = new Map<string, number[]>();
  for (const a of acts) (byModule.get(a.module) ?? byModule.set(a.module, []).get(a.module)!).push(a.start);
  let best: number[] = [];
  let module = '';
  for (const [m, starts] of byModule) if (starts.length > best.length) [best, module] = [starts, m];
  if (best.length < 3) return undefined;
  const gaps = best.slice(1).map((s, i) => s - best[i]!).sort((a, b) => a - b);
  return { ns: gaps[Math.floor(gaps.length / 2)]!, module };
}

/** The module field of a record line (the third), to key its time check; '' when none. */
function recordModule(line: string): string {
  const a = line.indexOf(',');
  const b = a < 0 ? -1 : line.indexOf(',', a + 1);
  const c = b < 0 ? -1 : line.indexOf(',', b + 1);
  return c < 0 ? '' : line.slice(b + 1, c);
}
