/**
 * The machinery of the differential tests (differential*.bwrap.test.ts): run an example for real
 * (`contract run --sandbox bwrap`: real processes, the real module code), turn its CSV trace into a
 * scenario (the events the supervisors got, at the times they got them since the start function
 * started), run that scenario in the simulator, and put both sides' supervisor decisions
 * (`sup_rule`) in one comparable form.
 *
 * What is replayed, and when: every event a supervisor received from a module that is not a
 * supervisor, from the supervisor's own log (`request_received`, `EVENT from_port=N`, peer = the
 * producer), at the time it was received. The receiver's log, not the producer's `event_posted`:
 * a supervisor decides in the order its mailbox gives it, and logs the receipt before it decides on
 * it, in the same file; a producer logs a post once sent, and on a loaded machine it can be
 * preempted in between, so the posts' log order is not the order of arrival. An event a producer
 * sent to several supervisors (ORD's, to each subscriber) is one scenario event: the k-th receipt
 * of that source at each supervisor (each mailbox is first in, first out), at the first of their
 * times. A supervisor's own notifications
 * are not replayed (the simulated supervisor makes them). Two timings of a real run that the
 * simulator (where a message takes no time) would meet in another order are moved: inFlight (an
 * event received while another supervisor's request was on its way) and shortRuns (a function
 * stopped before its `elapsed` timer came).
 *
 * The comparison ends when the launcher stops the run (the first supervisor's STOP from it), or
 * earlier when a request one supervisor sent another was still on its way then
 * (endBeforeUnreceived): the simulator delivers a request at the decision that sends it. The real
 * decisions compared are those on inputs before the end, though logged after it
 * (decisionsOnInputsBefore): the simulator, run until the end, makes them too.
 *
 * A module run that its own code ended (`run_finished` with no STOP: the tutorial's MAB at once,
 * MAA after posting "disconnected" when its end comes before SUP's STOP) is replayed as `finish M`
 * at the time it ended, before an event
 * logged at the same time, so that the simulated supervisors find the module as the real ones did
 * (its STOP finding no run); or, when that STOP was decided on an event the supervisor received
 * before the end, just before that event (ownEndBeforeStop: the simulator delivers the STOP at the
 * decision).
 *
 * Which ORD events there are (deadline misses `ORD:0`, conflicts `ORD:1`) depends on the machine's
 * timing, so the simulated ORD (whose virtual modules are never late) cannot make them by itself:
 * they are replayed like the others.
 *
 * Values: the CSV has none for an event (only its size), but a rule change it caused names it
 * (`cause=OBS:0 value=0.35`), and it goes to the latest receipt of that source by the deciding
 * supervisor before the decision (the same file: no guessing). An ORD event names its schema in
 * ORD's own records: the k-th `ord_deadline_miss` for the k-th `ORD:0`, the k-th conflict for the
 * k-th `ORD:1`. A datatype's value is logged field by field (`{v=0.5,w=0}`) and replayed as that
 * value (scenarioValueOf); one logged abridged (an array's first elements, `...`), older logs'
 * `{N bytes}` and events that changed no rule name no value: those take the example's `fallback`
 * (a value the test explains), else the type's default.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { isRule, ownRunEndText, parseTrace, type KnownRecord, type RuleRecord, type TraceRecord } from '@contract-studio/build-service/trace';
import { formatTime, loadScenario, runLoadedScenario, type RuleChange, type ScenarioResult } from '../../src/index.js';
import { prepared, REPO } from '../support.js';

export interface RealRun {
    records: TraceRecord[];
    code: number | null;
    /** stderr and the end of stdout, for the assertion message. */
    output: string;
    cleanUp(): void;
}

/** Runs a copy of `project` (without its logs) for `duration` in bwrap and reads its CSV trace. */
export function runForReal(project: string, duration: string): RealRun {
    const scratch = mkdtempSync(join(tmpdir(), 'contract-sim-diff-'));
    const name = basename(project);
    cpSync(project, join(scratch, name), { recursive: true, filter: (src) => !/\/(logs|run)$/.test(src) });
    const run = spawnSync(process.execPath, [join(REPO, 'packages/cli/bin/contract.js'), 'run', name, '--sandbox', 'bwrap', '--duration', duration, '--logs', join(scratch, 'logs'), '--format', 'json'],
        { cwd: scratch, encoding: 'utf8', timeout: 280_000, maxBuffer: 64 * 1024 * 1024 });
    const dir = join(scratch, 'logs');
    let files: { name: string; text: string }[] = [];
    try {
        files = readdirSync(dir).filter((f) => f.endsWith('.csv')).map((f) => ({ name: f, text: readFileSync(join(dir, f), 'utf8') }));
    } catch {
        /* no logs: the status says why */
    }
    return {
        records: parseTrace(files),
        code: run.status,
        output: `${run.stderr ?? ''}\n${(run.stdout ?? '').slice(-2000)}`,
        cleanUp: () => rmSync(scratch, { recursive: true, force: true }),
    };
}

export interface ReplayPlan {
    /** The supervisors of the project. */
    supervisors: ReadonlySet<string>;
    /** The function the launcher starts, as a scenario `start` takes it (`GLB.mission()`). */
    start: string;
    /** The value of an event whose value the logs do not give (undefined: the port type's default). */
    fallback?: (module: string, port: number) => string | undefined;
    /**
     * The scenario value of a cause the logs print abridged (an array shows its first elements:
     * `{ranges=[5,5,...],blocked=true}`), rebuilt from what the module is known to send; undefined:
     * the logged text is the value.
     */
    causeValue?: (module: string, port: number, logged: string) => string | undefined;
    /**
     * Per supervisor, the rules of other supervisors whose changes send it a request
     * (`SUP function.RULE`: a rule that does `activate supervisor X.f()` sends X a START when it
     * becomes active and a STOP when it ends), so that the k-th request X received from SUP is
     * matched with the k-th such change of SUP (a mailbox is first in, first out). Without it, a
     * request is taken as sent by the sender's latest decision before it was received, which is
     * wrong when the receiver was not scheduled meanwhile and the sender decided again.
     */
    requestRules?: Readonly<Record<string, readonly string[]>>;
}

export interface RunScenario {
    /** The scenario text: `until`, `start`, then one line per replayed event. */
    text: string;
    /** The run's `sup_rule` records of the supervisors on inputs before the comparison's end (the scenario's `until`). */
    real: RuleRecord[];
    /** How many replayed events of each source (`OBS:0`, `ORD:0`...), for the test's own checks. */
    counts: Map<string, number>;
    /** The modules whose runs their own code ended, once per such run, in time order (`finish` steps). */
    finished: string[];
    /** What inFlight and shortRuns moved (or left, and why), for a failure's message (firstDifference). */
    adjustments: string[];
}

const mono = (r: KnownRecord | RuleRecord): bigint => BigInt(r.monoNs);
const LOGGED_DATATYPE = /^\{\d+ bytes\}$/;
const EVENT_RECEIVED = /^EVENT from_port=(\d+)/;

/** One event as the scenario replays it: received by one supervisor or more. */
interface Emission {
    /** The first of its receipts. */
    t: bigint;
    source: string;
    value?: string;
}

/** An event received by one supervisor, in its log's order. */
interface Receipt {
    t: bigint;
    source: string;
    emission?: Emission;
}

/** The scenario of a real run (see the header for what is replayed). */
export function scenarioOfRun(records: TraceRecord[], plan: ReplayPlan): RunScenario {
    const known = records.filter((r): r is KnownRecord | RuleRecord => r.kind !== 'unknown');
    const [startSup, startFn] = plan.start.replace(/\(.*$/, '').split('.');
    const started = known.find((r) => r.module === startSup && r.kind === 'supervisor' && r.fields['what'] === 'function_started' && r.fields['function'] === startFn);
    if (!started) throw new Error(`the run has no "function ${startFn} started" record of ${startSup}`);
    const t0 = mono(started);
    // the launcher's stop (KILL/STOP from contract-launch) ends the comparison
    const stop = known.find((r) => plan.supervisors.has(r.module) && r.kind === 'request_received' && r.peer === 'contract-launch' && /^(STOP|KILL)/.test(r.detail));
    const launcherStop = stop ? mono(stop) : BigInt(Number.MAX_SAFE_INTEGER);

    // when each supervisor's engine took each module event (event_received, in its log's order): a
    // supervisor waiting for a module's answer (a priority change, docs/engines.md "Known limits")
    // takes an event that arrived meanwhile later, and the simulator, which never waits, is given it
    // then; events of a log without them (and ORD's) count from their arrival
    const takes = new Map<string, bigint[]>(); // `${supervisor} ${source}` -> times taken
    for (const r of known) {
        if (r.kind !== 'event_received' || !plan.supervisors.has(r.module) || plan.supervisors.has(r.peer)) continue;
        const key = `${r.module} ${r.peer}:${(r as KnownRecord).fields?.['from_port'] ?? ''}`;
        // a supervisor's record says when its engine took the event (taken_ns): it is written after the rule changes the event made
        const taken = (r as KnownRecord).fields?.['taken_ns'];
        (takes.get(key) ?? takes.set(key, []).get(key)!).push(typeof taken === 'number' ? BigInt(taken) : mono(r));
    }
    // every event each supervisor received from a module, over the whole run, in its log's order
    const received = new Map<string, Receipt[]>(); // `${supervisor} ${source}` -> receipts
    const receivers = new Map<string, string[]>(); // source -> its supervisors
    for (const r of known) {
        if (r.kind !== 'request_received' || !plan.supervisors.has(r.module) || plan.supervisors.has(r.peer)) continue;
        const port = EVENT_RECEIVED.exec(r.detail)?.[1];
        if (port === undefined) continue;
        const source = `${r.peer}:${port}`;
        const key = `${r.module} ${source}`;
        if (!received.has(key)) {
            received.set(key, []);
            receivers.set(source, [...(receivers.get(source) ?? []), r.module]);
        }
        const list = received.get(key)!;
        list.push({ t: takes.get(key)?.[list.length] ?? mono(r), source });
    }
    // one emission per event sent: the k-th receipt of a source at each of its supervisors
    const emissions: Emission[] = [];
    for (const [source, sups] of receivers) {
        // (a supervisor that stopped first got fewer: the receipts past the shortest list are its own)
        const lists = sups.map((sup) => received.get(`${sup} ${source}`)!);
        const longest = Math.max(...lists.map((l) => l.length));
        for (let k = 0; k < longest; k++) {
            const got = lists.filter((l) => k < l.length).map((l) => l[k]!);
            const emission: Emission = { t: got.reduce((min, x) => (x.t < min ? x.t : min), got[0]!.t), source };
            for (const x of got) x.emission = emission;
            emissions.push(emission);
        }
    }
    // a supervisor's request to another (START/STOP of a function) takes time in a real run and none
    // in the simulator, which delivers it at the decision that sent it: an event the receiver got
    // while such a request was on its way (after the event that started the sender's decision,
    // before the request) is replayed just before that event, so that the receiver meets both in
    // the order it really did
    const timeline = timelineOf(known, plan, received, receivers, launcherStop, t0);
    inFlight(timeline);
    // a function that really ran less than its `elapsed` delay must do so in the simulator too
    shortRuns(timeline);
    // a request still on its way when the launcher stopped the run: the comparison ends before it
    const end = endBeforeUnreceived(timeline, plan, launcherStop);
    const real = decisionsOnInputsBefore(known, plan.supervisors, end);
    for (const r of real) if (mono(r) >= end) timeline.adjustments.push(`end: kept ${r.module} ${r.function}.${r.rule} ${r.active ? 'active' : 'inactive'} <- ${r.cause} logged at ${timeline.at(mono(r))}, after the end, on an input before it`);

    // ORD's events name their schema in ORD's own records, in the order it sent them
    const ordValues = new Map<string, string[]>([
        ['ORD:0', known.filter((r): r is KnownRecord => r.module === 'ORD' && r.kind === 'ord_deadline_miss').map((r) => JSON.stringify(String(r.fields.schema)))],
        ['ORD:1', known.flatMap((r) => (r.module === 'ORD' && r.kind === 'scheduler' ? /^conflict: (\S+) shares .*\(ORD:1\)$/.exec(r.detail)?.slice(1, 2).map((s) => JSON.stringify(s)) ?? [] : []))],
    ]);
    for (const [source, values] of ordValues) {
        const sent = emissions.filter((e) => e.source === source);
        if (sent.length > values.length) throw new Error(`${source} was received ${sent.length} times but ORD logged ${values.length} such events`);
        sent.forEach((e, k) => (e.value = values[k]));
    }
    // each rule change caused by an event names its value: the deciding supervisor's latest receipt
    // of that source before the decision
    for (const r of real) {
        const c = r.causeEvent;
        if (c.kind !== 'event' || LOGGED_DATATYPE.test(c.value)) continue;
        const list = received.get(`${r.module} ${c.module}:${c.port}`) ?? [];
        let receipt: Receipt | undefined;
        for (const x of list) {
            if (x.t > mono(r)) break;
            receipt = x;
        }
        if (receipt?.emission && receipt.emission.value === undefined) receipt.emission.value = plan.causeValue?.(c.module, c.port, c.value) ?? scenarioValueOf(c.value);
    }

    // the runs their own code ended (not a supervisor's: its functions are what the scenario starts)
    const ownEnds = known.filter((r) => r.kind === 'run_finished' && !r.peer && !plan.supervisors.has(r.module) && ownRunEndText(r.detail) !== undefined && mono(r) >= t0 && mono(r) < end);
    const finished = ownEnds.map((r) => r.module);
    const finishAt = (r: KnownRecord | RuleRecord): bigint => ownEndBeforeStop(known, plan, received, r, (why) => timeline.adjustments.push(why), (t) => timeline.at(t));
    const replayed = [...ownEnds.map((r): Emission => ({ t: finishAt(r), source: `finish ${r.module}` })), ...emissions.filter((e) => e.t >= t0 && e.t < end)]
        .sort((a, b) => (a.t < b.t ? -1 : a.t > b.t ? 1 : 0)); // stable: a run's end before an event of the same time
    const counts = new Map<string, number>();
    const lines = [`until ${formatTime(Number(end - t0))}`, `start ${plan.start}`];
    for (const e of replayed) {
        if (e.source.startsWith('finish ')) {
            lines.push(`t=${formatTime(Number(e.t - t0))} ${e.source}`);
            continue;
        }
        counts.set(e.source, (counts.get(e.source) ?? 0) + 1);
        const [module, port] = e.source.split(':');
        const value = e.value ?? plan.fallback?.(module!, Number(port)) ?? '';
        lines.push(`t=${formatTime(Number(e.t - t0))} ${e.source} ${value}`.trimEnd());
    }
    return { text: lines.join('\n') + '\n', real, counts, finished, adjustments: timeline.adjustments };
}

/**
 * When to replay run end `r` (a module's `run_finished` that its own code ended): at its time, or,
 * when the STOP a supervisor sent that module arrived after it (finding no run) but was decided on
 * an event the supervisor had received before it, just before that event: the simulator delivers
 * the STOP at the decision, and would stop the run before its own end (the tutorial's MAA ending
 * its run 37 µs after posting "disconnected", while SUP's STOP of it is on its way, or before SUP
 * has decided). The event itself still comes after: the simulator takes an event from a module
 * whose run has ended, as SUP's mailbox did.
 */
function ownEndBeforeStop(known: readonly (KnownRecord | RuleRecord)[], plan: ReplayPlan, received: ReadonlyMap<string, Receipt[]>, r: KnownRecord | RuleRecord,
    said: (why: string) => void, at: (t: bigint) => string): bigint {
    const tf = mono(r);
    const stop = known.find((x) => x.kind === 'request_received' && x.module === r.module && plan.supervisors.has(x.peer) && /^STOP\b/.test(x.detail) && mono(x) > tf);
    if (!stop) return tf;
    // the stopping supervisor's decision that sent it: its latest rule change before the STOP arrived, on an event
    let decision: RuleRecord | undefined;
    for (const x of known) if (isRule(x) && x.module === stop.peer && mono(x) < mono(stop)) decision = x;
    const cause = decision?.causeEvent;
    if (!decision || cause?.kind !== 'event') return tf;
    const source = `${cause.module}:${cause.port}`;
    let input: Receipt | undefined;
    for (const x of received.get(`${stop.peer} ${source}`) ?? []) if (x.t <= mono(decision)) input = x;
    if (!input?.emission || input.t > tf || input.emission.t >= tf) return tf;
    said(`finish ${r.module}: moved from ${at(tf)} to ${at(input.emission.t)}, before ${source}: ${stop.peer}'s STOP of it, decided on that event, reached it after its run ended (at ${at(mono(stop))})`);
    return input.emission.t;
}

/**
 * The tutorial's plan: its supervisors, GLB's mission started by the launcher, SUP's function
 * started by GLB's rule SINGLE (supervisor2.contract: `activate supervisor SUP.action(…)`), and
 * the value of MAA:2 events that changed no rule ("connected", the only other status the
 * tutorial's MAA script posts).
 */
export const TUTORIAL_PLAN: ReplayPlan = {
    supervisors: new Set(['SUP', 'GLB']),
    start: 'GLB.mission()',
    requestRules: { SUP: ['GLB mission.SINGLE'] },
    fallback: (module, port) => (module === 'MAA' && port === 2 ? '"connected"' : undefined),
};

/** The scenario of a real run (scenarioOfRun), checked against project `dir` and run in the simulator. */
export async function replayInSimulator(dir: string, records: TraceRecord[], plan: ReplayPlan): Promise<RunScenario & { sim: ScenarioResult; diagnostics: unknown[] }> {
    const scenario = scenarioOfRun(records, plan);
    const project = await prepared(dir);
    const s = loadScenario('run.scenario', 'run.scenario', scenario.text, project.index);
    return { ...scenario, diagnostics: s.diagnostics, sim: await runLoadedScenario(project, s) };
}

/**
 * A value as a rule's cause logs it, in scenario syntax: a datatype's fields without their names
 * (`{v=0.5,w=0}` -> `{0.5, 0}`), an array in braces (`[1,2]` -> `{1, 2}`); undefined when the log
 * does not give the whole value (`...` of an abridged array or string, `{N bytes}`) or gives an
 * enumeration member without its enumeration (`AUTO`): such an event is replayed with the plan's
 * fallback.
 */
export function scenarioValueOf(logged: string): string | undefined {
    if (LOGGED_DATATYPE.test(logged)) return undefined;
    let out = '';
    for (let i = 0; i < logged.length;) {
        const ch = logged[i]!;
        if (ch === '"') {
            let j = i + 1;
            while (j < logged.length && logged[j] !== '"') j += logged[j] === '\\' ? 2 : 1;
            if (j >= logged.length) return undefined; // cut inside the string
            out += logged.slice(i, j + 1);
            i = j + 1;
        } else if (logged.startsWith('...', i)) {
            return undefined;
        } else if (ch === '[' || ch === '{') {
            out += '{';
            i++;
        } else if (ch === ']' || ch === '}') {
            out += '}';
            i++;
        } else if (ch === ',') {
            out += ', ';
            i++;
        } else {
            const word = /^[A-Za-z_]\w*/.exec(logged.slice(i));
            if (word && logged[i + word[0].length] === '=') {
                i += word[0].length + 1; // a field's name
            } else if (word && word[0] !== 'true' && word[0] !== 'false') {
                return undefined; // an enumeration member, logged without its enumeration
            } else {
                const token = word?.[0] ?? /^[^,\]}]+/.exec(logged.slice(i))![0];
                out += token;
                i += token.length;
            }
        }
    }
    return out;
}

/** How long before a decision the event that caused it may have been received (same file: microseconds). */
const CAUSE_WINDOW = 5_000_000n;

/** How far under its first `elapsed` delay a function that met no timer is stopped (shortRuns). */
const TIMER_MARGIN = 1_000n;

/** What inFlight and shortRuns look at: the supervisors' decisions, receipts and requests to each other. */
interface Timeline {
    receivers: Map<string, string[]>;
    /** Each supervisor's decision times, in order. */
    decisions: Map<string, bigint[]>;
    /** Each supervisor's decisions not made by a function's stop (`cause=stop`), in order. */
    eventDecisions: Map<string, bigint[]>;
    /** Each supervisor's receipts of every source, in time order. */
    receipts(sup: string): Receipt[];
    /** START/STOP/KILL requests a supervisor received from another, in order. */
    requests: (KnownRecord | RuleRecord)[];
    /** `SUP function` -> the shortest `elapsed` delay that changed one of its rules in the run (ns). */
    firstTimers: Map<string, bigint>;
    /** A request -> the time of the sender's decision that sent it (ReplayPlan.requestRules). */
    sentAt: Map<KnownRecord | RuleRecord, bigint>;
    /** Receiver -> sender -> the times of the sender's decisions that sent it a request (ReplayPlan.requestRules). */
    requestChanges: Map<string, Map<string, bigint[]>>;
    /** A time as the scenario writes it (`t=1551400us`). */
    at(t: bigint): string;
    /** What inFlight and shortRuns did, in words (RunScenario.adjustments). */
    adjustments: string[];
}

function timelineOf(known: (KnownRecord | RuleRecord)[], plan: ReplayPlan, received: Map<string, Receipt[]>, receivers: Map<string, string[]>, end: bigint, t0: bigint): Timeline {
    const supervisors = plan.supervisors;
    const decisions = new Map<string, bigint[]>();
    const eventDecisions = new Map<string, bigint[]>();
    for (const r of known) {
        if (!isRule(r) || !supervisors.has(r.module)) continue;
        (decisions.get(r.module) ?? decisions.set(r.module, []).get(r.module)!).push(mono(r));
        if (r.causeEvent.kind !== 'stop') (eventDecisions.get(r.module) ?? eventDecisions.set(r.module, []).get(r.module)!).push(mono(r));
    }
    const bySupervisor = new Map<string, Receipt[]>();
    for (const [key, list] of received) {
        const sup = key.slice(0, key.indexOf(' '));
        bySupervisor.set(sup, [...(bySupervisor.get(sup) ?? []), ...list]);
    }
    for (const list of bySupervisor.values()) list.sort((a, b) => (a.t < b.t ? -1 : a.t > b.t ? 1 : 0));
    const requests = known.filter((q) => q.kind === 'request_received' && supervisors.has(q.module) && supervisors.has(q.peer) && /^(START|STOP|KILL)\b/.test(q.detail));
    const firstTimers = new Map<string, bigint>();
    for (const r of known) {
        if (!isRule(r) || r.causeEvent.kind !== 'elapsed') continue;
        const key = `${r.module} ${r.function}`;
        const ns = BigInt(r.causeEvent.ns);
        const shortest = firstTimers.get(key);
        if (shortest === undefined || ns < shortest) firstTimers.set(key, ns);
    }
    // the k-th request a receiver got from a sender was sent by the k-th change of the sender's rules
    // that activate it (a mailbox is first in, first out)
    const sentAt = new Map<KnownRecord | RuleRecord, bigint>();
    const requestChanges = new Map<string, Map<string, bigint[]>>();
    for (const [receiver, rules] of Object.entries(plan.requestRules ?? {})) {
        const changes = new Map<string, bigint[]>(); // sender -> its request-sending decisions, in order
        for (const r of known) {
            // (a rule ended by its own function's stop sends nothing: the launcher stops every supervisor)
            if (!isRule(r) || r.causeEvent.kind === 'stop' || !rules.includes(`${r.module} ${r.function}.${r.rule}`)) continue;
            (changes.get(r.module) ?? changes.set(r.module, []).get(r.module)!).push(mono(r));
        }
        requestChanges.set(receiver, changes);
        for (const [sender, sent] of changes) {
            const got = requests.filter((q) => q.peer === sender && q.module === receiver);
            // a stale table would match requests with the wrong decisions: more requests than changes says so
            const beforeEnd = got.filter((q) => mono(q) < end).length;
            if (beforeEnd > sent.length) throw new Error(`${receiver} received ${beforeEnd} requests from ${sender}, but the plan's requestRules name only ${sent.length} changes of ${sender} that send them`);
            got.forEach((q, k) => {
                if (k < sent.length) sentAt.set(q, sent[k]!);
            });
        }
    }
    return { receivers, decisions, eventDecisions, receipts: (sup) => bySupervisor.get(sup) ?? [], requests, firstTimers, sentAt, requestChanges, at: (t) => `t=${formatTime(Number(t - t0))}`, adjustments: [] };
}

/**
 * Where the comparison ends: at the launcher's stop, or earlier when a supervisor's decision before
 * it sent another a request (ReplayPlan.requestRules) that had not reached it then. The simulator
 * delivers that request at the decision, and the receiver would decide on it (`cause=stop`, or a
 * START's first timer) where the real one never did before it was stopped: the comparison then
 * ends where that decision began (the replay time of the event that caused it), so that neither
 * side has it. Without requestRules, the launcher's stop.
 */
function endBeforeUnreceived(tl: Timeline, plan: ReplayPlan, launcherStop: bigint): bigint {
    let end = launcherStop;
    for (const receiver of Object.keys(plan.requestRules ?? {})) {
        for (const [sender, sent] of tl.requestChanges.get(receiver) ?? []) {
            const got = tl.requests.filter((q) => q.peer === sender && q.module === receiver && mono(q) < launcherStop).length;
            const unreceived = sent.filter((t) => t < launcherStop)[got];
            if (unreceived === undefined) continue;
            const start = startOfDecision(tl, sender, unreceived);
            if (start >= end) continue;
            tl.adjustments.push(`end: ${sender}'s decision at ${tl.at(unreceived)} sent ${receiver} a request it had not received when the launcher stopped the run (${tl.at(launcherStop)}): the comparison ends at ${tl.at(start)}`);
            end = start;
        }
    }
    return end;
}

/**
 * The supervisors' decisions the comparison keeps: those logged before `end`, and those logged
 * after it on an input that came before it, which the simulator (run until `end`) makes too: a
 * request or an event the supervisor took before `end` and had not decided on yet (a STOP's
 * `cause=stop` is logged some 20 to 60 us after the request), or a timer due before `end` (an
 * `elapsed` delay from the function's start, a `duration` from its rule's activation). The
 * launcher's stop is an input at or after `end`: what it made is not kept.
 */
function decisionsOnInputsBefore(known: (KnownRecord | RuleRecord)[], supervisors: ReadonlySet<string>, end: bigint): RuleRecord[] {
    const input = new Map<string, bigint>(); // supervisor -> its latest request or event taken
    const started = new Map<string, bigint>(); // supervisor -> its latest function start
    const activeSince = new Map<string, bigint>(); // `SUP function.RULE` -> when it became active
    const kept: RuleRecord[] = [];
    for (const r of known) {
        if (!supervisors.has(r.module)) continue;
        const t = mono(r);
        const taken = r.kind === 'event_received' ? (r as KnownRecord).fields?.['taken_ns'] : undefined;
        if (r.kind === 'request_received' || r.kind === 'event_received') input.set(r.module, typeof taken === 'number' ? BigInt(taken) : t);
        else if (r.kind === 'supervisor' && (r as KnownRecord).fields?.['what'] === 'function_started') started.set(r.module, t);
        if (!isRule(r)) continue;
        if (r.active) activeSince.set(`${r.module} ${r.function}.${r.rule}`, t);
        const c = r.causeEvent;
        const due = c.kind === 'elapsed' ? (started.get(r.module) ?? end) + BigInt(c.ns)
            : c.kind === 'duration' ? (activeSince.get(`${r.module} ${r.function}.${c.rule}`) ?? end) + BigInt(c.ns)
            : input.get(r.module) ?? end;
        if (t < end || due < end) kept.push(r);
    }
    return kept;
}

/**
 * When a decision `sender` made at `tp` began: the replay time of the event that caused it
 * (received at most CAUSE_WINDOW before it), else the decision's own time.
 */
function startOfDecision(tl: Timeline, sender: string, tp: bigint): bigint {
    return triggerOf(tl, sender, tp)?.emission?.t ?? tp;
}

/** The event that caused the decision `sender` made at `tp`: its latest receipt at most CAUSE_WINDOW before. */
function triggerOf(tl: Timeline, sender: string, tp: bigint): Receipt | undefined {
    return tl.receipts(sender).filter((x) => x.t <= tp && tp - x.t <= CAUSE_WINDOW && x.emission).pop();
}

/**
 * The time of the sender's decision that sent request `q`: the k-th of its request-sending
 * decisions for the k-th request the receiver got from it (ReplayPlan.requestRules), else its
 * latest decision before the receipt; undefined when there is none.
 */
function sendingDecision(tl: Timeline, q: KnownRecord | RuleRecord): bigint | undefined {
    const tq = mono(q);
    const sent = tl.sentAt.get(q);
    if (sent !== undefined && sent <= tq) return sent;
    return (tl.decisions.get(q.peer) ?? []).filter((t) => t <= tq).pop();
}

/**
 * When the decision that sent request `q` to another supervisor began: the replay time of the
 * event that caused it (received at most CAUSE_WINDOW before it), else the decision's own time;
 * undefined when the sender made no decision before.
 */
function decisionStart(tl: Timeline, q: KnownRecord | RuleRecord): { start: bigint; trigger?: Receipt } | undefined {
    const sender = q.peer;
    const tp = sendingDecision(tl, q);
    if (tp === undefined) return undefined;
    const trigger = triggerOf(tl, sender, tp);
    return { start: trigger?.emission?.t ?? tp, trigger };
}

/**
 * Moves the events a supervisor received while another's request was on its way (see scenarioOfRun):
 * those it met before the first request of the sender's decision, not those after an earlier one.
 */
function inFlight(tl: Timeline): void {
    for (const q of tl.requests) {
        const tq = mono(q);
        // the sender's decision that sent it, and the event that started that decision (if one did)
        const at = decisionStart(tl, q);
        if (!at) continue;
        // an earlier request the sender made on the same event (STOP autonomous as AUTO ended,
        // then START safestop as STOP began): the receiver met the events after it after that
        // request, as in the simulator, which delivers both at that event: only those before the
        // first such request move
        const first = tl.requests.filter((p) => p.module === q.module && p.peer === q.peer && mono(p) <= tq && decisionStart(tl, p)?.start === at.start).map(mono);
        const to = first.reduce((min, t) => (t < min ? t : min), tq);
        // the receiver's own events (not shared with another supervisor) that came in between: one
        // the sender received too (ORD's go to every supervisor) cannot move before the sender's
        // trigger without the sender meeting it in another order (see othersKeepOrder)
        const between = tl.receipts(q.module).filter((x) => x.emission && x.t > at.start && x.t < to && tl.receivers.get(x.source)?.length === 1);
        if (between.length) tl.adjustments.push(`inFlight: ${between.map((x) => `${x.source} ${tl.at(x.emission!.t)}`).join(', ')} moved before ${tl.at(at.start)}, ${q.module} having met them before ${q.peer}'s ${q.detail}`);
        between.forEach((x, i) => (x.emission!.t = at.start - BigInt(between.length - i)));
    }
}

/**
 * A function a supervisor started and stopped at another's request before any of its rules changed
 * (a real run: MIS starts DRV.autonomous on OBS:0, a deadline miss 1.9 ms after that OBS:0 makes it
 * stop it 0.8 ms after DRV got the START, before the function's `elapsed=1ms` came). The simulator
 * starts the function at the event that made the caller decide, with no delay, so replayed at its
 * own time the stopping event would come after the `elapsed` timer, and the simulated function
 * would make a decision the real one never made. The event that made the caller stop the function
 * is replayed instead as long after the start's event as the function really ran (and the caller's
 * own events between the two times just before it, in their order), so the simulated function
 * runs as long as the real one did. An event to move that other supervisors received too (ORD's
 * go to every supervisor, the function's own included) moves only when each of them meets it in
 * the same order as it really did (othersKeepOrder).
 *
 * A function that made no decision ran, as far as its timers go, less than its first `elapsed`
 * delay, even when it got the STOP later than that (a real run on a loaded host: DRV got START
 * safestop, was not scheduled for 1.5 ms, and then took the STOP already waiting in its mailbox
 * before the timer that had come due meanwhile, since an engine takes a waiting request first).
 * The replayed run is then cut to 1 us under that delay (the shortest `elapsed` that changed a rule
 * of that function anywhere in the run; a function none changed keeps its real length).
 */
function shortRuns(tl: Timeline): void {
    for (const [k, q1] of tl.requests.entries()) {
        if (!q1.detail.startsWith('START')) continue;
        const q2 = tl.requests.slice(k + 1).find((q) => q.module === q1.module);
        if (!q2 || q2.peer !== q1.peer || !/^(STOP|KILL)\b/.test(q2.detail)) continue;
        const [tq1, tq2] = [mono(q1), mono(q2)];
        if ((tl.decisions.get(q1.module) ?? []).some((t) => t > tq1 && t < tq2)) continue;
        const started = decisionStart(tl, q1);
        const stopped = decisionStart(tl, q2);
        const e = stopped?.trigger?.emission;
        if (!started || !e) continue;
        const timer = tl.firstTimers.get(`${q1.module} ${/^START (\S+)/.exec(q1.detail)?.[1]}`);
        const ran = timer !== undefined && tq2 - tq1 >= timer ? timer - TIMER_MARGIN : tq2 - tq1;
        const latest = started.start + ran;
        if (e.t <= latest) continue;
        const between = tl.receipts(q1.peer).filter((x) => x.emission && x.emission !== e && x.emission.t >= latest && x.emission.t < e.t);
        if (latest - BigInt(between.length) <= started.start) continue;
        const moves = [...between.map((x, i) => ({ emission: x.emission!, to: latest - BigInt(between.length - i) })), { emission: e, to: latest }];
        const what = `${q1.module}'s ${q1.detail.slice('START '.length)} (${tl.at(started.start)}) ran ${formatTime(Number(ran))} without a decision`;
        const refused = moves.find((m) => !othersKeepOrder(tl, m.emission, m.to, q1.peer));
        if (refused) {
            tl.adjustments.push(`shortRuns: ${what}; nothing moved: another receiver of ${refused.emission.source} ${tl.at(refused.emission.t)} met something else before it`);
            continue;
        }
        tl.adjustments.push(`shortRuns: ${what}: ${moves.map((m) => `${m.emission.source} ${tl.at(m.emission.t)} -> ${tl.at(m.to)}`).join(', ')}`);
        for (const m of moves) m.emission.t = m.to;
    }
}

/**
 * Whether an event received by several supervisors (ORD's, sent to every one) can be replayed at
 * `to`, earlier than its time, for `mover`'s sake: every other receiver then meets it in the same
 * order among its own module events and decisions as it really did, since none of them falls
 * between the two times. A decision a function's stop made (`cause=stop`) does not count: the
 * simulator delivers the request at the decision that sent it, not at the receiver's time.
 */
function othersKeepOrder(tl: Timeline, emission: Emission, to: bigint, mover: string): boolean {
    const within = (t: bigint): boolean => t >= to && t < emission.t;
    return (tl.receivers.get(emission.source) ?? []).filter((sup) => sup !== mover).every((sup) =>
        !tl.receipts(sup).some((x) => x.emission !== emission && within(x.emission?.t ?? x.t))
        && !(tl.eventDecisions.get(sup) ?? []).some(within));
}

/** One decision, as both sides write it: `SUP action.SECOND active <- MAA:2 value="disconnected"`. */
export const decision = (sup: string, fn: string, rule: string, active: boolean, cause: string): string => `${sup} ${fn}.${rule} ${active ? 'active' : 'inactive'} <- ${cause}`;

export const realDecisions = (real: RuleRecord[], sup: string): string[] =>
    real.filter((r) => r.module === sup).map((r) => decision(sup, r.function, r.rule, r.active, r.cause));

export const simulatedDecisions = (changes: RuleChange[], sup: string): string[] =>
    changes.filter((c) => c.supervisor === sup).map((c) => decision(sup, c.function, c.rule, c.active, c.cause));

/**
 * The assertion message of a decision comparison: where the two sides first part, with the
 * decisions around it, what the replay moved, and the whole scenario, also saved to a file (it is
 * long: 180-beam scans). CI prints only the first 6 lines of a failure, cut at 300 characters:
 * the first 4 say what differs, one line each.
 */
export function firstDifference(sup: string, simulated: string[], real: string[], scenario: string, adjustments: readonly string[] = []): string {
    let i = 0;
    while (i < simulated.length && i < real.length && simulated[i] === real[i]) i++;
    if (i === simulated.length && i === real.length) return `${sup}: the same ${i} decisions`;
    const from = Math.max(0, i - 2);
    const around = (list: string[]): string => [...list.slice(from, i + 3).map((d, k) => `${from + k === i ? '> ' : ''}${d}`), ...(list.length <= i + 2 ? ['(end)'] : [])].join(' | ');
    const file = join(mkdtempSync(join(tmpdir(), 'contract-sim-diff-scenario-')), 'run.scenario');
    writeFileSync(file, scenario);
    const short = scenario.split('\n').map((l) => (l.length > 160 ? `${l.slice(0, 160)}...` : l)).join('\n');
    return [
        `${sup}: decision ${i} differs (simulated ${simulated.length}, real ${real.length})`,
        `simulated: ${around(simulated)}`,
        `real: ${around(real)}`,
        `replay adjustments: ${adjustments.length ? adjustments.join('; ') : 'none'}`,
        `scenario replayed (${file}):\n${short}`,
    ].join('\n');
}
