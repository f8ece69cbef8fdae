/**
 * Each released module's CPU time per release, from its `run_finished` records' `cpu_ns` (the CPU
 * time of the module's own thread during the run: docs/runtime-api.md "Trace records"): how many
 * releases, the max and p99, and the release that took the max — its schema and cycle, and its share
 * of that schema's PERIOD. The figure for sizing a period and a CRITICAL_DELAY from the worst-case
 * execution time of a module's exec region, which ORD's `response_ns` (tick to ORD's read of the
 * ack: waiting included) is not. Only the runs ORD released and the module ended with ACK_FINISHED
 * count: ORD's and the supervisors' own runs (their whole life: engine-cpu.ts tells them) and runs a
 * STOP ended are none. A release whose `cpu_ns` is -1 (its thread's CPU clock could not be read) is
 * in no quantile: the module's line counts it as a release without a CPU time.
 */
import { DurationQuantiles } from './duration-quantiles.js';
import { durationText } from './duration-text.js';
import { hasWordIn } from './field-checks.js';
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** One module's figure, as `contract run --format json` gives it (its `moduleCpu`). */
export interface ModuleCpuFigure {
    module: string;
    /** Its releases whose run_finished said a CPU time. */
    releases: number;
    /** Its releases whose run_finished said `cpu_ns=-1` (the thread's CPU clock could not be read): in no figure below; absent when none. */
    releasesWithoutCpu?: number;
    /** The figures of the releases that said a CPU time: absent when none did. */
    maxNs?: number;
    p99Ns?: number;
    /** The release that took maxNs (the first such). */
    maxSchema?: string;
    maxCycle?: number;
    /** That schema's PERIOD, from the ticks of two of its cycles ORD released (absent when it released one cycle only). */
    periodNs?: number;
    /** maxNs / periodNs. */
    maxShareOfPeriod?: number;
}

/** Modules and schemas followed at most (a forged log could name any number). */
const FOLLOWED = 4096;

interface Released { schema: string; cycle: number }
interface Cpu { q: DurationQuantiles; maxAt?: Released; unknown: number }

export class ModuleCpu {
    /** Each module's last release by ORD (ORD writes its `ord_release` before it sends it). */
    private readonly released = new Map<string, Released>();
    /** Per schema: the tick of the last cycle seen, and the PERIOD two cycles' ticks gave. */
    private readonly ticks = new Map<string, { cycle: number; tickNs: number; periodNs?: number }>();
    private readonly cpu = new Map<string, Cpu>();

    see(k: KnownRecord): void {
        if (k.kind === 'ord_release') this.release(k);
        else if (k.kind === 'run_finished') this.finished(k);
    }

    private release(k: KnownRecord): void {
        const schema = k.fields['schema'], cycle = k.fields['cycle'], tick = k.fields['tick_ns'];
        if (typeof schema !== 'string' || typeof cycle !== 'number') return;
        if (this.released.has(k.peer) || this.released.size < FOLLOWED) this.released.set(ownString(k.peer), { schema: ownString(schema), cycle });
        if (typeof tick !== 'number') return;
        const t = this.ticks.get(schema);
        if (t && cycle > t.cycle && tick > t.tickNs) t.periodNs = Math.round((tick - t.tickNs) / (cycle - t.cycle));
        if (t) {
            t.cycle = cycle;
            t.tickNs = tick;
        } else if (this.ticks.size < FOLLOWED) this.ticks.set(ownString(schema), { cycle, tickNs: tick });
    }

    private finished(k: KnownRecord): void {
        const r = this.released.get(k.module);
        if (!r) return; // not released by ORD: a START of a supervisor or a control tool, or ORD's and a supervisor's own run
        this.released.delete(k.module);
        const ns = k.fields['cpu_ns'];
        if (typeof ns !== 'number' || !hasWordIn(k.detail, 'ACK_FINISHED')) return; // logs of older versions; a release a STOP ended
        let c = this.cpu.get(k.module);
        if (!c) {
            if (this.cpu.size >= FOLLOWED) return;
            this.cpu.set(ownString(k.module), (c = { q: new DurationQuantiles(), unknown: 0 }));
        }
        if (ns < 0) { // -1: the thread's CPU clock could not be read (mailbox.c)
            c.unknown++;
            return;
        }
        if (ns > c.q.maxNs || c.q.count === 0) c.maxAt = r;
        c.q.add(ns);
    }

    /** The modules' figures, in name order. */
    figures(): ModuleCpuFigure[] {
        return [...this.cpu].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)).map(([module, c]) => {
            const f: ModuleCpuFigure = { module, releases: c.q.count };
            if (c.unknown) f.releasesWithoutCpu = c.unknown;
            if (!c.maxAt) return f;
            Object.assign(f, { maxNs: c.q.maxNs, p99Ns: c.q.quantileNs(0.99), maxSchema: c.maxAt.schema, maxCycle: c.maxAt.cycle });
            const periodNs = this.ticks.get(c.maxAt.schema)?.periodNs;
            if (periodNs) {
                f.periodNs = periodNs;
                f.maxShareOfPeriod = c.q.maxNs / periodNs;
            }
            return f;
        });
    }

    /**
     * `module CTL: CPU per release max 1.25 ms (velocityLoop cycle 412, 12.5 % of its PERIOD 10 ms),
     * p99 1.1 ms, 5,000 releases`, one line per module ORD released whose runs said their CPU time;
     * `, 3 releases without a CPU time` after it when some said `cpu_ns=-1` (a module none of whose
     * releases said one: `module CTL: 3 releases without a CPU time (its thread's CPU clock could not be read)`).
     */
    lines(): string[] {
        return this.figures().map((f) => {
            const unknown = f.releasesWithoutCpu ? `${count(f.releasesWithoutCpu)} without a CPU time` : '';
            if (f.maxNs === undefined) return `module ${f.module}: ${unknown} (its thread's CPU clock could not be read)`;
            const share = f.periodNs ? `, ${shareText(f.maxShareOfPeriod!)} of its PERIOD ${durationText(f.periodNs)}` : '';
            return `module ${f.module}: CPU per release max ${durationText(f.maxNs)} (${f.maxSchema} cycle ${f.maxCycle}${share}), p99 ${durationText(f.p99Ns!)}, ${count(f.releases)}${unknown ? `, ${unknown}` : ''}`;
        });
    }
}

/** `1 release`, `5,000 releases`. */
function count(n: number): string {
    return `${n.toLocaleString('en-US')} release${n === 1 ? '' : 's'}`;
}

/** `12.5 %`, `0.04 %`: a share with 3 significant digits at most. */
function shareText(share: number): string {
    return `${+(share * 100).toPrecision(3)} %`;
}
