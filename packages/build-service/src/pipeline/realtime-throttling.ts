/**
 * Whether a real-time run was throttled by its job's real-time CPU budget (docs/sandbox.md
 * "Real-time mode": `cpu.rt_runtime_us` per `cpu.rt_period_us`), read from ORD's CSV log. The
 * kernel counts no real-time throttling in cgroup v1 (`cpu.stat` counts the CFS quota only), so
 * it is recognised by what it does: once the architecture has used its budget in a period, nothing
 * of it runs until the period ends, so ORD — which writes a record at every release — is silent
 * until then, and each such silence ends at the same point of the budget's period (the kernel's
 * period timer). Silences of a loaded machine end anywhere.
 */
import { MinHeap } from '../trace/min-heap.js';

/** How to give a throttled architecture more: the budget is per CPU, and fixed (REALTIME_BOUNDS). */
export const THROTTLED_ADVICE = 'Give it more CPUs to share it (contract run --cpus 0,1: the budget is on each CPU), or do not pin it (no --cpus); ' +
  'the budget itself is the build service\'s REALTIME_BOUNDS.cpuRuntimeUs (docs/sandbox.md "Real-time mode")';

/** A silence of ORD this long or more is looked at (a 1 kHz schema's ORD writes every millisecond). */
const SILENCE_NS = 3_000_000;
/** Bins of the phase in the period where silences end, and the window of bins around the commonest. */
const PHASE_BIN_NS = 500_000;
const PHASE_WINDOW_BINS = 2;
/** Silences ending in that window: at least this many, and at least this share of all silences. */
const MIN_THROTTLES = 3;
const MIN_SHARE = 0.5;

export interface Throttling {
  /** Silences of ORD that ended at the budget's period boundary. */
  times: number;
  /** Their length in all (from ORD's last record before each to its first after: about the time throttled). */
  totalNs: number;
  /** Silences of ORD of SILENCE_NS or more, wherever they ended. */
  silences: number;
}

/**
 * Records held to put ORD's lines in time order before their silences are measured: a log is in
 * time order but for two threads writing within a millisecond (log-clock.ts BACK_TOLERANCE_NS).
 */
const REORDER = 1024;

/**
 * Reads ORD's CSV log as it is given, chunk by chunk (`add`), in bounded memory whatever its size
 * (a 256 MiB log is millions of records): each line's first field, mono_ns, read in place from the
 * bytes (a line whose first field is not 1 to 19 digits, the header, is skipped), the times put in order
 * through a window of REORDER records, and each silence of SILENCE_NS or more counted in the bin
 * of the period's phase where it ended, with its length: no text of the log, no list of its times.
 */
export class ThrottlingReader {
  private readonly bins: number;
  /** Silences ending in each bin, and their length in all. */
  private readonly count: Uint32Array;
  private readonly totalNs: Float64Array;
  private silences = 0;
  /** The times read and not yet measured (the lowest goes first). */
  private readonly pending = new MinHeap<number>((a, b) => a < b);
  private last = -1;
  /** The line being read: its first field's value and digits so far, or past its first field (`skipping` to its end). */
  private value = 0;
  private digits = 0;
  private skipping = false;

  constructor(private readonly periodNs: number) {
    this.bins = Math.max(1, Math.round(periodNs / PHASE_BIN_NS));
    this.count = new Uint32Array(this.bins);
    this.totalNs = new Float64Array(this.bins);
  }

  /** The next bytes of the log (a line may go on in the next chunk). */
  add(chunk: Uint8Array): void {
    const n = chunk.length;
    for (let i = 0; i < n;) {
      if (this.skipping) {
        const nl = chunk.indexOf(10, i);
        if (nl < 0) return;
        this.skipping = false;
        this.value = 0;
        this.digits = 0;
        i = nl + 1;
        continue;
      }
      const c = chunk[i++]!;
      if (c >= 48 && c <= 57) {
        this.value = this.value * 10 + (c - 48);
        this.digits++;
        continue;
      }
      // a 64-bit time, past 2^53 on a machine up for 105 days: a double then rounds it to a few ns, nothing to silences of milliseconds
      if (c === 44 /* , */ && this.digits > 0 && this.digits <= 19) this.time(this.value);
      if (c === 10) {
        // a line with no comma: the next one begins
        this.value = 0;
        this.digits = 0;
      } else this.skipping = true;
    }
  }

  private time(t: number): void {
    this.pending.push(t);
    if (this.pending.size > REORDER) this.measure(this.pending.pop()!);
  }

  /** The next time in order: the silence before it, when long enough, counted. */
  private measure(t: number): void {
    const last = this.last;
    this.last = t;
    if (last < 0) return; // the first time: no silence before it
    const ns = t - last;
    if (ns < SILENCE_NS) return;
    const bin = Math.floor((t % this.periodNs) / PHASE_BIN_NS) % this.bins;
    this.silences++;
    this.count[bin]!++;
    this.totalNs[bin]! += ns;
  }

  /**
   * How often the log shows the run throttled by a real-time budget of the period, or undefined
   * when it does not: MIN_THROTTLES or more silences of ORD of SILENCE_NS or more that end within
   * 1 ms of one point of the period, and at least half of all its silences.
   */
  result(): Throttling | undefined {
    while (this.pending.size) this.measure(this.pending.pop()!);
    const { bins, count } = this;
    const near = (c: number, add: (bin: number) => number): number => {
      let n = 0;
      for (let d = -PHASE_WINDOW_BINS; d <= PHASE_WINDOW_BINS; d++) n += add((c + d + bins) % bins);
      return n;
    };
    let best = 0, bestBin = 0;
    for (let c = 0; c < bins; c++) {
      const n = near(c, (bin) => count[bin]!);
      if (n > best) [best, bestBin] = [n, c];
    }
    if (best < MIN_THROTTLES || best < MIN_SHARE * this.silences) return undefined;
    // the bins within the window of the commonest (each once, whatever the number of bins)
    const window = new Set<number>();
    near(bestBin, (bin) => (window.add(bin), 0));
    let times = 0, totalNs = 0;
    for (const bin of window) {
      times += count[bin]!;
      totalNs += this.totalNs[bin]!;
    }
    return { times, totalNs, silences: this.silences };
  }
}

/** ORD's whole log (`ordLog`, its CSV bytes or text) read by a ThrottlingReader for a budget of period `periodNs`. */
export function budgetThrottling(ordLog: Uint8Array | string, periodNs: number): Throttling | undefined {
  const reader = new ThrottlingReader(periodNs);
  reader.add(typeof ordLog === 'string' ? Buffer.from(ordLog) : ordLog);
  return reader.result();
}

/**
 * The run's warning (one of the job's `warnings`, and a `warning: ...` line of its run): `the architecture was throttled by its real-time CPU budget about 149 times
 * (3.52 s in all): ...`, with the budget and how to give it more.
 */
export function throttlingWarning(t: Throttling, runtimeUs: number, periodUs: number): string {
  return `the architecture was throttled by its real-time CPU budget about ${t.times} times (${(t.totalNs / 1e9).toFixed(2)} s in all): ` +
    `the sandbox gives the whole architecture ${runtimeUs / 1000} ms of each ${periodUs / 1000} ms on each CPU, and it used them up; ` +
    `nothing of it ran for the rest of those periods (ORD silent, ending each time at the same point of the period), so ORD's missed ticks ` +
    `and the deadline misses then are the budget's, not the modules'. ${THROTTLED_ADVICE}`;
}
