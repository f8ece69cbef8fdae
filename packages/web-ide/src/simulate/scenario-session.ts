/**
 * A simulation session of the Simulate panel (docs/simulation.md "In the IDE"): a scenario text
 * grown step by step. The session is the `start` line, the lines injected at the current virtual
 * time and that time (the scenario's `until`); each change is simulated by running the whole text
 * again in virtual time (POST /api/simulate), so what the panel shows is exactly what
 * `contract simulate` of the saved file computes. Pure: no DOM, no network.
 */
import { formatTime, parseTimeLiteral, MAX_TIME_NS, STEP_DIRECTIVES } from '@contract-studio/language/scenario';
import type { SimulateStep } from '../../server/api-types.js';
import type { MonitorState } from '../monitor/monitor-state.js';

/** A session as the browser keeps it across a reload. */
export interface SessionSnapshot {
  start: SessionStart;
  nowNs: number;
  lines: Array<{ atNs: number; text: string }>;
}

export interface SessionStart {
  supervisor: string;
  fn: string;
  /** What goes between the parentheses: `consigne = {1.0, 2.0, 3.0}`, or '' for the defaults. */
  params: string;
}

const MAX_LINES = 2_000;
const MAX_LINE = 2_000;
const NAME = /^[A-Za-z_]\w*$/;
/** Directives a user may inject (docs/simulation.md §1 "Steps"): the scenario parser's steps but `start`; `start` and times are the session's. */
const INJECTED = STEP_DIRECTIVES.filter((d) => d !== 'start');
const STEP = new RegExp(`^(?:[A-Za-z_]\\w*:\\w+\\b|(?:${INJECTED.join('|')})\\s)`);

export class ScenarioSession {
  start: SessionStart | undefined;
  nowNs = 0;
  readonly lines: Array<{ atNs: number; text: string }> = [];

  /** Starts a new session; an error message when the names cannot be a function. */
  begin(start: SessionStart): string | undefined {
    if (!NAME.test(start.supervisor) || !NAME.test(start.fn)) return 'pick a supervisor function';
    if (/[\n\r#]/.test(start.params) || start.params.length > MAX_LINE) return 'parameters: one line, `name = value, ...`';
    this.start = { ...start, params: start.params.trim() };
    this.nowNs = 0;
    this.lines.length = 0;
    return undefined;
  }

  /** Moves the virtual time to a literal (`1ms`) or by one (`+1ms`); an error message when it is not a later time. */
  advance(text: string): string | undefined {
    const t = text.trim();
    const rel = t.startsWith('+');
    const ns = parseTimeLiteral(rel ? t.slice(1).trim() : t);
    if (ns === undefined) return `'${t}' is not a time (0, 250us, 1ms, 1.5s)`;
    const to = rel ? this.nowNs + ns : ns;
    if (to < this.nowNs) return `times never go backwards: now ${formatTime(this.nowNs)}`;
    if (to > MAX_TIME_NS) return 'at most one day of virtual time';
    this.nowNs = to;
    return undefined;
  }

  /** Adds one step at the current time (`MAA:2 connection_status = "disconnected"`, `crash MSC`...). */
  inject(text: string): string | undefined {
    const t = text.trim();
    if (!this.start) return 'start a supervisor function first';
    if (!t || /[\n\r]/.test(t) || t.length > MAX_LINE) return 'one step on one line';
    if (!STEP.test(t)) return 'a step: `MODULE:PORT value`, `ORD:0 "schema"`, `crash M`, `finish M`, `exec M 2ms`, `stop SUP.fn` or `expect ...`';
    if (this.lines.length >= MAX_LINES) return `at most ${MAX_LINES} steps in a session`;
    this.lines.push({ atNs: this.nowNs, text: t });
    return undefined;
  }

  /**
   * The time of the first thing the engines did after now (a rule change, an action: a timer of
   * `elapsed`/`duration`, a release, a deadline), in a look-ahead run of the session; undefined when
   * nothing happens in it.
   */
  static nextChange(steps: SimulateStep[], afterNs: number): number | undefined {
    let next: number | undefined;
    const see = (timeNs: number): void => {
      if (timeNs > afterNs && (next === undefined || timeNs < next)) next = timeNs;
    };
    for (const st of steps) {
      for (const x of st.rules) see(x.timeNs);
      for (const x of st.actions) see(x.timeNs);
      // what the engines did by themselves, in their typed records: a release, a completion, a deadline miss
      for (const x of st.records ?? []) see(x.timeNs);
    }
    return next;
  }

  /** What a reload needs to grow the session again (SimulateController keeps it in the browser). */
  snapshot(): SessionSnapshot | undefined {
    return this.start ? { start: { ...this.start }, nowNs: this.nowNs, lines: this.lines.map((l) => ({ ...l })) } : undefined;
  }

  /**
   * Grows the session again from a snapshot, through the same checks as when it was grown (the
   * snapshot is read from the browser's storage: anything may be there). An error message, and
   * the session unchanged, when it is not one.
   */
  restore(data: unknown): string | undefined {
    const d = data as Partial<SessionSnapshot> | null;
    const s = d?.start;
    if (!d || typeof d !== 'object' || !s || typeof s.supervisor !== 'string' || typeof s.fn !== 'string' || typeof s.params !== 'string'
      || !Number.isSafeInteger(d.nowNs) || !Array.isArray(d.lines) || d.lines.length > MAX_LINES) return 'not a saved session';
    const copy = new ScenarioSession();
    const error = copy.begin(s);
    if (error) return error;
    for (const l of d.lines as unknown[]) {
      const line = l as { atNs?: unknown; text?: unknown };
      if (!Number.isSafeInteger(line?.atNs) || typeof line.text !== 'string') return 'not a saved session';
      const e = copy.advance(formatTime(line.atNs as number)) ?? copy.inject(line.text);
      if (e) return e;
    }
    const e = copy.advance(formatTime(d.nowNs as number));
    if (e) return e;
    this.start = copy.start;
    this.nowNs = copy.nowNs;
    this.lines.splice(0, this.lines.length, ...copy.lines);
    return undefined;
  }

  /** Drops the last injected step. */
  undo(): void {
    this.lines.pop();
  }

  /** Line of the scenario text where the first injected step is (1-based). */
  static readonly FIRST_STEP_LINE = 4;

  /** The scenario text of the session (also what "Save as scenario" writes, before the expectations). */
  text(title = 'simulation session', untilNs = this.nowNs): string {
    if (!this.start) return '';
    const s = this.start;
    const out = [`scenario ${title.replace(/[\n\r#]/g, ' ')}`, `until ${formatTime(Math.max(untilNs, this.nowNs))}`, `start ${s.supervisor}.${s.fn}(${s.params ?? ''})`];
    for (const l of this.lines) out.push(`t=${formatTime(l.atNs)} ${l.text}`);
    return `${out.join('\n')}\n`;
  }

  /**
   * The session as a regression test: its text plus, at the current time, the state the
   * simulator showed (every rule seen, active or inactive; the active schemas; the deadline misses
   * and overruns of the periodic schemas, from `shown`: the Monitor's state of the same steps).
   */
  withExpectations(steps: SimulateStep[], shown: SchedulerFigures, title?: string): string {
    const rules = ruleStates(steps);
    const at = formatTime(this.nowNs);
    const lines = [...rules].map(([name, r]) => `expect at ${at} rule ${name} ${r.active ? 'active' : 'inactive'}`);
    const last = steps.at(-1);
    for (const schema of last?.schemas ?? []) lines.push(`expect at ${at} schema ${schema} active`);
    for (const [schema, c] of schedulerCounts(steps, shown) ?? []) {
      lines.push(`expect at ${at} deadline misses ${schema} == ${c.deadlineMisses}`);
      lines.push(c.overruns === undefined
        ? `# overruns of ${schema} not pinned: its cycle still overran at ${at} (ORD tells how many releases it skipped when the cycle ends)`
        : `expect at ${at} overruns ${schema} == ${c.overruns}`);
    }
    return this.text(title) + (lines.length ? `# the state the Simulate panel showed at ${at}\n${lines.join('\n')}\n` : '');
  }
}

export interface RuleState {
  active: boolean;
  cause: string;
  timeNs: number;
}

/** What the Monitor folded of the session's periodic schemas (its state of the steps' records). */
export type SchedulerFigures = Pick<MonitorState, 'periodic'>;

/**
 * The deadline misses (ORD:0) and overruns (skipped releases) of each periodic schema released in
 * the steps, as the Monitor counted them from the steps' records; undefined when the steps do not
 * hold every record (the answer left some out: a count would be wrong). A schema whose cycle still
 * overruns has no overrun count: ORD tells the cycle's skipped releases when it ends.
 */
export function schedulerCounts(steps: SimulateStep[], shown: SchedulerFigures): Map<string, { deadlineMisses: number; overruns?: number }> | undefined {
  if (!steps.length || steps.some((s) => s.dropped || !s.records)) return undefined;
  return new Map([...shown.periodic].filter(([, p]) => p.releases > 0)
    .map(([schema, p]) => [schema, { deadlineMisses: p.deadlineMisses, ...(p.overrunning ? {} : { overruns: p.overruns }) }]));
}

/** Every rule that changed in the steps, with its last state and cause, keyed `SUP.fn.RULE` in order of first change. */
export function ruleStates(steps: SimulateStep[]): Map<string, RuleState> {
  const rules = new Map<string, RuleState>();
  for (const s of steps) for (const r of s.rules) rules.set(`${r.supervisor}.${r.function}.${r.rule}`, { active: r.active, cause: r.cause, timeNs: r.timeNs });
  return rules;
}
