/**
 * ORD's and each supervisor's own CPU time, from their runs' `run_finished` records' `cpu_ns` (the
 * CPU time of the thread that read the run's START, from its `run_started` to its `run_finished`:
 * docs/runtime-api.md "Trace records"). An engine's run is its working life — ORD releasing the
 * schemas' cycles, a supervisor evaluating its rules — ended by the STOP or KILL of the run's end,
 * so the sum of its runs' CPU over the sum of their lengths is the share of one CPU the engine took
 * while it worked: what it leaves to the modules. The runtime's log writer thread is not in it.
 * A module is a supervisor when it wrote a `supervisor` record; ORD is the module named ORD. A
 * simulation measures no engine's CPU: nothing is told of it.
 */
import { durationText } from './duration-text.js';
import { ownString } from './parse.js';
import type { KnownRecord } from './records.js';

/** One engine's figure, as `contract run --format json` gives it (its `engineCpu`). */
export interface EngineCpuFigure {
    module: string;
    role: 'scheduler' | 'supervisor';
    /** Its runs that ended with a CPU time. */
    runs: number;
    /** Their CPU time, summed. */
    cpuNs: number;
    /** Their length (run_started to run_finished), summed. */
    runNs: number;
    /** cpuNs / runNs: the share of one CPU (absent when runNs is 0). */
    shareOfCpu?: number;
    /** Its runs whose run_finished said `cpu_ns=-1` (the thread's CPU clock could not be read): in no figure above; absent when none. */
    runsWithoutCpu?: number;
}

/** Modules followed at most (a forged log could name any number). */
const FOLLOWED = 4096;

interface Own { runs: number; cpuNs: number; runNs: number; unknown: number; startedNs?: number }

export class EngineCpu {
    private readonly supervisors = new Set<string>();
    private readonly own = new Map<string, Own>();
    private simulation = false;

    /** The records are a simulation's: its engines' CPU is not measured, no figure is told. */
    simulated(): void {
        this.simulation = true;
    }

    see(k: KnownRecord): void {
        if (k.kind === 'supervisor') {
            if (this.supervisors.size < FOLLOWED) this.supervisors.add(ownString(k.module));
        } else if (k.kind === 'run_started') {
            const o = this.entry(k.module);
            if (o) o.startedNs = Number(k.monoNs);
        } else if (k.kind === 'run_finished') this.finished(k);
    }

    private entry(module: string): Own | undefined {
        let o = this.own.get(module);
        if (!o && this.own.size < FOLLOWED) this.own.set(ownString(module), (o = { runs: 0, cpuNs: 0, runNs: 0, unknown: 0 }));
        return o;
    }

    private finished(k: KnownRecord): void {
        const o = this.own.get(k.module), ns = k.fields['cpu_ns'];
        if (!o || o.startedNs === undefined) return; // no start read: not a run this reader can measure
        const startedNs = o.startedNs;
        o.startedNs = undefined;
        if (typeof ns !== 'number') return; // logs of older versions
        if (ns < 0) {
            o.unknown++;
            return;
        }
        o.runs++;
        o.cpuNs += ns;
        o.runNs += Math.max(0, Number(k.monoNs) - startedNs);
    }

    /** ORD's figure first, then the supervisors' in name order. */
    figures(): EngineCpuFigure[] {
        if (this.simulation) return [];
        const role = (m: string) => (m === 'ORD' ? 'scheduler' : this.supervisors.has(m) ? 'supervisor' : undefined);
        return [...this.own]
            .filter(([m, o]) => role(m) && (o.runs || o.unknown))
            .sort(([a], [b]) => (a === 'ORD' ? -1 : b === 'ORD' ? 1 : a < b ? -1 : a > b ? 1 : 0))
            .map(([module, o]) => {
                const f: EngineCpuFigure = { module, role: role(module)!, runs: o.runs, cpuNs: o.cpuNs, runNs: o.runNs };
                if (o.runNs > 0) f.shareOfCpu = o.cpuNs / o.runNs;
                if (o.unknown) f.runsWithoutCpu = o.unknown;
                return f;
            });
    }

    /**
     * `ORD (scheduler): own CPU 586 µs in 1 run of 1.981 s (0.0296 % of one CPU)`, then one such
     * line per supervisor (`supervisor SUP: own CPU ...`), `, 1 run without a CPU time` after it when
     * a run said `cpu_ns=-1`.
     */
    lines(): string[] {
        return this.figures().map((f) => {
            const who = f.role === 'scheduler' ? `${f.module} (scheduler)` : `supervisor ${f.module}`;
            const unknown = f.runsWithoutCpu ? `${runs(f.runsWithoutCpu)} without a CPU time` : '';
            if (!f.runs) return `${who}: ${unknown} (its thread's CPU clock could not be read)`;
            const share = f.shareOfCpu !== undefined ? ` (${+(f.shareOfCpu * 100).toPrecision(3)} % of one CPU)` : '';
            return `${who}: own CPU ${durationText(f.cpuNs)} in ${runs(f.runs)} of ${durationText(f.runNs)}${share}${unknown ? `, ${unknown}` : ''}`;
        });
    }
}

/** `1 run`, `3 runs`. */
function runs(n: number): string {
    return `${n.toLocaleString('en-US')} run${n === 1 ? '' : 's'}`;
}
