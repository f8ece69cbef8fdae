/**
 * Parses the runtime's per-module CSV logs (docs/runtime-api.md: columns
 * `mono_ns,wall_time,module,event,peer,port,size,detail`) into activations: each `run_started`
 * paired with the module's next `run_finished`, and each event an asynchronous module handles
 * outside a run (its `event_received` to its `event_handled`) (fields split by the trace reader's
 * splitCsvLine). Pure: used by the timeline view and tests.
 */
import { LogClocks, parseRecordLine, splitCsvLine, type KnownRecord } from '@contract-studio/build-service/trace';

export interface Activation {
  module: string;
  /** Monotonic start/end in ns; end undefined if the log stops while running. */
  start: number;
  end?: number;
  detail: string;
  /**
   * Set when this is an event an asynchronous module handled while no run of it was going on (its
   * handler, `_react_to_event`, called from its request loop): `start` is its `event_received`
   * (GetEventId), `end` its `event_handled` (written when the module reads its mailbox again:
   * `ended`), or, in logs of runtimes that wrote none, the last record the handler wrote (its
   * posts, its own lines) before the module's next request, the reception when it wrote none.
   * `records`: how many the handler wrote; `last`: the kind of the last.
   */
  event?: { from: string; records: number; last?: string; ended: boolean };
  /**
   * Set when the module's log has no end of this bar and the launcher's own line says the module
   * ended then (gone-activations.ts): `end` is that line's time, this its words
   * (`contract-launch: module SRT (pid 41) died by signal 9 (Killed)`).
   */
  gone?: string;
}

/**
 * Records a module's handler writes while it handles an event (in a log with no `event_handled`,
 * an older runtime's, they stretch its bar): its posts, what it reads, its own lines. Any other
 * record of the module (the next request read, a priority changed by a request, a run, its exit)
 * is written once it reads requests again: it ends the bar.
 */
const HANDLER_RECORDS = new Set(['event_posted', 'event_waited', 'data_posted', 'data_dropped', 'data_received', 'setparam_sent', 'user', 'error']);

/** ORD's readable line of a schema activated or deactivated (`activate S (activation #N from SUP)`). */
const ENGINE_SCHEMA = /^(activate|deactivate) [A-Za-z_]\w*(?: \(|$)/;
/** A supervisor's readable line of a function started or stopped (`function F(p = v) started`, `function F stopped`). */
const ENGINE_FUNCTION = /^function [A-Za-z_]\w*(?:\(.*\))? (started|stopped)$/s;

/**
 * What the project's model says of the run's modules, when the IDE has it: its supervisors' and its
 * other modules' names. A module it names among its modules is no supervisor, whatever its log holds;
 * one it does not name at all (another project's run, a module renamed since) is judged by its log.
 */
export interface ModelModules {
  supervisors: ReadonlySet<string>;
  /** Its modules that are no supervisor (synchronous, asynchronous). */
  modules: ReadonlySet<string>;
}

/**
 * The modules of a log whose runs ORD started (a `run_started` record whose peer is ORD: a
 * release of a periodic schema): modules of schemas, never a supervisor (the engine starts none).
 */
function releasedModules(lines: readonly string[], file: string): Set<string> {
  const out = new Set<string>();
  for (let n = 1; n < lines.length; n++) {
    const l = lines[n]!;
    if (!l.includes(',run_started,ORD,')) continue;
    const r = parseRecordLine(file, n + 1, l);
    if (r.kind === 'run_started' && (r as KnownRecord).peer === 'ORD') out.add((r as KnownRecord).module);
  }
  return out;
}

/**
 * `file`: the log's name (a line of another module than the one it names is no record of that
 * module's). Each line the bars use is read by the trace reader (parseRecordLine, with each
 * module's time check, log-clock.ts): a line it does not read as a record, or whose time it does
 * not believe, makes no bar; `unreadable` (when given) counts them.
 * A `supervisor` record makes its module an engine (its bars are the functions it runs, not its
 * runs) only when it may be a supervisor: the model (`model`, when the IDE has it) names it among
 * its supervisors, not among its other modules, or, when the model does not name it, ORD never
 * started a run of it (a module's code may write
 * such a line into its own log: its lane must not vanish; docs/runtime-api.md "Whose records, and
 * their times").
 */
export function activationsFromCsv(text: string, file = '', unreadable?: { n: number }, model?: ModelModules): Activation[] {
  const lines = text.split(/\r?\n/).filter((l) => l.length > 0);
  if (!lines.length) return [];
  const header = splitCsvLine(lines[0]!);
  const col = (name: string) => header.indexOf(name);
  const [iMono, iModule, iEvent] = [col('mono_ns'), col('module'), col('event')];
  if (iMono < 0 || iModule < 0 || iEvent < 0) throw new Error('not a ContrACT CSV log (missing mono_ns/module/event columns)');
  const open = new Map<string, Activation>();
  const out: Activation[] = [];
  // the event each module is handling now (its bar grows with the handler's records)
  const handling = new Map<string, Activation>();
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
  // only run_started / run_finished / event_received lines, the engines' activate/deactivate and
  // function lines, and the lines after an event_received until the handler's end matter (a 1 kHz
  // run's logs are most of a million lines): with the event column between two others, such a line
  // holds `,run_started,`, `,run_finished,`, `,event_received,`, `,scheduler,` or `,supervisor,`
  const inside = iEvent > 0 && iEvent < header.length - 1;
  const clocks = new LogClocks();
  // read only when a supervisor record's module is one the model does not name (a log of a plain
  // module holds no supervisor record, a supervisor's no release: most logs never read it)
  let released: Set<string> | undefined;
  const mayBeSupervisor = (module: string): boolean =>
    model?.supervisors.has(module) ? true : model?.modules.has(module) ? false : !(released ??= releasedModules(lines, file)).has(module);
  for (let n = 1; n < lines.length; n++) {
    const l = lines[n]!;
    if (inside && !handling.size && !l.includes(',run_started,') && !l.includes(',run_finished,') && !l.includes(',event_received,') && !l.includes(',scheduler,') && !l.includes(',supervisor,')) continue;
    const r = parseRecordLine(file, n + 1, l, clocks.of(recordModule(l)));
    if (r.kind === 'unknown') {
      if (unreadable) unreadable.n++;
      continue;
    }
    const k = r as KnownRecord;
    const t = Number(k.monoNs);
    const module = k.module;
    const event = k.kind;
    const handled = handling.get(module);
    if (handled) {
      if (event === 'event_handled') {
        handled.end = Math.max(handled.end!, t);
        handled.event!.ended = true;
        handling.delete(module);
        continue;
      }
      if (HANDLER_RECORDS.has(event)) {
        handled.end = Math.max(handled.end!, t);
        handled.event!.records++;
        handled.event!.last = event;
        continue;
      }
      handling.delete(module); // it reads requests again (an older runtime's log): the handler had ended
    }
    if (event === 'scheduler' || (event === 'supervisor' && mayBeSupervisor(module))) {
      const detail = k.detail;
      if (!engines.has(module)) {
        engines.set(module, 0);
        // its run records so far were no bars of its own
        open.delete(module);
        handling.delete(module);
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
    } else if (event === 'event_received' && !running(open.get(module))) {
      // an event handled outside a run (one taken during a run is inside that run's bar)
      const a: Activation = { module, start: t, end: t, detail: `event from ${k.peer}:${k.port}`, event: { from: `${k.peer}:${k.port}`, records: 0, ended: false } };
      handling.set(module, a);
      out.push(a);
    }
  }
  return out.sort((a, b) => a.start - b.start);
}

/**
 * The period guess: the median gap between consecutive activations (runs, not events handled) of
 * the most active module (ns), and that module (a run with loops of several periods has its grid drawn at its period).
 */
export function inferPeriodOf(acts: Activation[]): { ns: number; module: string } | undefined {
  const byModule = new Map<string, number[]>();
  for (const a of acts) if (!a.event) (byModule.get(a.module) ?? byModule.set(a.module, []).get(a.module)!).push(a.start);
  let best: number[] = [];
  let module = '';
  for (const [m, starts] of byModule) if (starts.length > best.length) [best, module] = [starts, m];
  if (best.length < 3) return undefined;
  const gaps = best.slice(1).map((s, i) => s - best[i]!).sort((a, b) => a - b);
  return { ns: gaps[Math.floor(gaps.length / 2)]!, module };
}

/** A run of the module still going on (started, not finished). */
function running(a: Activation | undefined): boolean {
  return a !== undefined && !a.event && a.end === undefined;
}

/** The module field of a record line (the third), to key its time check; '' when none. */
function recordModule(line: string): string {
  const a = line.indexOf(',');
  const b = a < 0 ? -1 : line.indexOf(',', a + 1);
  const c = b < 0 ? -1 : line.indexOf(',', b + 1);
  return c < 0 ? '' : line.slice(b + 1, c);
}
