/**
 * Whether a real-time run was throttled by its job's real-time CPU budget (docs/sandbox.md
 * "Real-time mode": `cpu.rt_runtime_us` per `cpu.rt_period_us`), read from ORD's CSV log. The
 * kernel counts no real-time throttling in cgroup v1 (`cpu.stat` counts the CFS quota only), so
 * it is recognised by what it does: once the architecture has used its budget in a period, nothing
 * of it runs until the period ends, so ORD — which writes a record at every release — is silent
 * until then, and each such silence ends at the same point of the budget's period (the kernel's
 * period timer). Silences of a loaded machine end anywhere.
 */
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

/** The mono_ns of each record line of a CSV log (its first field; the header and other lines skipped). */
function recordTimes(log: Buffer): number[] {
  const times: number[] = [];
  for (let at = 0; at < log.length;) {
    let end = log.indexOf(10, at); // the bytes, never the whole log as one string: ORD's may be larger than a string can be
    if (end < 0) end = log.length;
    const comma = log.indexOf(44, at);
    if (comma > at && comma < end && comma - at <= 20) {
      const t = Number(log.toString('latin1', at, comma));
      if (Number.isSafeInteger(t) && t >= 0) times.push(t);
    }
    at = end + 1;
  }
  return times;
}

/**
 * How often ORD's log (`ordLog`, its CSV text) shows the run throttled by a real-time budget of
 * period `periodNs`, or undefined when it does not: MIN_THROTTLES or more silences of ORD of
 * SILENCE_NS or more that end within 1 ms of one point of the period, and at least half of all its
 * silences.
 */
export function budgetThrottling(ordLog: Buffer | string, periodNs: number): Throttling | undefined {
  const times = recordTimes(typeof ordLog === 'string' ? Buffer.from(ordLog, 'utf8') : ordLog).sort((a, b) => a - b);
  const bins = Math.max(1, Math.round(periodNs / PHASE_BIN_NS));
  const silences: Array<{ ns: number; bin: number }> = [];
  const count = new Uint32Array(bins);
  for (let i = 1; i < times.length; i++) {
    const ns = times[i]! - times[i - 1]!;
    if (ns < SILENCE_NS) continue;
    const bin = Math.floor((times[i]! % periodNs) / PHASE_BIN_NS) % bins;
    silences.push({ ns, bin });
    count[bin]!++;
  }
  let best = 0, bestBin = 0;
  for (let c = 0; c < bins; c++) {
    let n = 0;
    for (let d = -PHASE_WINDOW_BINS; d <= PHASE_WINDOW_BINS; d++) n += count[(c + d + bins) % bins]!;
    if (n > best) [best, bestBin] = [n, c];
  }
  if (best < MIN_THROTTLES || best < MIN_SHARE * silences.length) return undefined;
  const near = (bin: number) => Math.min((bin - bestBin + bins) % bins, (bestBin - bin + bins) % bins) <= PHASE_WINDOW_BINS;
  const throttled = silences.filter((s) => near(s.bin));
  return { times: throttled.length, totalNs: throttled.reduce((sum, s) => sum + s.ns, 0), silences: silences.length };
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
