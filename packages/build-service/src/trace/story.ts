/**
 * A readable story of a recorded run from its trace records (`contract trace`): supervisor
 * decisions with their causes, functions started/stopped/refused, schema activations, the
 * supervisors' actions in the simulator's words (`simulate --verbose` tells the same lines),
 * conflicts, deadline misses with their cycle, overruns, module starts and exits. Releases,
 * completions and deliveries are counted, not told one by one. Pure: returns the lines.
 */
import { posingText } from './log-clock.js';
import { formatNanoseconds, STUCK_ADVICE, withCrashMeaning } from '@contract-studio/conventions';
import { ownString, parseCause } from './parse.js';
import { hasWordIn, isDigitsIn, wordValueIn } from './field-checks.js';
import { confirmingHold, type ConfirmingHold } from './action-holds.js';
import { missedTicksOf, skippedReleasesOf } from './ord-counts.js';
import { durationText } from './duration-text.js';
import { ReleaseLateness } from './release-lateness.js';
import { ModuleCpu, type ModuleCpuFigure } from './module-cpu.js';
import { EngineCpu, type EngineCpuFigure } from './engine-cpu.js';
import { UndosToOrd } from './undos-to-ord.js';
import { DataFlowUse } from './data-flow-use.js';
import { EventWaits } from './event-waits.js';
import { EventHandling, type EventHandlingFigures } from './event-handling.js';
import { LostEvents, lostFlowText } from './lost-events.js';
import { UnmatchedEvents } from './unmatched-events.js';
import { UnrecordedDeliveries } from './unrecorded-deliveries.js';
import { ProducerChanges } from './producer-changes.js';
import { EndedMidRun, RUN_STOPPING, type LauncherToldEnd } from './ended-mid-run.js';
import type { LauncherFileLine } from './launcher-lines-file.js';
import { stuckSaysGone } from './receiver-gone.js';

export { stuckSaysGone };
import { countRecord, isRule, type KnownRecord, type RecordCounts, type RuleCause, type TraceRecord, type TraceRecordBase } from './records.js';

/** How the runtime ends the detail of an `error` record written while contract-launch stops the run. */
export { RUN_STOPPING };

/**
 * A rule's cause as a reader writes it: the `sup_rule` cause `elapsed=1000000ns` as `elapsed=1ms`,
 * `MAA:2 value="disconnected"` as `MAA:2 = "disconnected"`, `stop` as `its function stopped`. The
 * same words in `contract trace`, `contract simulate` and the IDE's Monitor and Simulate panels.
 */
export function readableCause(logged: string): string {
    return describeCause(parseCause(logged));
}

function describeCause(c: RuleCause): string {
    switch (c.kind) {
        case 'event': return `${c.module}:${c.port} = ${c.value}`;
        case 'started': return `started(${c.rule})`;
        case 'endof': return `endof(${c.rule})`;
        case 'duration': return `duration(${c.rule})=${formatNanoseconds(c.ns)}`;
        case 'elapsed': return `elapsed=${formatNanoseconds(c.ns)}`;
        case 'stop': return 'its function stopped';
        case 'other': return c.text;
    }
}


/* the readable lines told (by their `what`, text-lines.ts); deadline misses come from their typed record */
const SUPERVISOR_TOLD = new Set(['function_started', 'function_stopped', 'function_refused', 'refused', 'error', 'warning', 'activation_refused']);
/* (not told: ORD's `late_ack` and `ignored: M finished outside a cycle`, expected when a schema is
   deactivated while its modules run; its `ignored: deactivate S (not this activation)` is: ignoredUndo) */
const SCHEDULER_TOLD = new Set(['activate', 'deactivate', 'conflict', 'refused', 'late_release', 'overrun', 'overrun_ended', 'missed_tick', 'missed_ticks_ended', 'gave_up', 'held', 'resumed', 'stuck', 'unstuck', 'warning',
    'parameterize', 'connect', 'disconnect']);

/**
 * Whether a record is ORD's `ignored: deactivate S (not this activation)`: the answer to a
 * supervisor's undo of an activation ORD does not serve (it refused it: ORD:1; or the schema's
 * active activation is another's), which deactivates nothing (docs/semantics.md "Scheduler:
 * conflict"). Told by `contract trace` after that undo, and marked by the IDE's Monitor with the
 * schema's (de)activations; not ORD's other `ignored` line (a module that finished outside a
 * cycle).
 */
export function ignoredUndo(k: Pick<KnownRecord, 'kind' | 'fields'>): boolean {
    return k.kind === 'scheduler' && k.fields['what'] === 'ignored' && typeof k.fields['schema'] === 'string';
}

/**
 * What an `event_posted` record with `no subscriber` of event port `port` (`DET:0`) says: an event
 * no one received (its subscriber had unsubscribed, none ever did), why a rule waiting for it did not fire.
 */
export function unheardEventText(port: string): string {
  return `event ${port} posted with no subscriber: no one received it (no supervisor or module subscribed to ${port} then)`;
}

/**
 * `crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array` for a
 * `module_crashed` record's detail, with what its signal means (conventions' crash-signals.ts; its
 * record count left to the log's checks): `contract trace`'s line and the IDE Monitor's crash line;
 * without it (`meaning` false) where the crash is recalled later (`it had exited before (crashed: signal 11 (SIGSEGV))`).
 */
export function crashText(detail: string, meaning = true): string {
    const told = `crashed: ${detail.split(' ').filter((w) => !/^records=\d+$/.test(w)).join(' ')}`;
    return meaning ? withCrashMeaning(told) : told;
}

/**
 * A cycle whose first release ORD sent this long after its tick or more is said released late, when
 * the deadline miss does not say its CRITICAL_DELAY (logs written before it did).
 */
export const LATE_RELEASE_NS = 1_000_000;

/**
 * The share of CRITICAL_DELAY that tells a cycle ORD released late: from this share of it after its
 * tick on, the story notes when ORD released the cycle; with less than this share of it left (or
 * none), its modules had no time to finish: ORD was late, not they.
 */
export const LATE_RELEASE_SHARE = 0.1;

/** A module ORD counted unfinished at a deadline miss, though its own records say it finished in time. */
export interface EarlyAck {
    module: string;
    /** When it finished, ns after the cycle's tick (its ack_sent, else its run_finished). */
    sinceTickNs: number;
    how: 'its ack sent' | 'its run finished';
}

/** The modules of a miss that finished in time (`text`), and those really not finished (`rest`, written out). */
export interface EarlyFinish {
    text: string;
    rest: string;
}

/** `+2.250 ms`: a time after a cycle's tick, as the miss text gives it. */
export function sinceTickText(ns: number): string {
    return `+${(ns / 1e6).toFixed(3)} ms`;
}

/**
 * The modules a deadline miss names as not finished, split by their own records: those that sent
 * their ack (or ended their run) by the deadline (`deadlineNs` after the tick) are ORD's lateness,
 * not theirs: `HOG finished at +2.250 ms (its ack sent), ORD had not read it at the deadline, 7.750
 * ms later`. `missSinceTickNs`: when ORD told the miss. Undefined when none finished in time.
 */
export function earlyFinish(notFinished: readonly string[], acks: ReadonlyMap<string, EarlyAck>, deadlineNs: number): EarlyFinish | undefined {
    const early = notFinished.map((m) => acks.get(m)).filter((a): a is EarlyAck => a !== undefined && a.sinceTickNs <= deadlineNs);
    if (!early.length) return undefined;
    const text = early.map((a) => `${a.module} finished at ${sinceTickText(a.sinceTickNs)} (${a.how}), ORD had not read it at the deadline, ${durationText(deadlineNs - a.sinceTickNs)} later`).join(', ');
    return { text, rest: notFinished.filter((m) => !early.some((a) => a.module === m)).join(', ') };
}

/**
 * What a missed cycle was waiting for, as `contract trace` and the IDE's Monitor say it after
 * `deadline miss (ORD:0): S cycle k`: ` (held: nothing released, GRP still runs an earlier
 * release)` when its cycle was held for `heldFor` (` (held: nothing released, GRP never finished an
 * earlier release: it is no longer running)` when `heldForGone`: a stuck record or its exit said it
 * had crashed, been killed or ended), ` (not finished: ARM, GRP)` for the modules released and not
 * finished (`notFinished`, written out), and when ORD sent the cycle's first release late
 * (`firstReleaseLateNs`: release_ns - tick_ns; ORD woke late on a loaded machine, or the cycle was
 * held and resumed), measured against the schema's CRITICAL_DELAY (`criticalDelayNs`, the miss
 * record's `critical_delay_ns`; LATE_RELEASE_SHARE):
 * - with less than a tenth of CRITICAL_DELAY left, or none, the modules are not blamed: ` (ORD
 *   late: it released the cycle 826 µs after its tick, past CRITICAL_DELAY 800 µs, leaving ENC no
 *   time)` (`..., 30 µs before CRITICAL_DELAY 800 µs, leaving ENC 30 µs)`);
 * - from a tenth of it on: ` (not finished: ENC; ORD released the cycle 200 µs after its tick, of
 *   CRITICAL_DELAY 800 µs)`;
 * - a miss record without CRITICAL_DELAY (an older log): `; ORD released the cycle 13.4 ms after its
 *   tick` from LATE_RELEASE_NS on;
 * - modules ORD counted unfinished whose own records say they finished before the deadline
 *   (`early`: their `ack_sent` to ORD, or `run_finished`, for that release) are not blamed: ` (HOG
 *   finished at +2.250 ms (its ack sent), ORD had not read it at the deadline, 7.75 ms later: ORD
 *   was late)`, beside those really not finished: ` (not finished: ARM; HOG finished ...: ORD was
 *   late reading it)`.
 */
export function missWaitText(heldFor: string | undefined, notFinished: string, firstReleaseLateNs?: number, heldForGone = false, criticalDelayNs?: number, early?: EarlyFinish): string {
    if (heldFor !== undefined && heldForGone) return ` (held: nothing released, ${heldFor} never finished an earlier release: it is no longer running)`;
    if (heldFor !== undefined) return ` (held: nothing released, ${heldFor} still runs an earlier release)`;
    const lateNs = firstReleaseLateNs;
    const withEarly = (late: string): string => {
        const parts = early!.rest ? [`not finished: ${early!.rest}`, `${early!.text}: ORD was late reading it`] : [`${early!.text}: ORD was late`];
        return ` (${[...parts, ...(late ? [late] : [])].join('; ')})`;
    };
    if (lateNs !== undefined && criticalDelayNs !== undefined && criticalDelayNs > 0) {
        const leftNs = criticalDelayNs - lateNs;
        const released = `released the cycle ${durationText(lateNs)} after its tick`;
        if (leftNs < criticalDelayNs * LATE_RELEASE_SHARE) {
            const when = leftNs <= 0 ? 'past' : `${durationText(leftNs)} before`;
            const leaving = notFinished ? `, leaving ${notFinished} ${leftNs <= 0 ? 'no time' : durationText(leftNs)}` : '';
            return ` (ORD late: it ${released}, ${when} CRITICAL_DELAY ${durationText(criticalDelayNs)}${leaving})`;
        }
        const late = lateNs >= criticalDelayNs * LATE_RELEASE_SHARE ? `ORD ${released}, of CRITICAL_DELAY ${durationText(criticalDelayNs)}` : '';
        if (early) return withEarly(late);
        if (notFinished) return ` (not finished: ${notFinished}${late ? `; ${late}` : ''})`;
        return late ? ` (${late})` : '';
    }
    const late = lateNs !== undefined && lateNs >= LATE_RELEASE_NS
        ? `ORD released the cycle ${(lateNs / 1e6).toFixed(1)} ms after its tick` : '';
    if (early) return withEarly(late);
    if (notFinished) return ` (not finished: ${notFinished}${late ? `; ${late}` : ''})`;
    return late ? ` (${late})` : '';
}

/** A miss record's `critical_delay_ns` (the deadline it missed), when it says one. */
export function missCriticalDelayNs(fields: KnownRecord['fields']): number | undefined {
    const cd = fields['critical_delay_ns'];
    return typeof cd === 'number' && Number.isFinite(cd) && cd > 0 ? cd : undefined;
}

/**
 * A `priority` record (`SCHED_FIFO 90`, `nice 1 (priority 90)`) as the story tells ORD's, so that a
 * run's story says whether it ran real-time: `priority SCHED_FIFO 90 (real-time)`, `priority nice 1
 * (priority 90): not real-time, a nice level`.
 */
export function priorityText(detail: string): string {
    if (detail.startsWith('SCHED_FIFO')) return `priority ${detail} (real-time)`;
    if (detail.startsWith('nice')) return `priority ${detail}: not real-time, a nice level`;
    return `priority ${detail}`;
}

/** `flow-SCN-0-DIV-0` (a flow_hold record's peer) as `SCN:0 -> DIV:0`; another name as it is. */
function flowName(peer: string): string {
    const m = /^flow-([A-Za-z_]\w*)-(\d+)-([A-Za-z_]\w*)-(\d+)$/.exec(peer);
    return m ? `${m[1]}:${m[2]} -> ${m[3]}:${m[4]}` : peer;
}

/** A hold record as the story tells it: `module M: hold taken (it was running)`, `event flow A:0 -> B:0: hold taken`. */
export function holdText(kind: 'module_hold' | 'flow_hold', peer: string, detail: string): string {
    return kind === 'module_hold' ? `module ${peer}: ${detail}` : `event flow ${flowName(peer)}: ${detail}`;
}

/**
 * Why a data value was not sent, from its `data_dropped` detail (`to_port=0 queue full` ->
 * `queue full`; `not sent` when it says nothing): the words of `contract trace` and the Monitor.
 */
export function dataDropReason(detail: string): string {
    return detail.replace(/^to_port=\S*\s*/, '') || 'not sent';
}

/**
 * The first dropped value of the data flow `flow` (`CAM:0 -> SRT:0`) to `consumer`'s input
 * `toPort`, from the `data_dropped` detail (`to_port=0 queue full`): `data CAM:0 -> SRT:0 dropped:
 * queue full (SRT does not read its input :0 as fast as it comes: ...)`.
 */
function dropText(flow: string, consumer: string, toPort: string, detail: string): string {
    const reason = dataDropReason(detail);
    const why = reason === 'queue full'
        ? ` (${consumer} does not read its input :${toPort} as fast as it comes: its exec region calls GetData or GetLatestData too seldom, or not at all)`
        : '';
    return `data ${flow} dropped: ${reason}${why}; its later drops are counted at the end`;
}

/** `1 release`, `2 releases`. */
function plural(n: number, one: string, many = `${one}s`): string {
    return `${n} ${n === 1 ? one : many}`;
}

/**
 * A module's own record (`user`: ContractLog under an event name of its own) as the story and the
 * IDE's Monitor (its timeline mark) tell it: `EVENT: DETAIL`, then those of the peer, port and size
 * it was logged with that it gave (a peer not empty; a port, its column not empty as a port < 0
 * leaves it; a size above 0): `gripper_closed: force=12.5 N (peer MAB, port 2, 16 bytes)`.
 * `detailChars`: the detail cut to so many characters (the Monitor's short mark label).
 */
export function userRecordText(k: KnownRecord, detailChars = Infinity): string {
    const detail = k.detail.slice(0, detailChars);
    const given = [k.peer ? `peer ${k.peer}` : '', k.port !== null ? `port ${k.port}` : '', k.size > 0 ? plural(k.size, 'byte') : ''].filter(Boolean);
    const posing = k.fields['posingAs'];
    return `${k.fields['event'] ?? k.kind}${detail ? `: ${detail}` : ''}${given.length ? ` (${given.join(', ')})` : ''}${typeof posing === 'string' ? ` ${posingText(k.module, posing)}` : ''}`;
}

/** How the runtime tries a request kept for a full mailbox again (docs/runtime-api.md, queued sends). */
const KEPT_RETRY = 'tried again every 5 ms, for up to 2 s';

/** A detail word of a record as text (a number the reader typed as one back to its digits), cut to 64 characters. */
function wordText(v: string | number | undefined): string {
    return v === undefined ? '' : String(v).slice(0, 64);
}

/** A count of a `requests_kept_end` detail: a whole number, else 0 (a forged word is no count). */
function keptCount(v: string | number | undefined): number {
    return typeof v === 'number' && Number.isSafeInteger(v) && v > 0 ? v : 0;
}

/**
 * A supervisor's `requests_kept` or `requests_kept_end` record as the story and the IDE's Monitor
 * (its timeline marks) tell it, else undefined: `VEL's mailbox is full: its STOP request is kept
 * (tried again every 5 ms, for up to 2 s)`; `the requests kept for VEL's full mailbox ended after
 * 2 s: 4 sent, 1 failed, 73 values replaced by later ones` (the counts that are 0 left out).
 */
export function keptRequestsText(k: Pick<KnownRecord, 'kind' | 'peer' | 'fields'>): string | undefined {
    const peer = k.peer || '?';
    if (k.kind === 'requests_kept') {
        const request = wordText(k.fields['request']);
        return `${peer}'s mailbox is full: its ${request ? `${request} ` : ''}request is kept (${KEPT_RETRY})`;
    }
    if (k.kind !== 'requests_kept_end') return undefined;
    const keptNs = k.fields['kept_ns'];
    const after = typeof keptNs === 'number' && keptNs >= 0 ? ` after ${durationText(keptNs)}` : '';
    const sent = keptCount(k.fields['sent']), failed = keptCount(k.fields['failed']), replaced = keptCount(k.fields['replaced']);
    const parts = [sent ? `${sent} sent` : '', failed ? `${failed} failed` : '',
        replaced ? `${plural(replaced, 'value')} replaced by ${replaced === 1 ? 'a later one' : 'later ones'}` : ''].filter(Boolean);
    return `the requests kept for ${peer}'s full mailbox ended${after}${parts.length ? `: ${parts.join(', ')}` : ''}`;
}

/** Characters of a log-capped record's detail told at most (the runtime's are shorter; a forged one is cut). */
const CAPPED_DETAIL_CHARS = 200;

/**
 * A `log-capped` record as the story tells it: `log capped: log reached its 197388288-byte bound
 * (CONTRACT_LOG_MAX_BYTES): later records are not written`, at the module's end `log capped: 667375
 * records not written after ...`; the build service's `log cut by the build service: collected the
 * first K of N bytes (...)`.
 */
function cappedText(k: KnownRecord): string {
    const detail = k.detail.length > CAPPED_DETAIL_CHARS ? `${k.detail.slice(0, CAPPED_DETAIL_CHARS)}…` : k.detail;
    return `${k.peer === 'build-service' ? 'log cut by the build service' : 'log capped'}: ${detail || 'its log reached its bound'}`;
}

/** A KILL that says why the run stops (contract-launch's, when the build service said: `KILL (the build service's memory limit was reached)`). */
const KILL_WHY = /^KILL \(([ -~]{1,120})\)$/;

/**
 * `asked to stop by contract-launch: <why>` for a request_received record of the launcher's KILL
 * that says why the run stops; undefined for any other record. The story and the IDE's Monitor
 * tell the first of them (every module gets one).
 */
export function askedToStopText(k: KnownRecord): string | undefined {
    if (k.kind !== 'request_received' || k.peer !== 'contract-launch') return undefined;
    const why = KILL_WHY.exec(k.detail);
    return why ? `asked to stop by contract-launch: ${why[1]}` : undefined;
}

/** What the story adds to a record cut at its log's end (TraceRecordBase.cut). */
export const CUT_RECORD = ' [cut: its log ends inside this line, with no line end; the record may have lost its end (its module was killed while writing it, or still writes it)]';

/** `+1.250000s` after the first record, `-0.000100s` before it (a record out of its place). */
function offset(ns: bigint): string {
    const s = (Number(ns < 0n ? -ns : ns) / 1e9).toFixed(6);
    return `${ns < 0n ? '-' : '+'}${s}s`;
}

/**
 * Schemas (cycles, held cycles) and modules (exits) the story follows at most, and modules released
 * and not finished in all followed cycles: a run has far fewer. Past them (a forged log of a
 * million schema names) a record is told without what it would add: the story's memory does not
 * grow with the logs. The names kept are copies (ownString), never the lines they were read from.
 */
export const STORY_FOLLOWED = 4096;
/**
 * The words of a run_finished detail (`activation=N [ACK_FINISHED|ACK_STOPPED|STOP|KILL]`) that say
 * what ended the run: without any, the module's code returned (libmodule's WaitForRequest). Read
 * as words, not as the detail's last one: a field added to the record does not change the reading.
 */
const RUN_END_WORDS = ['ACK_FINISHED', 'ACK_STOPPED', 'STOP', 'KILL'] as const;

/** The activation number of a run_finished detail that no STOP, KILL or ack ended, else undefined. */
function ownRunActivation(detail: string): string | undefined {
    const from = wordValueIn(detail, 'activation');
    if (from < 0) return undefined;
    const space = detail.indexOf(' ', from);
    const to = space < 0 ? detail.length : space;
    if (!isDigitsIn(detail, 1, 19, from, to) || RUN_END_WORDS.some((w) => hasWordIn(detail, w))) return undefined;
    return detail.slice(from, to);
}

/**
 * `run #N ended by its own code` for the detail of a run_finished that no STOP, KILL or ack ended,
 * else undefined: the words of the story and of `simulate --verbose` (a scenario's `finish`).
 */
export function ownRunEndText(detail: string): string | undefined {
    const run = ownRunActivation(detail);
    return run === undefined ? undefined : `run #${run} ended by its own code`;
}
const RUNNING_FOLLOWED = 65_536;

/**
 * What ORD did of one periodic schema in a run or a scenario, as the story's schema lines tell it
 * (and `contract run` / `contract simulate --format json` give it: their `schemas`).
 */
export interface SchemaFigures {
    completedCycles: number;
    maxResponseNs: number;
    deadlineMisses: number;
    /** Every skipped release (ord-counts.ts), as `expect overruns` counts them. */
    overruns: number;
    heldCycles: number;
    missedTicks: number;
    /** Cycles ORD itself released at or past their CRITICAL_DELAY (`late release: ...`): missed, but no ORD:0, not in deadlineMisses. */
    lateReleases: number;
}

/** A periodic schema's figures with its name, as `schemaFigures()` lists them. */
export interface NamedSchemaFigures extends SchemaFigures {
    schema: string;
}

/** The modules released in one cycle and not finished yet; how late ORD sent its first release. */
interface CycleRunning {
    cycle: string;
    running: Set<string>;
    firstReleaseLateNs?: number;
    /** Its tick (an ord_release's tick_ns), and each running module's release id. */
    tickNs?: number;
    releases?: Map<string, string>;
    /** Running modules whose own records say they finished (ORD had not read their ack yet). */
    acks?: Map<string, EarlyAck>;
    /** Modules its deadline miss did not blame (they had finished): ORD's later read of their ack is told. */
    readLate?: Set<string>;
}

/**
 * The story told one record at a time, in time order (a streamed run of any length: only the
 * counts are kept): `tell` gives the record's line, if it is told; `schemaLines` each periodic
 * schema's figures, `summary` the line of counts.
 */
export class StoryTeller {
    private t0: bigint | undefined;
    /** Records told and unreadable lines (countRecord). */
    private readonly counted: RecordCounts = { records: 0, unreadable: 0 };
    private readonly counts = new Map<string, number>();
    /**
     * Per periodic schema: its current and previous cycle and the modules released in each and not
     * finished (a deadline miss names them; it may come after the next cycle's releases when
     * CRITICAL_DELAY = PERIOD).
     */
    private readonly cycles = new Map<string, { current: CycleRunning; previous?: CycleRunning }>();
    /** Per periodic schema whose new cycle is held: the module it waits for. */
    private readonly held = new Map<string, string>();
    /** Modules whose exit record was read, with its detail: ORD's stuck advice does not fit them. */
    private readonly exited = new Map<string, string>();
    /**
     * Modules (at most STORY_FOLLOWED) a `stuck:` record said are no longer running (crashed, killed):
     * a cycle held for one of them does not wait for a module that "still runs" its release.
     */
    private readonly gone = new Set<string>();
    /** Modules in the `running` sets of all cycles followed. */
    private running = 0;
    /** Each running module's cycle (the last it was released in): its own ack_sent or run_finished is noted there. */
    private readonly releasedIn = new Map<string, CycleRunning>();
    /**
     * Per supervisor (at most STORY_FOLLOWED): the hold record that would only confirm the action
     * line it wrote last (`start module M` then `module M: hold taken (started it)`): not told again.
     */
    private readonly confirming = new Map<string, ConfirmingHold>();
    /**
     * Modules (at most STORY_FOLLOWED) whose current run a supervisor or a control tool began (a
     * `run_started` whose peer is not ORD), with that peer: a run of theirs that ends with no STOP
     * and no ack (`activation=N` alone) is told: the module's own code ended it. ORD's releases end
     * with an ack and are not followed.
     */
    private readonly runs = new Map<string, string>();
    /** Event ports (at most STORY_FOLLOWED) whose first event with no subscriber was told; all such events are counted. */
    private readonly unheardPorts = new Set<string>();
    private unheard = 0;
    /** Data flows (at most STORY_FOLLOWED) whose first dropped value was told: later drops are only counted. */
    private readonly droppingFlows = new Set<string>();
    /** The supervisors' undos to ORD, followed until ORD serves them: those its end left unserved are told (undos-to-ord.ts). */
    private readonly undos = new UndosToOrd();
    /** Modules whose records stopped mid-run, told at their last record once another gives the first sign that they are gone. */
    private readonly endedMidRun = new EndedMidRun();
    /** Why the run stopped was told (the first module's KILL that says it: the others say the same). */
    private stopWhyTold = false;
    /** Per periodic schema (at most STORY_FOLLOWED): its figures, told before the counts (schemaLines). */
    private readonly schemas = new Map<string, SchemaFigures>();
    /** Schemas past STORY_FOLLOWED: counted in the totals only. */
    private schemasLeftOut = 0;
    /**
     * Logs (at most STORY_FOLLOWED) that stopped before the run's end — their module's first
     * `log-capped` record: its bound, the logs' disk reserve, a full disk, the build service's cut —
     * with the run's time then: the figures and counts after it are partial (partialLines).
     */
    private readonly cappedLogs = new Map<string, string>();
    /** Per periodic schema (at most STORY_FOLLOWED): how late ORD released its cycles, told in its schema line. */
    private readonly lateness = new Map<string, ReleaseLateness>();
    /** Each released module's CPU time per release (run_finished's cpu_ns): moduleCpuLines. */
    readonly moduleCpu = new ModuleCpu();
    /** ORD's and each supervisor's own CPU time in their runs (run_finished's cpu_ns): moduleCpuLines. */
    readonly engineCpu = new EngineCpu();
    /** ORD's data flows: those connected long enough that delivered nothing, or far less than read; the event flows supervisors connected that delivered nothing (flowLines). */
    private readonly dataFlows = new DataFlowUse();
    /** Event flows whose posts waited for room in their subscriber's full mailbox (flowLines). */
    private readonly eventWaits = new EventWaits();
    /** Each asynchronous module's handling of its events (`event_handled`: handlingLines). */
    private readonly eventHandling = new EventHandling();
    /** Events whose posts failed during the run: lost (lost-events.ts; flowLines, the line of counts). */
    private readonly lostEvents = new LostEvents();
    /** A supervisor's module events that changed no rule (unmatched-events.ts). */
    private readonly unmatched = new UnmatchedEvents();
    /** Supervisors whose event deliveries the log does not record (an older version's: unrecorded-deliveries.ts). */
    private readonly unrecordedDeliveries = new UnrecordedDeliveries();
    /** Changes of producer on input data ports: schema switches, interleaves (producer-changes.ts). */
    private readonly producerChanges = new ProducerChanges();

    /**
     * `+S.mmmmmm MODULE what` for a told record, else undefined; counts every record, and every
     * unreadable line apart. A record cut at its log's end (`cut`) is told whatever its kind, and
     * said to be cut.
     */
    tell(r: TraceRecord): string | undefined {
        const told = this.tellRecord(r);
        if (r.kind === 'unknown' || !(r as TraceRecordBase).cut) return told;
        const k = r as TraceRecordBase & { kind: string };
        return told ? `${told}${CUT_RECORD}` : `${offset(BigInt(k.monoNs) - (this.t0 ?? 0n))} ${k.module.padEnd(4)} ${k.kind} record${CUT_RECORD}`;
    }

    /**
     * The records told are a simulation's (a trace file's `sim_start`): its virtual modules run no
     * code, so the flows' use (data values read, events modules post) is not told as findings of
     * module code (data-flow-use.ts: one line says why), and no engine's CPU time is measured
     * (engine-cpu.ts tells none).
     */
    simulation(): void {
        this.dataFlows.simulated();
        this.engineCpu.simulated();
    }

    /**
     * One of the launcher's own end lines of the logs folder (contract-launch.log), handed in before
     * the first record after its time (LauncherLinesQueue): the module it says ended on its own, told
     * at its last record with the line as the evidence (EndedMidRun.launcherLine); undefined when the
     * line is not taken (another pid than the module's start record's, an end the records already
     * tell) or no record was read yet.
     */
    tellLauncherLine(end: LauncherFileLine): LauncherToldEnd | undefined {
        const t0 = this.t0;
        if (t0 === undefined) return undefined;
        return this.endedMidRun.launcherLine(end, (ns) => offset(ns - t0));
    }

    private tellRecord(r: TraceRecord): string | undefined {
        countRecord(this.counted, r);
        this.counts.set(r.kind, (this.counts.get(r.kind) ?? 0) + 1);
        this.countSchema(r);
        if (r.kind === 'unknown') return undefined;
        const t0 = (this.t0 ??= BigInt((r as TraceRecordBase).monoNs));
        const at = (x: TraceRecordBase) => `${offset(BigInt(x.monoNs) - t0)} ${x.module.padEnd(4)}`;
        if (isRule(r)) {
            this.unrecordedDeliveries.seeRule(r);
            return `${at(r)} rule ${r.function}.${r.rule} ${r.active ? 'active  ' : 'inactive'} <- ${describeCause(r.causeEvent)}`;
        }
        const k = r as KnownRecord;
        const what = String(k.fields['what'] ?? '');
        this.unrecordedDeliveries.seeRecord(k);
        if (k.kind === 'supervisor') this.followAction(k, what);
        if (k.kind === 'ack_sent' || k.kind === 'run_finished') this.followAck(k);
        this.moduleCpu.see(k);
        this.engineCpu.see(k);
        this.undos.see(k);
        this.endedMidRun.see(k);
        this.dataFlows.see(k);
        this.lostEvents.see({ module: k.module, kind: k.kind, peer: k.peer, port: k.port ?? undefined, detail: k.detail });
        this.eventHandling.see(k);
        const waited = this.eventWaits.see(k);
        if (waited) return `${at(k)} ${waited}`;
        const unmatched = this.unmatched.see(k);
        if (unmatched) return `${at(k)} ${unmatched}`;
        const changed = this.producerChanges.see(k);
        if (changed) return `${at(k)} ${changed}`;
        if (k.kind === 'supervisor' && SUPERVISOR_TOLD.has(what)) return `${at(k)} ${k.detail}`;
        // every action and undo, with its target and value: who activated a schema or a function, what it sent,
        // the modules it started and stopped, the flows it connected, the priorities it claimed
        if (k.kind === 'supervisor' && what === 'action') return `${at(k)} ${k.detail}`;
        // a line of another engine version, or forged: told, but not as an action
        if (k.kind === 'supervisor' && what === 'other') return `${at(k)} (a supervisor line this reader does not know) ${k.detail}`;
        // what the holds of the modules a supervisor starts and stops (event schemas, activate
        // resttime|critical module) and of the event flows it connects decided: told unless it only
        // confirms the action line just told (a log of an older version has no such line: all told)
        if (k.kind === 'module_hold' || k.kind === 'flow_hold') {
            if (this.confirms(k)) return undefined;
            return `${at(k)} ${holdText(k.kind, k.peer, k.detail)}`;
        }
        if (k.kind === 'scheduler' && (what === 'held' || what === 'resumed' || what === 'deactivate')) {
            const schema = String(k.fields['schema']);
            if (what === 'held' && (this.held.has(schema) || this.held.size < STORY_FOLLOWED)) this.held.set(ownString(schema), ownString(String(k.fields['module'])));
            else if (what !== 'held') this.held.delete(schema);
        }
        // a new activation counts its cycles from 0 again, and a deactivated one has no cycle left:
        // the releases of the one before, acknowledged late or never, are not this one's to wait for
        if (k.kind === 'scheduler' && (what === 'activate' || what === 'deactivate')) this.forgetCycles(String(k.fields['schema']));
        if (k.kind === 'scheduler' && what === 'stuck' && stuckSaysGone(k.detail)) {
            const module = String(k.fields['module']);
            if (this.gone.has(module) || this.gone.size < STORY_FOLLOWED) this.gone.add(ownString(module));
        }
        if (k.kind === 'scheduler' && (what === 'unstuck' || what === 'late_ack')) this.gone.delete(String(k.fields['module'])); // it ran on after all
        if (k.kind === 'scheduler' && what === 'held' && this.isGone(String(k.fields['module']))) {
            // ORD only knows the release is outstanding: the module that "still runs" it is gone
            return `${at(k)} cycle of ${String(k.fields['schema'])} held: ${String(k.fields['module'])} never finished a release of an earlier activation: it is no longer running`;
        }
        if (k.kind === 'scheduler' && what === 'stuck' && this.exited.has(String(k.fields['module']))) {
            // a module that had ended (a crash the simulator made, an exit) never finishes: the advice to set *stateindex = -1 does not fit it
            return `${at(k)} ${k.detail.replace(STUCK_ADVICE, `: it had exited before (${this.exited.get(String(k.fields['module']))})`)}`;
        }
        if (k.kind === 'scheduler' && (SCHEDULER_TOLD.has(what) || ignoredUndo(k))) {
            // ORD's `stuck: ... it is no longer running`, the first sign that its module is gone: told at that module's last record
            return (what === 'stuck' ? this.endedMidRun.lineFor(k, k.detail, (ns) => offset(ns - t0)) : undefined) ?? `${at(k)} ${k.detail}`;
        }
        if (k.kind === 'scheduler' && what === 'other') return `${at(k)} (an ORD line this reader does not know) ${k.detail}`;
        if (k.kind === 'ord_release' || k.kind === 'ord_finished') {
            const readLate = k.kind === 'ord_finished' ? this.readLateText(k) : undefined;
            this.followCycle(k);
            return readLate && `${at(k)} ${readLate}`;
        }
        if (k.kind === 'ord_deadline_miss') return `${at(k)} ${this.missText(k)}`;
        if (k.kind === 'request_received' && !this.stopWhyTold) {
            // the launcher's KILL saying why the run stops (the build service's limit, a cancel): told once
            const asked = askedToStopText(k);
            if (asked) {
                this.stopWhyTold = true;
                return `${at(k)} ${asked} (every module's KILL says so; the first is told)`;
            }
        }
        if (k.kind === 'run_started') {
            if (k.peer === 'ORD') this.runs.delete(k.module);
            else if (this.runs.has(k.module) || this.runs.size < STORY_FOLLOWED) this.runs.set(ownString(k.module), ownString(k.peer));
            return undefined;
        }
        if (k.kind === 'run_finished') {
            const starter = this.runs.get(k.module);
            this.runs.delete(k.module);
            const ended = starter === undefined ? undefined : ownRunEndText(k.detail);
            // (its CPU time, cpu_ns, is no part of it: the figures of the released modules say theirs, module-cpu.ts)
            return ended && `${at(k)} ${ended} (started by ${starter || 'a control tool'})`;
        }
        if (k.kind === 'module_started') {
            this.exited.delete(k.module); // started again: a later stuck report is about this run of it
            this.gone.delete(k.module);
            return `${at(k)} started (${k.detail})`;
        }
        // ORD's priority, right after its start: whether the run was real-time (SCHED_FIFO) or at nice levels
        if (k.kind === 'priority' && k.module === 'ORD') return `${at(k)} ${priorityText(k.detail)}`;
        if (k.kind === 'module_exit') {
            if (this.exited.has(k.module) || this.exited.size < STORY_FOLLOWED) this.exited.set(ownString(k.module), ownString(k.detail.slice(0, 120)));
            return `${at(k)} exited (${k.detail})${this.unservedUndoText(k.module)}`;
        }
        if (k.kind === 'module_crashed') {
            const crash = crashText(k.detail);
            if (this.exited.has(k.module) || this.exited.size < STORY_FOLLOWED) this.exited.set(ownString(k.module), ownString(crashText(k.detail, false).slice(0, 120)));
            return `${at(k)} ${crash}${this.unservedUndoText(k.module)}`;
        }
        if (k.kind === 'data_dropped') {
            const text = this.firstDropText(k);
            return text && `${at(k)} ${text}`;
        }
        if (k.kind === 'event_posted' && k.detail === 'no subscriber') {
            // an event no one received (its subscriber had unsubscribed, none ever did): why a rule
            // waiting for it did not fire; the port's first told, the others counted at the end
            this.unheard++;
            const port = `${k.module}:${k.port ?? '?'}`;
            if (this.unheardPorts.has(port) || this.unheardPorts.size >= STORY_FOLLOWED) return undefined;
            this.unheardPorts.add(ownString(port));
            return `${at(k)} ${unheardEventText(port)}; its later ones are counted at the end`;
        }
        if (k.kind === 'user') return `${at(k)} ${userRecordText(k)}`;
        // a log's bound reached (the runtime's at the bound and at its end, the build service's on a log it cut)
        if (k.kind === 'log-capped') {
            if (!this.cappedLogs.has(k.module) && this.cappedLogs.size < STORY_FOLLOWED) this.cappedLogs.set(ownString(k.module), offset(BigInt(k.monoNs) - t0).trim());
            return `${at(k)} ${cappedText(k)}`;
        }
        // a supervisor's requests kept for a receiver's full mailbox: when it began, and what came of them
        if (k.kind === 'requests_kept' || k.kind === 'requests_kept_end') return `${at(k)} ${keptRequestsText(k)}`;
        // a request to a module already gone while the launcher stopped the run (no error line on stderr either)
        if (k.kind === 'error') {
            const told = `${k.detail.endsWith(RUN_STOPPING) ? 'while the run stopped' : 'error'}: ${k.detail}`;
            // the first sign that its receiver is gone mid-run: told at the receiver's last record, this record its evidence
            return this.endedMidRun.lineFor(k, told, (ns) => offset(ns - t0)) ?? `${at(k)} ${told}`;
        }
        return undefined;
    }

    /**
     * The first value a data flow dropped (`data_dropped`), told with why; its later drops are only
     * counted (a consumer that never reads drops one value per release): undefined for them.
     */
    private firstDropText(k: KnownRecord): string | undefined {
        const toPort = k.fields['to_port'];
        const flow = `${k.module}:${k.port ?? '?'} -> ${k.peer}:${toPort ?? '?'}`;
        if (this.droppingFlows.has(flow) || this.droppingFlows.size >= STORY_FOLLOWED) return undefined;
        this.droppingFlows.add(ownString(flow));
        return dropText(flow, k.peer, String(toPort ?? '?'), k.detail);
    }

    /**
     * What ORD's end left unserved, told with its exit or crash record: `; while the run stopped: ORD
     * ended before it served SUP's undo: deactivate schema S (activation #N): S stayed active to its
     * end (...)` (UndosToOrd.atOrdEnd); empty for another module or none left.
     */
    private unservedUndoText(module: string): string {
        const left = module === 'ORD' ? this.undos.atOrdEnd() : undefined;
        return left ? `; ${left.text}` : '';
    }

    /**
     * The lines told once the records end (after the last tell): the undos to ORD its log never
     * answered when ORD wrote no exit record (killed, or terminated at the stop) and the run is seen
     * to have ended (UndosToOrd.atRecordsEnd), at the last of them: `+5.009420s ORD  ORD's log ends
     * with no exit record (...) and no answer to SUP's undo: ...`. None while an undo may be in flight.
     */
    endLines(): string[] {
        const left = this.undos.atRecordsEnd();
        if (!left) return [];
        return [`${offset(BigInt(left.monoNs) - (this.t0 ?? 0n))} ${'ORD'.padEnd(4)} ${left.text}`];
    }

    /** A supervisor's record: the hold record its action line expects, if any, replaces the one it expected. */
    private followAction(k: KnownRecord, what: string): void {
        const hold = what === 'action' ? confirmingHold(k.fields) : undefined;
        if (!hold) {
            this.confirming.delete(k.module);
        } else if (this.confirming.has(k.module) || this.confirming.size < STORY_FOLLOWED) {
            this.confirming.set(ownString(k.module), { kind: hold.kind, peer: ownString(hold.peer), detail: hold.detail });
        }
    }

    /** Whether a hold record only confirms the action line its supervisor wrote just before (it is then expected no more). */
    private confirms(k: KnownRecord): boolean {
        const c = this.confirming.get(k.module);
        if (!c) return false;
        this.confirming.delete(k.module);
        return c.kind === k.kind && c.peer === k.peer && c.detail === k.detail;
    }

    /**
     * `deadline miss (ORD:0): S cycle k (not finished: ARM)` for an `ord_deadline_miss` record, from
     * the releases and completions told before it (`simulate --verbose` says it so too).
     */
    missText(k: KnownRecord): string {
        return `deadline miss (ORD:0): ${k.fields['schema']} cycle ${k.fields['cycle']}${this.lateOf(k)}`;
    }

    private followCycle(k: KnownRecord): void {
        const schema = String(k.fields['schema'] ?? ''), cycle = String(k.fields['cycle'] ?? '');
        this.held.delete(schema);
        let s = this.cycles.get(schema);
        if (!s) {
            if (this.cycles.size >= STORY_FOLLOWED) return;
            this.cycles.set(ownString(schema), (s = { current: { cycle: ownString(cycle), running: new Set() } }));
        }
        if (k.kind === 'ord_release') {
            if (s.current.cycle !== cycle || s.current.firstReleaseLateNs === undefined) {
                const late = Number(k.fields['release_ns']) - Number(k.fields['tick_ns']);
                if (s.current.cycle !== cycle) {
                    this.running -= s.previous?.running.size ?? 0; // the cycle before the previous one is no longer followed
                    s = { current: { cycle: ownString(cycle), running: new Set() }, previous: s.current };
                }
                s.current.firstReleaseLateNs = Number.isFinite(late) ? late : 0;
                this.latenessOf(schema)?.add(late);
            }
            this.cycles.set(schema, s);
            if (this.running < RUNNING_FOLLOWED && !s.current.running.has(k.peer)) {
                const module = ownString(k.peer);
                s.current.running.add(module);
                this.running++;
                const tick = Number(k.fields['tick_ns']);
                if (Number.isFinite(tick)) s.current.tickNs = tick;
                (s.current.releases ??= new Map()).set(module, String(k.fields['release'] ?? ''));
                s.current.acks?.delete(module);
                this.releasedIn.set(module, s.current);
            }
        } else if (this.cycleOf(schema, cycle)?.running.delete(k.peer)) {
            this.running--;
            if (this.releasedIn.get(k.peer) === this.cycleOf(schema, cycle)) this.releasedIn.delete(k.peer);
        }
    }

    /**
     * ORD's `ord_finished` for a module its cycle's deadline miss did not blame: when ORD read the
     * ack, `ORD read HOG's ack of slow cycle 152 at +13.820 ms, 11.570 ms after HOG sent it (ORD's
     * response_ns counts to this read, not to HOG's finish)`.
     */
    private readLateText(k: KnownRecord): string | undefined {
        const schema = String(k.fields['schema'] ?? ''), cycle = String(k.fields['cycle'] ?? '');
        const c = this.cycleOf(schema, cycle);
        const ack = c?.readLate?.has(k.peer) ? c.acks?.get(k.peer) : undefined;
        if (!c || !ack || c.tickNs === undefined) return undefined;
        const readNs = Number(k.monoNs) - c.tickNs;
        return `read ${k.peer}'s ack of ${schema} cycle ${cycle} at ${sinceTickText(readNs)}, ${durationText(readNs - ack.sinceTickNs)} after ${k.peer} ${ack.how === 'its ack sent' ? 'sent it' : 'finished'} ` +
            `(ORD's response_ns counts to this read, not to ${k.peer}'s finish)`;
    }

    /**
     * A module's own `ack_sent` to ORD (`ACK_FINISHED id=N`, N its release) or `run_finished`
     * (`activation=N ACK_FINISHED`): noted on the cycle that released it while ORD has not counted
     * it finished, so that a deadline miss does not blame a module that had finished (ORD read its ack late).
     */
    private followAck(k: KnownRecord): void {
        const c = this.releasedIn.get(k.module);
        if (!c || !c.running.has(k.module) || c.tickNs === undefined) return;
        let how: EarlyAck['how'];
        if (k.kind === 'ack_sent') {
            if (k.peer !== 'ORD' || !hasWordIn(k.detail, 'ACK_FINISHED')) return;
            const id = k.fields['id'], released = c.releases?.get(k.module);
            if (released && id !== undefined && String(id) !== released) return; // an ack of another release
            how = 'its ack sent';
        } else {
            if (!hasWordIn(k.detail, 'ACK_FINISHED') || c.acks?.has(k.module)) return;
            how = 'its run finished';
        }
        (c.acks ??= new Map()).set(k.module, { module: k.module, sinceTickNs: Number(k.monoNs) - c.tickNs, how });
    }

    /** The release lateness of schema `schema` (undefined past STORY_FOLLOWED schemas). */
    private latenessOf(schema: string): ReleaseLateness | undefined {
        let l = this.lateness.get(schema);
        if (!l && this.lateness.size < STORY_FOLLOWED) this.lateness.set(ownString(schema), (l = new ReleaseLateness()));
        return l;
    }

    /** Schema `schema`'s cycles no longer followed (a new activation, or none). */
    private forgetCycles(schema: string): void {
        const s = this.cycles.get(schema);
        if (!s) return;
        this.running -= s.current.running.size + (s.previous?.running.size ?? 0);
        for (const c of [s.current, s.previous]) for (const m of c?.running ?? []) if (this.releasedIn.get(m) === c) this.releasedIn.delete(m);
        this.cycles.delete(schema);
    }

    private cycleOf(schema: string, cycle: string): CycleRunning | undefined {
        const s = this.cycles.get(schema);
        return s?.current.cycle === cycle ? s.current : s?.previous?.cycle === cycle ? s.previous : undefined;
    }

    private lateOf(k: KnownRecord): string {
        const schema = String(k.fields['schema'] ?? '');
        const c = this.cycleOf(schema, String(k.fields['cycle'] ?? ''));
        const heldFor = this.held.get(schema);
        const running = c ? [...c.running].sort() : [];
        const cd = missCriticalDelayNs(k.fields);
        // the deadline: tick + CRITICAL_DELAY, or (an older log) when ORD told the miss
        const deadlineNs = c?.tickNs === undefined ? undefined : cd ?? Number(k.monoNs) - c.tickNs;
        const early = c?.acks && deadlineNs !== undefined ? earlyFinish(running, c.acks, deadlineNs) : undefined;
        if (c && early) for (const m of running) if (!early.rest.split(', ').includes(m)) (c.readLate ??= new Set()).add(m);
        return missWaitText(heldFor, running.join(', '), c?.firstReleaseLateNs, heldFor !== undefined && this.isGone(heldFor), cd, early);
    }

    /** Whether `module` is known to be no longer running: a stuck record said so, or its exit record was read. */
    private isGone(module: string): boolean {
        return this.gone.has(module) || this.exited.has(module);
    }

    /** The figures of schema `name` (undefined past STORY_FOLLOWED schemas). */
    private figuresOf(name: unknown): SchemaFigures | undefined {
        if (typeof name !== 'string' || !name) return undefined;
        let f = this.schemas.get(name);
        if (!f) {
            if (this.schemas.size >= STORY_FOLLOWED) {
                this.schemasLeftOut++;
                return undefined;
            }
            f = { completedCycles: 0, maxResponseNs: 0, deadlineMisses: 0, overruns: 0, heldCycles: 0, missedTicks: 0, lateReleases: 0 };
            this.schemas.set(ownString(name), f);
        }
        return f;
    }

    /**
     * A record's share of its periodic schema's figures (ORD's completions, misses, overruns, held
     * cycles, missed ticks), and of the totals' overruns (every skipped release, as ORD counts them:
     * ord-counts.ts) and held cycles (`scheduler:overrun`, `scheduler:held`).
     */
    private countSchema(r: TraceRecord): void {
        if (r.kind !== 'ord_complete' && r.kind !== 'ord_deadline_miss' && r.kind !== 'scheduler') return;
        const fields = (r as KnownRecord).fields;
        if (r.kind === 'ord_complete') {
            const f = this.figuresOf(fields['schema']);
            if (!f) return;
            f.completedCycles++;
            const resp = fields['response_ns'];
            if (typeof resp === 'number' && Number.isFinite(resp) && resp > f.maxResponseNs) f.maxResponseNs = resp;
        } else if (r.kind === 'ord_deadline_miss') {
            const f = this.figuresOf(fields['schema']);
            if (f) f.deadlineMisses++;
        } else {
            const what = fields['what'];
            if (what === 'late_release') {
                const f = this.figuresOf(fields['schema']);
                if (f) f.lateReleases++;
                return;
            }
            if (what !== 'overrun' && what !== 'overrun_ended' && what !== 'held' && what !== 'missed_tick' && what !== 'missed_ticks_ended') return;
            const skipped = skippedReleasesOf(fields);
            const held = what === 'held' ? 1 : 0;
            if (skipped) this.counts.set('scheduler:overrun', (this.counts.get('scheduler:overrun') ?? 0) + skipped);
            if (held) this.counts.set('scheduler:held', (this.counts.get('scheduler:held') ?? 0) + 1);
            const f = this.figuresOf(fields['schema']);
            if (!f) return;
            f.overruns += skipped;
            f.missedTicks += missedTicksOf(fields);
            f.heldCycles += held;
        }
    }

    /**
     * One line per periodic schema ORD completed, missed or overran a cycle of, in name order, told
     * before the counts: `schema velocityLoop: 492 completed cycles (response max 89.221 ms), 2
     * deadline misses, 9 overruns, 1 held cycle; release lateness p50 23.1 µs, p99 965 µs, max 8.8 ms`
     * (held cycles, ORD's missed ticks and the cycles it released past their CRITICAL_DELAY when any; how late ORD released its cycles when the log has
     * their releases: release-lateness.ts).
     */
    schemaLines(): string[] {
        // ORD's log stopped early: its completions, misses and overruns after that were not written
        const ordCapped = this.cappedLogs.get('ORD');
        const upTo = ordCapped ? ` — up to ${ordCapped} only: ORD's log stopped then (log-capped), its later cycles are not counted` : '';
        const lines = this.schemaFigures().map((f) =>
            `schema ${f.schema}: ${plural(f.completedCycles, 'completed cycle')}${f.completedCycles ? ` (response max ${durationText(f.maxResponseNs)})` : ''}, ` +
            `${plural(f.deadlineMisses, 'deadline miss', 'deadline misses')}, ${plural(f.overruns, 'overrun')}` +
            `${f.heldCycles ? `, ${plural(f.heldCycles, 'held cycle')}` : ''}${f.missedTicks ? `, ${plural(f.missedTicks, 'missed tick')} (ORD itself late)` : ''}` +
            `${f.lateReleases ? `, ${plural(f.lateReleases, 'cycle')} released past CRITICAL_DELAY (ORD itself late, no ORD:0)` : ''}` +
            `${this.lateness.get(f.schema)?.text().replace(/^./, '; $&') ?? ''}${upTo}`);
        if (this.schemasLeftOut) lines.push(`(${plural(this.schemasLeftOut, 'record')} of schemas past the ${STORY_FOLLOWED} followed: in the counts below only)`);
        lines.push(...this.partialLines());
        return lines;
    }

    /** One line per module ORD released whose runs said their CPU time, after the schema lines (module-cpu.ts), then ORD's and each supervisor's own CPU (engine-cpu.ts). */
    moduleCpuLines(): string[] {
        return [...this.moduleCpu.lines(), ...this.engineCpu.lines()];
    }

    /** ORD's and the supervisors' own CPU as data (`contract run --format json`'s `engineCpu`). */
    engineCpuFigures(): EngineCpuFigure[] {
        return this.engineCpu.figures();
    }

    /** The same as data, in module order (`contract run --format json`'s `moduleCpu`). */
    moduleCpuFigures(): ModuleCpuFigure[] {
        return this.moduleCpu.figures();
    }

    /**
     * One line when some log stopped before the run's end (a `log-capped` record: `partial counts:
     * the logs of ORD (from +28.1 s), CUR (from +27.9 s) stopped before the run's end (log-capped):
     * the figures above and the counts below hold only their records up to then`); none otherwise.
     */
    partialLines(): string[] {
        if (!this.cappedLogs.size) return [];
        const logs = [...this.cappedLogs].map(([m, at]) => `${m} (from ${at})`).join(', ');
        return [`partial counts: the log${this.cappedLogs.size > 1 ? 's' : ''} of ${logs} stopped before the run's end (log-capped): ` +
            'the figures above and the counts below hold only their records up to then'];
    }

    /**
     * What the flows did, told at the end before the schemas' lines: each event flow that lost
     * events (its posts failed, lost-events.ts), each event flow whose posts waited for room (event-waits.ts), each supervisor's flow whose events changed no rule, with
     * their values (unmatched-events.ts), each input data port whose producer changed
     * (producer-changes.ts), each data flow ORD connected that delivered nothing or far less than
     * its reader read (data-flow-use.ts).
     */
    flowLines(): string[] {
        return [...this.lostEvents.lostFlows().map(lostFlowText), ...this.eventWaits.lines(), ...this.unmatched.lines(), ...this.producerChanges.lines(), ...this.dataFlows.lines()];
    }

    /**
     * One line per asynchronous module that handled events (its `event_handled` records), in name
     * order, told after the flows' lines: the events handled, the handling time's p99 and max, the
     * longest with its event and when it was received (event-handling.ts).
     */
    handlingLines(): string[] {
        return this.eventHandling.lines((ns) => offset(ns - (this.t0 ?? ns)));
    }

    /** The same as data, in module order (`contract run --format json`'s `eventHandling`). */
    eventHandlingFigures(): EventHandlingFigures[] {
        return this.eventHandling.figures();
    }

    /** The same figures as data, in name order (`contract run` and `contract simulate --format json`). */
    schemaFigures(): NamedSchemaFigures[] {
        return [...this.schemas].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([schema, f]) => ({ schema, ...f }));
    }

    /** The records told so far (readable ones) and, apart, the unreadable lines: the numbers of the summary's first and last counts. */
    get recordCounts(): RecordCounts {
        return { ...this.counted };
    }

    /** The line of counts' words for the flows flowLines tells (`1 data flow that delivered nothing, 2 event posts that failed (the event lost), 340 event posts that waited for room, `), '' when none. */
    private flowCounts(): string {
        const { silent, sparse, silentEvents } = this.dataFlows.counts, waits = this.eventWaits.waits, lost = this.lostEvents.lost;
        return `${silent ? `${plural(silent, 'data flow')} that delivered nothing, ` : ''}` +
            `${silentEvents ? `${plural(silentEvents, 'event flow')} a supervisor connected that delivered nothing, ` : ''}` +
            `${sparse ? `${plural(sparse, 'data flow')} written far less often than read, ` : ''}` +
            `${lost ? `${plural(lost, 'event post')} that failed (the event lost), ` : ''}` +
            `${waits ? `${plural(waits, 'event post')} that waited for room, ` : ''}` +
            `${this.unmatched.count ? `${plural(this.unmatched.count, 'event')} that changed no rule, ` : ''}` +
            `${this.producerChanges.interleaves ? `${plural(this.producerChanges.interleaves, 'interleaved producer change')}, ` : ''}`;
    }

    /**
     * `3 event deliveries`; when supervisors' rules changed on module events that their log does not
     * record (logs of an older version: unrecorded-deliveries.ts), that the number is not known.
     */
    private eventDeliveries(recorded: number): string {
        const unknown = this.unrecordedDeliveries.supervisors();
        if (unknown.length === 0) return plural(recorded, 'event delivery', 'event deliveries');
        const named = unknown.slice(0, 3).join(', ') + (unknown.length > 3 ? ` and ${unknown.length - 3} more` : '');
        const why = `${named}'s log${unknown.length === 1 ? ' is' : 's are'} of an older version, which records no event a supervisor takes, though its rules changed on module events`;
        return recorded === 0 ? `an unknown number of event deliveries (${why})` : `${plural(recorded, 'event delivery', 'event deliveries')} and an unknown number more (${why})`;
    }

    /**
     * The line of counts: the records (readable ones: an unreadable line is no record, as in the
     * IDE's Monitor), what they were, and the unreadable lines.
     */
    summary(): string {
        const n = (kind: string) => this.counts.get(kind) ?? 0;
        return `${plural(this.counted.records, 'record')}: ${plural(n('ord_release'), 'module release')}, ${plural(n('ord_complete'), 'completed cycle')}, ` +
            `${plural(n('ord_deadline_miss'), 'deadline miss', 'deadline misses')}, ${plural(n('scheduler:overrun'), 'overrun')}, ` +
            `${plural(n('scheduler:held'), 'held cycle')}, ${plural(n('sup_rule'), 'rule change')}, ` +
            `${n('data_received')} data and ${this.eventDeliveries(n('event_received'))}, ` +
            `${n('data_dropped') ? `${plural(n('data_dropped'), 'data value')} dropped, ` : ''}` +
            `${this.flowCounts()}` +
            `${this.unheard ? `${plural(this.unheard, 'event')} with no subscriber, ` : ''}${plural(this.counted.unreadable, 'unreadable line')}`;
    }
}

/** One line per told record, `+S.mmmmmm MODULE what`, then the flows' lines, then one line per asynchronous module that handled events, then one line per periodic schema, then one per released module's CPU per release, then a summary line of counts. */
export function renderStory(records: TraceRecord[]): string[] {
    const teller = new StoryTeller();
    const lines: string[] = [];
    for (const r of records) {
        const line = teller.tell(r);
        if (line !== undefined) lines.push(line);
    }
    lines.push(...teller.endLines(), ...teller.flowLines(), ...teller.handlingLines(), ...teller.schemaLines(), ...teller.moduleCpuLines(), teller.summary());
    return lines;
}
