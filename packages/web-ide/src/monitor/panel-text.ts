/**
 * The Monitor panel's words (monitor-panel.ts), as pure functions of what it shows: the time
 * readout, the follow button, a rule's row (its cause, accessible name and tooltip). Kept apart so that they are tested
 * without a page (panel-text.test.ts). What a record says (a value, a name, a line: anybody's, a
 * module's code writes its log) is written visibly (conventions' visibleText): a bidirectional
 * override, a control character or a character of no width as its escape, `\u202e`, as the CLI
 * shows it (docs/watching-a-run.md "Characters shown as escapes").
 */
import { visibleText } from '@contract-studio/conventions';
import { durationText, flowWaitsLine, priorityText, readableCause, SIMULATED_FLOWS_WHY, waitTotalsText, type FlowWaitTotals } from '@contract-studio/build-service/trace';
import { MAX_NAMES, quantileBoundNs, type EndedSchema, type FlowCount, type KeptRequests, type ModuleState, type MonitorState, type PeriodicState, type RuleState } from './monitor-state.js';

/** `+2.010325 s`: a time of the run (ns since its first record). */
export const fmtT = (ns: number): string => `+${(ns / 1e9).toFixed(6)} s`;

export interface ReadoutInput {
  /** The cursor's time, and the time of the run's last record (ns since its first). */
  t: number;
  end: number;
  /** Following a live run (the cursor at its last record). */
  following: boolean;
  /** While following: the run's own clock, estimated from when its records arrived (MonitorView.runClock); undefined before the first. */
  runClock?: number;
  /** Whether the state at `t` is exact (its raw records still kept). */
  exact: boolean;
}

/**
 * The time readout. Following a live run, it runs with the run's clock (a quiet stretch of the
 * run does not look stalled) and says where the shown state is: `+20.1 s · live (last record
 * +4.130000 s)`; before the run's first record, that it waits for it. Otherwise the cursor and
 * the run's end: `+1.500000 s / +4.130000 s`.
 */
export function timeReadout({ t, end, following, runClock, exact }: ReadoutInput): string {
  // a live run (its build, its modules' init) before its first record: no time to say yet
  if (following && runClock === undefined && end === 0) return 'waiting for the run\'s first record · live';
  const approximate = exact ? '' : ' · counters approximate this far back';
  if (following && runClock !== undefined) return `+${(Math.max(runClock, end) / 1e9).toFixed(1)} s · live (last record ${fmtT(end)})${approximate}`;
  return `${fmtT(t)} / ${fmtT(end)}${following ? ' · live' : ''}${approximate}`;
}

export interface FollowButton {
  text: string;
  /** Its accessible name: what pressing it does (it is no toggle: no aria-pressed). */
  label: string;
  title: string;
}

/**
 * The follow button: on a live run it pauses (❚❚ Pause) and follows the newest record again
 * (⇥ Follow); on a run that ended there is nothing to follow: ⇥ End puts the cursor at its end.
 * An action button whose words change with what it does, never "pressed".
 */
export function followButton(live: boolean, following: boolean): FollowButton {
  if (live && following) return { text: '❚❚ Pause', label: 'Pause', title: 'Following the live run: pause here (Space)' };
  if (live) return { text: '⇥ Follow', label: 'Follow live', title: 'Paused: follow the live run again (Space, End)' };
  return {
    text: '⇥ End', label: 'Go to the end',
    title: following ? 'The cursor is at the end of the run, which has ended (Space pauses here, Home goes to the start)' : 'Put the cursor at the end of the run (End)',
  };
}

/** Marks a supervisor, function or rule the run names and the model no longer has. */
export const NOT_IN_MODEL = '(not in the model)';
export const NOT_IN_MODEL_LONG = 'not in the model: renamed or removed since this run';

export interface RuleTexts {
  /** The shown cause: `← MAA:2 = "disconnected" → schemaCommande1` (what it started, while active), `off ← ...` once inactive, '' before. */
  shown: string;
  /**
   * Its accessible name, the state said in words (a lit rule is a plain button that opens the
   * rule, not a toggle): `SECOND, active since +2.010325 s ← MAA:2 = "disconnected" → schemaCommande1`,
   * `FIRST, inactive since +2.010325 s ← MAA:2 = "disconnected"`, `THIRD, not active yet`, and
   * `, not in the model: ...` for a rule the model no longer has.
   */
  label: string;
  /** The tooltip: the whole cause (the row cuts it) and what a click does. */
  title: string;
}

/**
 * The words of rule `fn.rule`'s row; `gone`: the model no longer has it; `fnGone`: nor its function
 * (or its supervisor): a click has nothing to open.
 */
export function ruleTexts(fn: string, rule: string, rs: Pick<RuleState, 'active' | 'since' | 'cause' | 'started'> | undefined, gone: boolean, fnGone = false): RuleTexts {
  const cause = rs ? `← ${visibleText(readableCause(rs.cause))}${rs.active && rs.started.length ? ` → ${visibleText(rs.started.join(', '))}` : ''}` : '';
  const state = rs ? `${rs.active ? 'active' : 'inactive'} since ${fmtT(rs.since)}${cause ? ` ${cause}` : ''}` : 'not active yet';
  return {
    shown: rs && !rs.active ? `off ${cause}` : cause,
    label: `${visibleText(rule)}, ${state}${gone ? `, ${NOT_IN_MODEL_LONG}` : ''}`,
    title: `${visibleText(`${fn}.${rule}`)}${rs ? ` ${state}` : `: ${state}`}${gone ? ` · ${NOT_IN_MODEL_LONG}${fnGone ? ', and so is its function: nothing to open' : ': click to open its function'}` : ' · click to open it in its .contract file'}`,
  };
}

/**
 * ` · 593 dropped (queue full: SRT does not read it fast enough)` for a data flow `A:0->SRT:0` that
 * dropped values, else ''.
 */
export function flowDropText(key: string, f: FlowCount): string {
  if (!f.dropped) return '';
  const consumer = key.slice(key.indexOf('->') + 2).split(':')[0];
  const why = f.dropReason === 'queue full' ? `queue full: ${consumer} does not read it fast enough` : f.dropReason;
  return ` · ${f.dropped} dropped (${visibleText(why ?? '')})`;
}

/**
 * ` · ⚠ waited for room 24 times (5.765 s in all, up to 298.55 ms)` on an event flow's Deliveries
 * row when its posts waited for room in the subscriber's full mailbox: the totals over all its
 * streaks so far, in `contract trace`'s words, else ''.
 */
export function flowWaitText(f: FlowCount): string {
  return f.waits ? ` · ⚠ ${waitTotalsText(waitTotals(f))}` : '';
}

/**
 * The title of that row: the story's closing line for the flow (`PSH's events to BIN (PSH:0 ->
 * BIN:0) waited for room 24 times (...): BIN takes its events slower than PSH posts them; delivery
 * latency up to 1.6 s`), with the totals so far; '' for a flow that did not wait. `key`: `PSH:0->BIN:0`.
 */
export function flowWaitTitle(key: string, f: FlowCount): string {
  if (!f.waits) return '';
  const [from = '', to = ''] = key.split('->');
  const name = (end: string): string => end.slice(0, end.lastIndexOf(':'));
  return visibleText(flowWaitsLine(`${from} -> ${to}`, name(from), name(to), waitTotals(f)));
}

function waitTotals(f: FlowCount): FlowWaitTotals {
  return { waits: f.waits ?? 0, waitNs: f.waitNs ?? 0, maxWaitNs: f.maxWaitNs ?? 0, maxLatencyNs: f.maxLatencyNs ?? 0 };
}

/**
 * ` · value "lost" · ⚠ 12 changed no rule` on a supervisor's event flow's Deliveries row: the last
 * value it received and how many of its events changed no rule (a rule waiting for another value:
 * `contract trace` tells them, `LFR got CAM:0 ×12 that changed no rule: "lsot" ×12`), else ''.
 */
export function flowValueText(f: FlowCount): string {
  if (f.lastValue === undefined) return '';
  return ` · value ${visibleText(f.lastValue)}${f.unmatched ? ` · ⚠ ${f.unmatched} changed no rule` : ''}`;
}

/**
 * A flow's Deliveries row: `┅ CAM:0 → LFR:0 ×2 · last +1.652499 s · value "found" · ⚠ 2 changed no
 * rule` (`━` for a data flow), its ports, value and findings written visibly. `key`: `CAM:0->LFR:0`.
 */
export function flowRow(kind: 'data' | 'event', key: string, f: FlowCount): string {
  return `${kind === 'data' ? '━' : '┅'} ${visibleText(key.replace('->', ' → '))} ×${f.count}${flowDropText(key, f)} · last ${fmtT(f.last)}${flowValueText(f)}${flowWaitText(f)}`;
}

/**
 * The Deliveries row of a connected data flow that delivered nothing or far less than read, told
 * once the records are over: `━ ⚠ data flow SRT:1 -> BLT:0 connected for 5.834 s (schema sortLoop): 0
 * values delivered (SRT posted none on its output :1); BLT read nothing in its 892 releases`; a
 * simulation's line saying why none is told (its modules ran no code) without ⚠.
 */
export function quietDataFlowRow(line: string): string {
  return isSimulatedFlowsLine(line) ? `━ ${visibleText(line)}` : `━ ⚠ ${visibleText(line)}`;
}

/** Whether a line of the flows' findings is a simulation's saying why its flows are not told (its modules ran no code): no warning. */
export function isSimulatedFlowsLine(line: string): boolean {
  return line.startsWith(SIMULATED_FLOWS_WHY);
}

/**
 * The Deliveries row of an event port whose events no one received: `┅ GCS:1 → no subscriber ×3 ·
 * no one received them · last +3.306199 s`.
 */
export function unheardEventsRow(port: string, f: FlowCount): string {
  return `┅ ${visibleText(port)} → no subscriber ×${f.count} · no one received ${f.count === 1 ? 'it' : 'them'} · last ${fmtT(f.last)}`;
}

/**
 * The modules whose code crashed, at the cursor (their `module_crashed` record read; a module
 * started again is no longer said): `⚠ EST crashed at +4.240958 s: signal 11 (SIGSEGV)`, and those
 * another module's record says are gone with no record of their end (killed from outside:
 * gone-signs.ts): `⚠ SRT gone at +3.024129 s: ORD: START request to SRT: module not running ...`;
 * one sentence each, sorted by time; '' when none.
 */
export function crashedModulesText(modules: ReadonlyMap<string, ModuleState>): string {
  const ended = [...modules].filter(([, m]) => m.crashed !== undefined || m.gone !== undefined).sort((a, b) => a[1].since - b[1].since);
  return ended.map(([name, m]) => visibleText(`⚠ ${name} ${(m.crashed ?? m.gone)!.replace(/^(crashed|gone): /, `$1 at ${fmtT(m.since)}: `)}`)).join('\n');
}

/**
 * A supervisor's line for a receiver whose full mailbox makes it keep its requests (while it does):
 * `keeping requests for VEL: its mailbox is full since +3.510000 s (first: STOP)`.
 */
export function keptRequestsLine(receiver: string, k: KeptRequests): string {
  return visibleText(`keeping requests for ${receiver}: its mailbox is full since ${fmtT(k.since)}${k.request ? ` (first: ${k.request})` : ''}`);
}

/**
 * What the Monitor says of records it did not fold because their names went past MAX_NAMES
 * (a log a module's code wrote: a run names far fewer), or '' when there were none.
 */
export function namesPastBoundText(n: number): string {
  if (!n) return '';
  return `⚠ ${n.toLocaleString('en-US')} record(s) named more supervisors, rules, schemas, modules and flows than the Monitor follows (${MAX_NAMES.toLocaleString('en-US')}): left out. A run names far fewer: did a module's code write into its log? contract trace tells every record.`;
}

/**
 * ` · release lateness p50 ≤ 42.2 µs, p99 ≤ 133 µs, max 988 µs`: how late ORD released the
 * schema's cycles (each cycle's first release after its tick), the quantiles as the bound of their
 * histogram bucket (an eighth of a decade: `contract trace` tells them finer); '' before any, or
 * when none was late (a simulation releases on its ticks).
 */
export function releaseLatenessText(p: Pick<PeriodicState, 'lateHistogram' | 'lateCycles' | 'maxLateNs'>): string {
  if (!p.lateCycles || !(p.maxLateNs > 0)) return '';
  const q = (x: number) => durationText(quantileBoundNs(p.lateHistogram, p.lateCycles, x, p.maxLateNs));
  return ` · release lateness p50 ≤ ${q(0.5)}, p99 ≤ ${q(0.99)}, max ${durationText(p.maxLateNs)}`;
}

/** Modules of a periodic schema whose CPU per release its block shows, at most: it says how many more there are. */
export const RELEASED_MODULES_SHOWN = 16;

/**
 * ` · CPU per release: CTL last 410 µs, max 1.25 ms; EST last 90 µs, max 120 µs`: the CPU time of
 * the schema's modules' own thread per release (their run_finished's `cpu_ns`: the exec region's
 * execution time, waiting not included, unlike the response time), in the order ORD released them,
 * the first RELEASED_MODULES_SHOWN, then how many more said theirs (`; 4 more modules not shown:
 * contract trace tells each`); '' when none said it (logs of older versions).
 */
export function moduleCpuText(released: readonly string[], modules: ReadonlyMap<string, Pick<ModuleState, 'lastCpuNs' | 'maxCpuNs'>>): string {
  const said = released.flatMap((name) => {
    const m = modules.get(name);
    return m?.lastCpuNs === undefined ? [] : [`${name} last ${durationText(m.lastCpuNs)}, max ${durationText(m.maxCpuNs ?? m.lastCpuNs)}`];
  });
  const more = said.length - RELEASED_MODULES_SHOWN;
  const notShown = more > 0 ? `; ${more} more ${more === 1 ? 'module' : 'modules'} not shown: contract trace tells each` : '';
  return said.length ? ` · CPU per release: ${visibleText(said.slice(0, RELEASED_MODULES_SHOWN).join('; '))}${notShown}` : '';
}

/**
 * The line above the active schemas saying how ORD was scheduled (its `priority` record): under nice
 * levels, deadline misses on a busy machine are expected, and the run settings' Real-time is the cure.
 */
export function schedulingText(detail: string): string {
  const how = `Scheduling: ORD ${visibleText(priorityText(detail))}`;
  return detail.startsWith('nice') ? `${how} (deadline misses are likely on a busy machine; the run settings' Real-time runs the modules at their SCHED_FIFO priorities)` : how;
}

/**
 * A periodic schema's block with no release: while a run goes on, not yet; once it has ended, never
 * (its schema was not activated); a run with no record at all did not start (a Build & Run whose
 * build failed): the run's label says why.
 */
export function notReleasedText(live: boolean, noRecords: boolean): string {
  if (live) return 'not released yet';
  return noRecords ? 'no release: the run has no records (it did not start: its label above says why)' : 'never released in this run';
}

/**
 * The count of a periodic schema's cycles ORD itself released past their CRITICAL_DELAY, in the words
 * of `contract trace`'s schema line (` · 2 cycles released past CRITICAL_DELAY (ORD itself late, no
 * ORD:0)`); nothing when there were none.
 */
export function lateReleasesText(n: number): string {
  return n ? ` · ${n} ${n === 1 ? 'cycle' : 'cycles'} released past CRITICAL_DELAY (ORD itself late, no ORD:0)` : '';
}

/**
 * The Active schemas' row when none is active: `none`, and once a schema has ended (state.lastEnded),
 * which one, when and why, so that an end reads as an end and not as a schema that never ran:
 * `none · schemaCommande1 (periodic) deactivated at +3.500000 s: SUP.action.SECOND, which activated
 * it, became inactive ← its function stopped`; an event schema `undone by SUP`; ORD's end
 * `ended with ORD (its exit record)`, or `shown ended: ORD's log ends there with no exit record`.
 */
export function noActiveSchemaText(s: Pick<MonitorState, 'lastEnded' | 'supervisors'>): string {
  const e = s.lastEnded;
  if (!e) return 'none';
  const what = `${e.name} (${e.kind === 'event' ? 'event schema' : e.kind})`;
  const at = fmtT(e.t);
  switch (e.how) {
    case 'ord-exit': return `none · ${what} ended with ORD at ${at} (its exit record)`;
    case 'ord-gone': return `none · ${what} shown ended at ${at}: ORD's log ends there with no exit record (killed?); whether it ran on is unknown`;
    default: {
      const verb = e.how === 'undone' ? `undone by ${e.by?.split('.')[0] ?? 'its supervisor'}` : 'deactivated by ORD';
      return `none · ${what} ${verb} at ${at}${endedRuleText(s, e)}`;
    }
  }
}

/** `: SUP.F.R, which activated it, became inactive ← cause` when that rule's last change, by the schema's end, made it inactive; else ''. */
function endedRuleText(s: Pick<MonitorState, 'supervisors'>, e: EndedSchema): string {
  const dot = e.by?.indexOf('.') ?? -1;
  if (dot <= 0) return e.by ? ` (activated by ${e.by})` : '';
  const rule = s.supervisors.get(e.by!.slice(0, dot))?.rules.get(e.by!.slice(dot + 1));
  if (!rule || rule.active || rule.since > e.t) return ` (activated by ${e.by})`;
  return `: ${e.by}, which activated it, became inactive ← ${readableCause(rule.cause).slice(0, 120)}`;
}
