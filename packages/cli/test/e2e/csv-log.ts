/**
 * Reading the runtime's CSV logs (docs/runtime-api.md "CSV log") for end-to-end assertions:
 * releases in precedence order, delivery periodicities, supervisor rule sequences.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { splitCsvLine } from '@contract-studio/build-service/trace';

export interface LogRecord {
    mono: bigint;
    module: string;
    event: string;
    peer: string;
    port: string;
    detail: string;
}

/** One CSV line -> fields: the trace reader's own splitter (RFC 4180 quoting). */
export { splitCsvLine };

/** Every record of every `<MODULE>_*.csv` in dir, sorted by CLOCK_MONOTONIC time. */
export function readLogs(dir: string): LogRecord[] {
    const records: LogRecord[] = [];
    for (const file of readdirSync(dir).filter((f) => /^[A-Z]{3}_.*\.csv$/.test(f))) {
        const lines = readFileSync(join(dir, file), 'utf8').split('\n').filter((l) => l.length > 0);
        for (const line of lines.slice(1)) {
            const [mono, , module, event, peer, port, , detail] = splitCsvLine(line);
            if (!mono || !/^\d+$/.test(mono)) continue;
            records.push({ mono: BigInt(mono), module: module!, event: event!, peer: peer ?? '', port: port ?? '', detail: detail ?? '' });
        }
    }
    return records.sort((a, b) => (a.mono < b.mono ? -1 : a.mono > b.mono ? 1 : 0));
}

export interface ChainReport {
    /** Cycles where every module of the chain ran, each after its predecessor had finished. */
    completeCycles: number;
    /** Releases that broke the order: a module started before its predecessor finished in the cycle. */
    violations: string[];
    /** A module started a second time in one cycle (order kept; reported, not a precedence violation). */
    repeats: string[];
    /** Median time between two releases of the chain's first module within one activation, in ms. */
    medianPeriodMs: number;
    /** Every time between two releases of the chain's first module within one activation, in ms, in order. */
    gapsMs: number[];
}

/**
 * Checks that a periodic chain A -> B -> C ... is released in precedence order: in the merged
 * timeline of run_started/run_finished of the chain's modules, a module starts only after its
 * predecessor in the chain finished in the same cycle (a cycle begins when the head starts), and
 * never while another module of the chain runs. A cycle may be cut short when its schema is
 * deactivated; the next cycle starts again at the head.
 */
export function checkChain(records: LogRecord[], chain: string[]): ChainReport {
    // ORD's `activate` records split the timeline into activation windows: the time between two
    // windows (the schema was inactive) is not a period.
    const isActivation = (r: LogRecord) => r.module === 'ORD' && r.event === 'scheduler' && r.detail.startsWith('activate ');
    const timeline = records.filter((r) => isActivation(r) || (chain.includes(r.module) && (r.event === 'run_started' || r.event === 'run_finished')));
    const violations: string[] = [];
    const repeats: string[] = [];
    let finished = new Set<string>(); // modules of the chain that finished in this cycle
    let started = new Set<string>();
    let running: string | null = null;
    let completeCycles = 0;
    const gaps: number[] = [];
    let lastHead: bigint | null = null;
    for (const r of timeline) {
        if (isActivation(r)) { lastHead = null; continue; }
        const index = chain.indexOf(r.module);
        if (r.event === 'run_started') {
            if (index === 0) {
                if (lastHead !== null) gaps.push(Number(r.mono - lastHead) / 1e6);
                lastHead = r.mono;
                finished = new Set();
                started = new Set();
                running = null;
            } else if (!finished.has(chain[index - 1]!) || running !== null) {
                violations.push(`${r.module} started at ${r.mono} before ${chain[index - 1]} finished in its cycle (running: ${running ?? 'none'})`);
            }
            if (started.has(r.module)) repeats.push(`${r.module} started twice in the cycle at ${r.mono}`);
            started.add(r.module);
            running = r.module;
        } else if (r.module === running) {
            running = null;
            if (index === chain.length - 1 && !finished.has(r.module)) completeCycles++;
            finished.add(r.module);
        }
    }
    const sorted = [...gaps].sort((a, b) => a - b);
    return { completeCycles, violations, repeats, medianPeriodMs: sorted.length ? sorted[Math.floor(sorted.length / 2)]! : NaN, gapsMs: gaps };
}

/** How many values `consumer` received on its input `port` from `producer`. */
export function received(records: LogRecord[], consumer: string, port: number, producer: string): number {
    return records.filter((r) => r.module === consumer && r.event === 'data_received' && r.peer === producer && r.port === String(port)).length;
}

export function runs(records: LogRecord[], module: string): number {
    return records.filter((r) => r.module === module && r.event === 'run_started').length;
}

/** The `supervisor` records of a supervisor (rule active/inactive, function started/stopped), in order. */
export function supervisorTrace(records: LogRecord[], supervisor: string): string[] {
    return records.filter((r) => r.module === supervisor && r.event === 'supervisor').map((r) => r.detail);
}

/** True when `expected` appears in `trace` in this order (other entries may come between). */
export function isSubsequence(trace: string[], expected: string[]): boolean {
    let i = 0;
    for (const entry of trace) if (i < expected.length && entry === expected[i]) i++;
    return i === expected.length;
}

export interface DeliveryWindow {
    /** k of the subscription (`periodicity=k` of the `subscribed` record). */
    periodicity: number;
    /** Activations of the producer while the subscription held. */
    activations: number;
    /** Values it posted to the consumer's port in that time. */
    posted: number;
    /**
     * The subscription came while the producer was running (between two states of a run: the
     * generated loop handles requests there): that run's post may go to it, though its start is
     * not counted in `activations`.
     */
    midRun: boolean;
}

/**
 * For each subscription of `consumer` to the producer's output `port` (one per schema activation,
 * from `subscribed` to `unsubscribed` in the producer's log): its periodicity k, how many times the
 * producer ran and how many values it posted to that consumer; expected posted = floor(activations / k).
 */
export function deliveryWindows(records: LogRecord[], producer: string, port: number, consumer: string): DeliveryWindow[] {
    const windows: DeliveryWindow[] = [];
    let open: DeliveryWindow | null = null;
    let running = false;
    for (const r of records) {
        if (r.module !== producer) continue;
        if (r.event === 'run_started') running = true;
        else if (r.event === 'run_finished') running = false;
        const ours = r.peer === consumer && r.port === String(port);
        if (r.event === 'subscribed' && ours) {
            open = { periodicity: Number(/periodicity=(\d+)/.exec(r.detail)?.[1] ?? NaN), activations: 0, posted: 0, midRun: running };
            windows.push(open);
        } else if (r.event === 'unsubscribed' && ours) {
            open = null;
        } else if (open && r.event === 'run_started') {
            open.activations++;
        } else if (open && r.event === 'data_posted' && ours) {
            open.posted++;
        }
    }
    return windows;
}

/** The scheduler's own trace lines (activate/deactivate, deadline misses, overruns). */
export function schedulerTrace(records: LogRecord[]): string[] {
    return records.filter((r) => r.module === 'ORD' && r.event === 'scheduler').map((r) => r.detail);
}

/** The records logged while `schema` was active (from ORD's `activate S` to its `deactivate S`). */
export function whileActive(records: LogRecord[], schema: string): LogRecord[] {
    const out: LogRecord[] = [];
    let active = false;
    for (const r of records) {
        if (r.module === 'ORD' && r.event === 'scheduler') {
            // `activate S (activation #N from SUP)`; logs of older versions end at the name
            const names = (what: string) => r.detail === `${what} ${schema}` || r.detail.startsWith(`${what} ${schema} (`);
            if (names('activate')) active = true;
            else if (names('deactivate')) active = false;
        }
        if (active) out.push(r);
    }
    return out;
}
