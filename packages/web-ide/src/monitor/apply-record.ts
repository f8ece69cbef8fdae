/**
 * Folds one trace record into a MonitorState (docs/runtime-api.md "Trace records": which module
 * writes which kind, and what peer/port/detail hold). Pure and total: a record it does not use
 * changes only the record count; nothing read from the trace can make it throw.
 */
import { changedNoRule, crashText, receivedValue, dataDropReason, isRule, missedTicksOf, overrunningAfter, skippedReleasesOf, type KnownRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { goneModuleSign, type GoneSign } from './gone-signs.js';
import {
  HIST_BUCKETS, histogramBucket, MAX_NAMES, RECENT_MARKS,
  type MonitorState, type Ns, type PeriodicState, type SupervisorState, type FunctionState, type FlowCount, type SchemaActivation, type ModuleState,
} from './monitor-state.js';

const MAX_STARTED = 16;

/**
 * The record kinds applyRecord folds into the state; a record of any other kind changes only the
 * record count and the time (applyUnfolded). Kept beside the switch below: a kind added there is
 * added here (line-scan.test.ts folds an example of every kind of the trace table: one outside
 * this set must change nothing else).
 */
export const FOLDED_KINDS: ReadonlySet<string> = new Set([
  'sup_rule', 'supervisor', 'module_hold', 'flow_hold', 'module_priority', 'request_received', 'scheduler',
  'ord_release', 'ord_complete', 'ord_deadline_miss', 'run_started', 'run_finished', 'module_started', 'module_exit',
  'module_crashed', 'data_posted', 'data_dropped', 'event_posted', 'event_received', 'event_waited', 'requests_kept', 'requests_kept_end', 'priority', 'error',
]);

/** What applyRecord does with a well-formed record of a kind not in FOLDED_KINDS, at time t. */
export function applyUnfolded(s: MonitorState, t: Ns): void {
  s.records++;
  s.t = t;
}

/**
 * The entry `key` of `map`, made by `make` when new, unless the state already folds MAX_NAMES
 * names: then undefined, and the record is counted in namesPastBound instead of folded.
 */
function entry<V>(s: MonitorState, map: Map<string, V>, key: string, make: () => V): V | undefined {
  let v = map.get(key);
  if (v === undefined) {
    if (s.names >= MAX_NAMES) {
      s.namesPastBound++;
      return undefined;
    }
    s.names++;
    map.set(key, (v = make()));
  }
  return v;
}

/** Supervisor `name`'s state, to change: every caller changes it (supervisorChanges counts it). */
function sup(s: MonitorState, name: string): SupervisorState | undefined {
  const sv = entry(s, s.supervisors, name, () => ({ functions: new Map(), rules: new Map(), actionsDone: 0, actionsUndone: 0, heldModules: new Map(), heldFlows: new Map(), keptFor: new Map() }));
  if (sv) s.supervisorChanges++;
  return sv;
}

function schemaActivation(s: MonitorState, name: string, t: Ns): SchemaActivation | undefined {
  return entry(s, s.schemas, name, () => ({ active: false, since: t, activations: 0, conflicts: 0 }));
}

function moduleState(s: MonitorState, name: string, t: Ns): ModuleState | undefined {
  return entry(s, s.modules, name, () => ({ running: false, alive: true, runs: 0, since: t }));
}

function periodic(s: MonitorState, schema: string): PeriodicState | undefined {
  return entry(s, s.periodic, schema, () => ({
    releases: 0, modules: [], lastCycle: -1, lastRelease: 0, completions: 0, lastResponseNs: 0, maxResponseNs: 0, sumResponseNs: 0,
    histogram: new Array<number>(HIST_BUCKETS).fill(0), lateHistogram: new Array<number>(HIST_BUCKETS).fill(0), lateCycles: 0, maxLateNs: 0, deadlineMisses: 0, overruns: 0, overrunning: false, missedTicks: 0, lateReleases: 0, recentMisses: [], recentOverruns: [], recentLateReleases: [],
  }));
}

function pushBounded<T>(list: T[], item: T, max: number): void {
  list.push(item);
  if (list.length > max) list.shift();
}

function count(s: MonitorState, map: Map<string, FlowCount>, key: string, t: Ns): FlowCount | undefined {
  const f = entry(s, map, key, () => ({ count: 0, last: t }));
  if (!f) return undefined;
  f.count++;
  f.last = t;
  return f;
}

const num = (v: unknown): number | undefined => (typeof v === 'number' && Number.isFinite(v) ? v : undefined);
const str = (v: unknown): string | undefined => (typeof v === 'string' && v ? v : undefined);

/**
 * Supervisor `sup`'s request to ORD for periodic `schema` that ORD's START from it stands for: the
 * oldest one its log names and ORD has not answered (`activate schema S() (activation #N, to
 * ORD)`: requests reach ORD in the order they are sent), else none (a log of an older version,
 * without that line: the rule that became active last is taken).
 */
function askedOf(s: MonitorState, sup: string, schema: string): { sup: string; rule?: string; activation?: string } {
  const sv = s.supervisors.get(sup);
  for (const [activation, req] of sv?.toOrd ?? []) {
    if (req.schema === schema) return { sup, rule: req.rule || undefined, activation };
  }
  return { sup, rule: sv?.lastRule };
}

/** Supervisor `sup`'s request to ORD `activation` answered or undone: no longer followed. */
function answered(s: MonitorState, sup: string, activation: string | undefined): void {
  if (activation !== undefined && s.supervisors.get(sup)?.toOrd?.delete(activation)) s.names--;
}

/**
 * ORD activated periodic `schema` (its `activate` line, `f` its fields): whose activation it
 * serves, from the line's `(activation #N from SUP)` and that supervisor's own line for #N (the
 * rule whose action asked for it), else from the START it received last for the schema.
 */
function servedBy(s: MonitorState, sc: SchemaActivation, schema: string, f: Record<string, unknown>): void {
  const requester = str(f['requester']);
  const activation = num(f['activation']);
  const asked = sc.asked;
  sc.asked = undefined;
  let sup: string | undefined;
  let rule: string | undefined;
  if (requester !== undefined && activation !== undefined) {
    sup = requester;
    const req = s.supervisors.get(requester)?.toOrd?.get(String(activation));
    if (req?.schema === schema) rule = req.rule || undefined;
    else if (asked?.sup === requester) rule = asked.rule;
    answered(s, requester, String(activation));
  } else if (asked) {
    ({ sup, rule } = asked);
    answered(s, asked.sup, asked.activation);
  }
  sc.by = sup === undefined ? undefined : rule ? `${sup}.${rule}` : sup;
  if (sup !== undefined && s.supervisors.has(sup)) noteStarted(s, sup, schema, rule);
}

/** `what` started by supervisor `supName`'s rule `ruleKey` (`F.R`; by default the one that became active last). */
function noteStarted(s: MonitorState, supName: string, what: string, ruleKey?: string): void {
  const sv = s.supervisors.get(supName);
  const key = ruleKey ?? sv?.lastRule;
  const rule = key ? sv?.rules.get(key) : undefined;
  if (rule && !rule.started.includes(what) && rule.started.length < MAX_STARTED) {
    rule.started.push(what);
    s.supervisorChanges++;
  }
}

// The folds of the kinds a 1 kHz schema writes most, from the fields they use: applyRecord calls
// them with a parsed record's fields, hot-line.ts with the fields read off the line in place.

/** ord_release: `schema`, `cycle`, `release_ns`, `tick_ns` as the reader types them (str/num). */
export function foldRelease(s: MonitorState, schema: string | undefined, cycle: number | undefined, releaseNs: number | undefined, t: Ns, t0: number, tickNs?: number, module?: string): void {
  if (!schema) return;
  const p = periodic(s, schema);
  if (!p) return;
  p.releases++;
  if (module && p.modules.length < MAX_NAMES && !p.modules.includes(module)) p.modules.push(module);
  if (cycle !== undefined && cycle !== p.lastCycle && releaseNs !== undefined && tickNs !== undefined && releaseNs >= tickNs) {
    // a cycle's first release: how late ORD sent it after its tick
    const late = releaseNs - tickNs;
    p.lateHistogram[histogramBucket(late)]!++;
    p.lateCycles++;
    if (late > p.maxLateNs) p.maxLateNs = late;
  }
  if (cycle !== undefined) p.lastCycle = cycle;
  p.lastRelease = releaseNs !== undefined ? releaseNs - t0 : t;
}

/** ord_complete: `schema`, `response_ns`. */
export function foldComplete(s: MonitorState, schema: string | undefined, resp: number | undefined): void {
  if (!schema || resp === undefined) return;
  const p = periodic(s, schema);
  if (!p) return;
  p.completions++;
  p.overrunning = false;
  p.lastResponseNs = resp;
  p.sumResponseNs += resp;
  if (resp > p.maxResponseNs) p.maxResponseNs = resp;
  p.histogram[histogramBucket(resp)]!++;
}

/** run_started (`started`) or run_finished of `module`, with the CPU time its run took (`cpu_ns`) when the record says it. */
export function foldRun(s: MonitorState, module: string, started: boolean, t: Ns, cpuNs?: number): void {
  const m = moduleState(s, module, t);
  if (!m) return;
  m.running = started;
  if (started) m.runs++;
  m.since = t;
  // a module's exec region only: ORD's and a supervisor's run is their whole life, no release
  if (!started && cpuNs !== undefined && cpuNs > 0 && module !== 'ORD' && !s.supervisors.has(module)) {
    m.lastCpuNs = cpuNs;
    if (cpuNs > (m.maxCpuNs ?? 0)) m.maxCpuNs = cpuNs;
  }
}

/** data_posted: `module`'s output `port` to `peer`'s `to_port`. */
export function foldDataPosted(s: MonitorState, module: string, port: number | null, peer: string, toPort: number | undefined, t: Ns): void {
  if (!peer || port === null || toPort === undefined) return;
  count(s, s.dataFlows, `${module}:${port}->${peer}:${toPort}`, t);
}

/** data_dropped: a value of `module`'s output `port` for `peer`'s `to_port` that was not sent, and why (dataDropReason: `queue full`). */
export function foldDataDropped(s: MonitorState, module: string, port: number | null, peer: string, toPort: number | undefined, reason: string, t: Ns): void {
  if (!peer || port === null || toPort === undefined) return;
  // a flow that never delivered: `last` is when it was first seen
  const f = entry<FlowCount>(s, s.dataFlows, `${module}:${port}->${peer}:${toPort}`, () => ({ count: 0, last: t }));
  if (!f) return;
  f.dropped = (f.dropped ?? 0) + 1;
  f.dropReason = reason.slice(0, 80);
}

/**
 * event_waited: a streak of `module`'s posts on its output `port` that waited for room in `peer`'s
 * full mailbox (its input `to_port`), added to the flow's totals over all its streaks (waits, their
 * time in all, the longest), as `contract trace`'s closing line for the flow counts them.
 */
function foldEventWaited(s: MonitorState, k: KnownRecord, t: Ns): void {
  const toPort = num(k.fields['to_port']);
  if (!k.peer || k.port === null || toPort === undefined) return;
  // a flow whose events were not received yet: `last` is when it was first seen
  const f = entry<FlowCount>(s, s.eventFlows, `${k.module}:${k.port}->${k.peer}:${toPort}`, () => ({ count: 0, last: t }));
  if (!f) return;
  const waits = whole(k.fields['waits']);
  if (!(waits > 0)) return;
  f.waits = (f.waits ?? 0) + waits;
  f.waitNs = (f.waitNs ?? 0) + whole(k.fields['wait_ns']);
  f.maxWaitNs = Math.max(f.maxWaitNs ?? 0, whole(k.fields['max_wait_ns']));
}

/** A whole, positive number of a record's fields, else 0 (a forged word is no count: EventWaits reads them so). */
function whole(v: unknown): number {
  return typeof v === 'number' && Number.isSafeInteger(v) && v > 0 ? v : 0;
}

/** Longest event value kept for a flow's row (the runtime cuts a string at 64 characters; a datatype's fields may be longer). */
const MAX_VALUE_CHARS = 80;

/** Longest request name kept for the panel (a forged detail can be a whole line). */
const MAX_REQUEST_CHARS = 40;

/**
 * requests_kept (`kept`) or requests_kept_end of supervisor `module` for receiver `peer`: the
 * receiver is listed while the supervisor keeps requests for it. A receiver no longer listed is a
 * name no longer folded (names counts down): a module slow now and then begins a new streak each
 * time, and that must not fill the bound of names of a real run.
 */
function foldKept(s: MonitorState, module: string, peer: string, kept: boolean, request: unknown, t: Ns): void {
  if (!peer) return;
  if (!kept) {
    const sv = s.supervisors.get(module);
    if (sv?.keptFor.delete(peer)) {
      s.names--;
      s.supervisorChanges++;
    }
    return;
  }
  const sv = sup(s, module);
  const k = sv && entry(s, sv.keptFor, peer, () => ({ since: t, request: '' }));
  if (!k) return;
  // a streak begun again without its end (a log cut, a forged one): the newer one
  k.since = t;
  k.request = typeof request === 'string' || typeof request === 'number' ? String(request).slice(0, MAX_REQUEST_CHARS) : '';
}

/** A supervisor that ended (its exit, its crash) keeps nothing any more, whatever its log said last. */
function endKept(s: MonitorState, module: string): void {
  const sv = s.supervisors.get(module);
  if (!sv?.keptFor.size) return;
  s.names -= sv.keptFor.size;
  sv.keptFor.clear();
  s.supervisorChanges++;
}

/**
 * ORD ended at `t` (its exit or crash record, `ord-exit`; or, when its log ends with no exit record,
 * its last record, `ord-gone`: monitor-model.ts OrdEnd): no periodic schema runs any more, and ORD
 * runs nothing; the schemas it ended are the last ended (lastEnded, said under Active schemas).
 * Schemas shown ended stay so (`since` kept): applied again to a state that has it, it changes nothing.
 */
export function endOrdSchemas(s: MonitorState, t: Ns, how: 'ord-exit' | 'ord-gone' = 'ord-gone'): void {
  const ended: string[] = [];
  for (const [name, sc] of s.schemas) {
    if (!sc.active) continue;
    sc.active = false;
    sc.since = t;
    if (ended.length < 8) ended.push(name);
  }
  if (ended.length) s.lastEnded = { name: ended.join(', '), kind: 'periodic', t, how };
  const ord = s.modules.get('ORD');
  if (ord) ord.running = false;
}

/**
 * A record (or the launcher's line) says module `sign.module` is no longer running (gone-signs.ts), though its log wrote no
 * end: shown gone from then on, as a crash is (a module whose end was read, or that crashed, is left as it is).
 */
export function foldGone(s: MonitorState, sign: GoneSign, t: Ns): void {
  const m = s.modules.get(sign.module);
  if (!m || !m.alive || m.crashed !== undefined || m.gone !== undefined) return;
  m.gone = `gone: ${sign.words}`;
  m.running = false;
  m.since = t;
}

/** Whether `k` is an `event_posted` record of an event no one received (`no subscriber`, no peer). */
export function isUnheardEvent(k: KnownRecord): boolean {
  return k.kind === 'event_posted' && !k.peer && k.detail === 'no subscriber';
}

/** The event port an unheard event was posted on: `GCS:1`. */
export function unheardPort(k: KnownRecord): string {
  return `${k.module}:${k.port ?? '?'}`;
}

/** `t`: the record's time in ns since the run's first record; `t0`: that first record's mono_ns. */
export function applyRecord(s: MonitorState, r: TraceRecord, t: Ns, t0: number): void {
  if (r.kind === 'unknown') {
    s.unknownLines++;
    return;
  }
  s.records++;
  s.t = t;
  if (isRule(r)) {
    const sv = sup(s, r.module);
    const key = `${r.function}.${r.rule}`;
    const rule = sv && entry(s, sv.rules, key, () => ({ function: r.function, rule: r.rule, active: false, since: t, cause: '', activations: 0, started: [] }));
    if (!sv || !rule) return;
    rule.active = r.active;
    rule.since = t;
    rule.cause = r.cause.slice(0, 200);
    if (r.active) {
      rule.activations++;
      rule.started = [];
      sv.lastRule = key;
    }
    return;
  }
  const k = r as KnownRecord;
  const f = k.fields ?? {};
  if (k.kind === 'error' || k.kind === 'scheduler') {
    const sign = goneModuleSign(k);
    if (sign) foldGone(s, sign, t);
  }
  switch (k.kind) {
    case 'supervisor': {
      const sv = sup(s, k.module);
      if (!sv) return;
      const what = f['what'];
      const fn = str(f['function']);
      const fs = fn && (what === 'function_started' || what === 'function_stopped' || what === 'function_refused')
        ? entry(s, sv.functions, fn, () => ({ state: 'stopped' as FunctionState['state'], since: t })) : undefined;
      if (what === 'function_started' && fs) Object.assign(fs, { state: 'running', since: t });
      else if (what === 'function_stopped' && fs) Object.assign(fs, { state: 'stopped', since: t });
      else if (what === 'function_refused' && fs) Object.assign(fs, { state: fs.state === 'running' ? 'running' : 'refused', since: t });
      else if (what === 'action') {
        // a module started or stopped, a flow connected or disconnected, a priority claimed or
        // released (field `action`): counted here, once; the hold and priority records that follow
        // are then not counted (a log of an older version has no such line: they count instead)
        if (f['action'] !== undefined) sv.actionLines = true;
        const schema = str(f['schema']);
        const activation = num(f['activation']);
        if (/^undo\b|^un/.test(k.detail)) {
          sv.actionsUndone++;
          if (schema && k.detail.endsWith('(event schema)')) {
            const rule = sv.eventSchemas?.get(schema);
            if (rule !== undefined) s.lastEnded = { name: schema, kind: 'event', t, how: 'undone', by: rule ? `${k.module}.${rule}` : k.module };
            if (sv.eventSchemas?.delete(schema)) s.names--;
          } else if (schema && activation !== undefined && k.detail.endsWith(', to ORD)')) {
            // the undo of a request ORD never activated (refused: ORD:1): no longer waited for
            answered(s, k.module, String(activation));
          }
        } else {
          sv.actionsDone++;
          const rule = sv.lastRule ?? '';
          if (schema && k.detail.endsWith('(event schema)')) {
            // an event schema it runs itself: what its rule started, and whose it is while it runs
            noteStarted(s, k.module, schema);
            const runs = (sv.eventSchemas ??= new Map());
            if (entry(s, runs, schema, () => rule) !== undefined) runs.set(schema, rule);
          } else if (schema && activation !== undefined && k.detail.endsWith(', to ORD)')) {
            // a periodic schema asked of ORD: the activation ORD serves for #N is this rule's, whenever ORD receives it
            const requests = (sv.toOrd ??= new Map());
            entry(s, requests, String(activation), () => ({ schema, rule }));
          }
        }
      }
      return;
    }
    case 'module_hold':
    case 'flow_hold': {
      const sv = sup(s, k.module);
      if (!sv) return;
      const held = k.kind === 'module_hold' ? sv.heldModules : sv.heldFlows;
      if (k.detail.startsWith('hold taken')) {
        const rule = sv.lastRule ?? '';
        if (entry(s, held, k.peer, () => rule) !== undefined) held.set(k.peer, rule);
        if (!sv.actionLines) sv.actionsDone++;
        // the modules its rule took a hold on: one that was running already (another supervisor, the
        // user or the launcher started it) is said shared, not started by it
        if (k.kind === 'module_hold') noteStarted(s, k.module, k.detail.includes('(it was running)') ? `${k.peer} (shared)` : k.peer);
      } else if (k.detail.startsWith('last hold dropped') || k.detail.startsWith('hold dropped')) {
        // its hold is gone either way: the last one, or kept for another supervisor (`hold dropped (kept running: …)`)
        held.delete(k.peer);
        if (!sv.actionLines) sv.actionsUndone++;
      }
      return;
    }
    case 'module_priority': {
      const sv = sup(s, k.module);
      if (sv && !sv.actionLines) sv.actionsDone++;
      return;
    }
    case 'request_received': {
      // ORD receives `START schema` from a supervisor: whose request it is, until ORD activates
      // the schema (its `activate` line names the activation it serves) or refuses it (`conflict`)
      if (k.module !== 'ORD') return;
      const m = /^START ([A-Za-z_]\w*)$/.exec(k.detail);
      if (m && k.peer) {
        const sc = schemaActivation(s, m[1]!, t);
        if (sc) sc.asked = askedOf(s, k.peer, m[1]!);
        // an older simulation's trace has ORD's `activate` (without activation numbers) before the
        // START it answers, at the same time: the START says whose it is then
        if (sc?.active && sc.by === undefined && sc.since === t) servedBy(s, sc, m[1]!, {});
      }
      return;
    }
    case 'scheduler': {
      const schema = str(f['schema']);
      if (!schema) return;
      const what = f['what'];
      if (what === 'activate' || what === 'deactivate' || what === 'conflict') {
        const sc = schemaActivation(s, schema, t);
        if (!sc) return;
        if (what === 'activate') {
          sc.active = true;
          sc.since = t;
          sc.activations++;
          servedBy(s, sc, schema, f);
        } else if (what === 'deactivate') {
          if (sc.active) s.lastEnded = { name: schema, kind: 'periodic', t, how: 'deactivated', ...(sc.by ? { by: sc.by } : {}) };
          sc.active = false;
          sc.since = t;
          const p = s.periodic.get(schema);
          if (p) p.overrunning = false;
        } else {
          // refused: the START it received is answered, the activation shown stays the one ORD serves
          sc.conflicts++;
          sc.asked = undefined;
        }
      } else if (what === 'overrun' || what === 'overrun_ended') {
        // every skipped release, as ORD counts them (ord-counts.ts); a mark at each cycle's first
        const p = periodic(s, schema);
        if (!p) return;
        p.overruns += skippedReleasesOf(f);
        p.overrunning = overrunningAfter(f) ?? p.overrunning;
        if (what === 'overrun') pushBounded(p.recentOverruns, { t, cycle: p.lastCycle }, RECENT_MARKS);
      } else if (what === 'late_release') {
        // a cycle ORD itself released past its CRITICAL_DELAY: its miss, told by its own line (no ORD:0)
        const p = periodic(s, schema);
        if (!p) return;
        p.lateReleases++;
        pushBounded(p.recentLateReleases, { t, cycle: num(f['cycle']) ?? -1 }, RECENT_MARKS);
      } else if (what === 'missed_tick' || what === 'missed_ticks_ended') {
        const p = periodic(s, schema);
        if (p) p.missedTicks += missedTicksOf(f);
      }
      return;
    }
    case 'ord_release':
      foldRelease(s, str(f['schema']), num(f['cycle']), num(f['release_ns']), t, t0, num(f['tick_ns']), k.peer);
      return;
    case 'ord_complete':
      foldComplete(s, str(f['schema']), num(f['response_ns']));
      return;
    case 'ord_deadline_miss': {
      const schema = str(f['schema']);
      if (!schema) return;
      const p = periodic(s, schema);
      if (!p) return;
      p.deadlineMisses++;
      pushBounded(p.recentMisses, { t, cycle: num(f['cycle']) ?? -1 }, RECENT_MARKS);
      return;
    }
    case 'run_started':
    case 'run_finished':
      foldRun(s, k.module, k.kind === 'run_started', t, num(f['cpu_ns']));
      return;
    case 'priority':
      // ORD's: whether the run was real-time (SCHED_FIFO) or at nice levels, as contract trace says after its start
      if (k.module === 'ORD') s.ordPriority = k.detail.slice(0, 80);
      return;
    case 'module_started':
    case 'module_exit':
    case 'module_crashed': { // the runtime's last record of a module that crashed: its end, as an exit
      if (k.kind !== 'module_started') endKept(s, k.module);
      const m = moduleState(s, k.module, t);
      if (!m) return;
      m.alive = k.kind === 'module_started';
      if (!m.alive) m.running = false;
      if (k.kind === 'module_crashed') m.crashed = crashText(k.detail).slice(0, 160);
      else if (k.kind === 'module_started') m.crashed = undefined;
      m.gone = undefined;
      m.since = t;
      // ORD gone (the end of a run: the launcher stops it before the supervisors, whose undos then
      // find no ORD to deactivate their schemas): no periodic schema runs any more
      if (!m.alive && k.module === 'ORD') endOrdSchemas(s, t, 'ord-exit');
      return;
    }
    case 'data_posted':
      foldDataPosted(s, k.module, k.port, k.peer, num(f['to_port']), t);
      return;
    case 'data_dropped':
      foldDataDropped(s, k.module, k.port, k.peer, num(f['to_port']), dataDropReason(k.detail), t);
      return;
    case 'requests_kept':
    case 'requests_kept_end':
      foldKept(s, k.module, k.peer, k.kind === 'requests_kept', f['request'], t);
      return;
    case 'event_posted':
      // an event no one received: counted per port (one a subscriber received is not folded)
      if (isUnheardEvent(k)) count(s, s.unheardEvents, unheardPort(k), t);
      return;
    case 'event_waited':
      foldEventWaited(s, k, t);
      return;
    case 'event_received': {
      const from = num(f['from_port']);
      if (!k.peer || k.port === null || from === undefined) return;
      const flow = `${k.peer}:${from}->${k.module}:${k.port}`;
      const counted = count(s, s.eventFlows, flow, t);
      // the longest delivery latency, which the story's closing line of a flow that waited names
      const latency = whole(f['latency_ns']);
      if (counted && latency > (counted.maxLatencyNs ?? 0)) counted.maxLatencyNs = latency;
      // a supervisor's: the value it received, and whether it changed no rule (unmatched-events.ts)
      const value = receivedValue(k);
      if (!counted || value === undefined) return;
      counted.lastValue = value.length > MAX_VALUE_CHARS ? `${value.slice(0, MAX_VALUE_CHARS)}…` : value;
      if (changedNoRule(k)) counted.unmatched = (counted.unmatched ?? 0) + 1;
      return;
    }
    default:
      return;
  }
}
