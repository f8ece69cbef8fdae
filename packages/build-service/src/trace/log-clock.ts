/**
 * Who may write a record, and when a record's time can be believed (docs/runtime-api.md "Trace
 * records", "Whose records, and their times"). Browser-safe; shared by every reader of a run's
 * records: the trace reader (parse.ts: `contract trace`, `contract run`'s figures and `--trace`),
 * the trace files' reader (jsonl.ts), the CLI's streamed and live readers and the IDE's Monitor
 * (live and replayed) and Timeline, so that they all take the same lines for records.
 *
 * - The engines' own kinds: `ord_*` and `scheduler` records are ORD's (the scheduler process is
 *   always named ORD); the supervisor kinds (`supervisor`, `sup_rule`, `module_hold`, `flow_hold`,
 *   `module_priority`, `priority_kept`) are never ORD's. A record of such a kind from another
 *   module is that module's own record (its code logged it under that name): read as a `user`
 *   record, marked (`fields.posingAs`), never counted as the engine's fact.
 * - Times (LogClock, one per log, its lines in file order): the runtime writes each log in
 *   CLOCK_MONOTONIC order and takes a record's mono_ns and wall_time at the same moment, so a
 *   record whose mono_ns goes back in its log (more than BACK_TOLERANCE_NS), jumps forward more
 *   than JUMP_CHECKED_NS while its wall_time moves less (by WALL_TOLERANCE_NS: a suspend moves the
 *   wall time on, not the monotonic one), or is past
 *   a 64-bit time, was not written by the runtime: an unreadable line, never the run's time.
 */
import type { TraceArea } from './record-kinds.js';

/** The scheduler process's name (the architecture's ORD: ORD:0, ORD:1 are its events). */
export const ORD_MODULE = 'ORD';

/** The engine whose own kind `area` is, when a module other than it writes one: a reason to mark it. */
export function posingAs(area: TraceArea, module: string): string | undefined {
    if (area === 'scheduler') return module === ORD_MODULE ? undefined : 'ORD';
    if (area === 'supervisor') return module === ORD_MODULE ? 'a supervisor' : undefined;
    return undefined;
}

/** What a record marked posingAs adds to its text in the story and the Monitor. */
export function posingText(module: string, engine: string): string {
    return `[${module.slice(0, 64)}'s own record under the name of ${engine === 'ORD' ? "ORD's" : "a supervisor's"} records: not taken for ${engine === 'ORD' ? "ORD's" : "a supervisor's"}]`;
}

const INT64_MAX = '9223372036854775807';

/** Whether the digits s[from, to) are a number past a signed 64-bit time (leading zeros left out). */
export function monoBeyondInt64(s: string, from = 0, to = s.length): boolean {
    while (to - from > 1 && s.charCodeAt(from) === 48) from++;
    const n = to - from;
    if (n !== 19) return n > 19;
    for (let i = 0; i < 19; i++) {
        const d = s.charCodeAt(from + i) - INT64_MAX.charCodeAt(i);
        if (d) return d > 0;
    }
    return false;
}

/** Why mono_ns s[from, to) (digits) is no time of a record, or undefined. */
export function monoTextProblem(s: string, from = 0, to = s.length): string | undefined {
    return monoBeyondInt64(s, from, to) ? 'mono_ns is past a 64-bit time (the runtime writes CLOCK_MONOTONIC ns, a signed 64-bit number)' : undefined;
}

/** A record's mono_ns may be this much before the one before it in its log (two threads of a module logging at once). */
export const BACK_TOLERANCE_NS = 1_000_000;
/** A step forward longer than this in a log has its wall_time checked. */
export const JUMP_CHECKED_NS = 1_000_000_000;
/** How far a step's wall_time may fall short of its mono_ns step (a wall clock set back during the run). */
export const WALL_TOLERANCE_NS = 60_000_000_000;

const d2 = (s: string, at: number): number => {
    const a = s.charCodeAt(at) - 48, b = s.charCodeAt(at + 1) - 48;
    return a >= 0 && a <= 9 && b >= 0 && b <= 9 ? a * 10 + b : NaN;
};

/** A wall_time s[from, to) as the runtime writes it (`2026-11-24T18:30:15.123456Z`) -> ms since the epoch, NaN for anything else. */
export function wallTimeMs(s: string, from = 0, to = s.length): number {
    if (to - from < 20 || to - from > 30 || s.charCodeAt(to - 1) !== 90 /* Z */) return NaN;
    if (s.charCodeAt(from + 4) !== 45 || s.charCodeAt(from + 7) !== 45 || s.charCodeAt(from + 10) !== 84 || s.charCodeAt(from + 13) !== 58 || s.charCodeAt(from + 16) !== 58) return NaN;
    const year = d2(s, from) * 100 + d2(s, from + 2);
    let ms = Date.UTC(year, d2(s, from + 5) - 1, d2(s, from + 8), d2(s, from + 11), d2(s, from + 14), d2(s, from + 17));
    let i = from + 19;
    if (i < to - 1) {
        if (s.charCodeAt(i) !== 46 /* . */) return NaN;
        let scale = 100;
        for (i++; i < to - 1; i++, scale /= 10) {
            const c = s.charCodeAt(i) - 48;
            if (c < 0 || c > 9) return NaN;
            ms += c * scale;
        }
    }
    return ms;
}

const seconds = (ns: number): string => `${(ns / 1e9).toFixed(3)} s`;

/**
 * The time check of one log's records, fed in file order (check: each record the reader read,
 * its mono_ns and its wall_time as text[wallFrom, wallTo)). Keeps the last record it took: a
 * record it refuses leaves it as it was.
 */
export class LogClock {
    private last = -1;
    private wallText = '';
    private wallFrom = 0;
    private wallTo = 0;

    /** Why the record is not believed (an unreadable line), or undefined (then it is the log's latest). */
    check(mono: number, text: string, wallFrom = 0, wallTo = text.length): string | undefined {
        const last = this.last;
        if (last >= 0) {
            if (mono < last - BACK_TOLERANCE_NS) return `mono_ns goes back in its log, ${seconds(last - mono)} before the record before it (the runtime writes a log in time order: a line written into it later?)`;
            if (mono - last > JUMP_CHECKED_NS) {
                const before = wallTimeMs(this.wallText, this.wallFrom, this.wallTo);
                if (!Number.isNaN(before)) {
                    const now = wallTimeMs(text, wallFrom, wallTo);
                    if (Number.isNaN(now)) return `mono_ns jumps ${seconds(mono - last)} past the record before it in its log, with no wall_time to confirm it`;
                    const wallStep = (now - before) * 1e6;
                    // one-sided: the wall time moving on further (a machine suspended mid-run, which
                    // CLOCK_MONOTONIC does not count; a wall clock set forward) is no forged time
                    if (mono - last - wallStep > WALL_TOLERANCE_NS) return `mono_ns jumps ${seconds(mono - last)} past the record before it in its log while its wall_time moved ${seconds(wallStep)} (the runtime takes both at the same moment)`;
                }
            }
        }
        if (mono > last) this.last = mono;
        this.wallText = text;
        this.wallFrom = wallFrom;
        this.wallTo = wallTo;
        return undefined;
    }
}

/** One LogClock per log (or per module of a trace file), made when first asked for. */
export class LogClocks {
    private readonly clocks = new Map<string, LogClock>();
    of(key: string): LogClock {
        let c = this.clocks.get(key);
        if (!c) this.clocks.set(key, (c = new LogClock()));
        return c;
    }
    /** Every log's time starts again (a trace file's next simulation, at time 0: its `sim_start`). */
    reset(): void {
        this.clocks.clear();
    }
}
