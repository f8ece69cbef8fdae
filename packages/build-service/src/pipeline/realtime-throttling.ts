/**
 * Whether a real-time run was throttled by its job's real-time CPU budget (docs/sandbox.md
 * "Real-time mode": `cpu.rt_runtime_us` per `cpu.rt_period_us`), read from ORD's CSV log. The
 * kernel counts no real-time throttling in cgroup v1 (`cpu.stat` counts the CFS quota only), so
 * it is recognised by what it does: once the architecture has used its budget in a period, nothing
 * of it runs until the period ends, so ORD is silent until then, though it has work due — a tick to
 * release, a deadline to tell — and each such silence ends at the same point of the budget's period
 * (the kernel's period timer). Silences of a loaded machine end anywhere; those of an ORD with
 * nothing to do (between the ticks of a 100 ms or 1 s schema) are no throttling, wherever they end.
 */

/** How to give a throttled architecture more: the budget is per CPU, and fixed (REALTIME_BOUNDS). */
export const THROTTLED_ADVICE = 'Give it more CPUs to share it (contract run --cpus 0,1: the budget is on each CPU), or do not pin it (no --cpus); ' +
  'the budget itself is the build service\'s REALTIME_BOUNDS.cpuRuntimeUs (docs/sandbox.md "Real-time mode")';

/** A silence of ORD this long or more is looked at (a 1 kHz schema's ORD writes every millisecond). */
const SILENCE_NS = 3_000_000;
/**
 * A silence counts when ORD had work due this long before it ended, or longer: a tick it released
 * or missed, or a deadline it told, that fell in the silence (an `ord_release`'s `tick_ns`, the tick
 * of a `missed tick of S (cycle k)` line on S's grid of ticks its releases show, an
 * `ord_deadline_miss`'s `tick_ns` + `critical_delay_ns`), read from the records after it.
 */
const DUE_NS = 1_000_000;
/** Bins of the phase in the period where silences end, and the window of bins around the commonest. */
const PHASE_BIN_NS = 500_000;
const PHASE_WINDOW_BINS = 2;
/** Silences ending in that window: at least this many, and at least this share of all silences. */
const MIN_THROTTLES = 3;
const MIN_SHARE = 0.5;
/** Bytes of a line read: its time, its kind and the start of its detail (an ord_release line is under 200). */
const LINE_HELD = 512;

export interface Throttling {
  /** Silences of ORD with work due that ended at the budget's period boundary. */
  times: number;
  /**
   * Their length in all: each from the first work due in it (or ORD's last record before it, if
   * later) to ORD's first record after it, at most what the budget can take of a period (period - runtime).
   */
  totalNs: number;
  /** Silences of ORD of SILENCE_NS or more with work due in them (DUE_NS or more before their end), wherever they ended. */
  silences: number;
}

/**
 * Records held to put ORD's lines in time order before their silences are measured: a log is in
 * time order but for two threads writing within a millisecond (log-clock.ts BACK_TOLERANCE_NS).
 */
const REORDER = 1024;

/**
 * The last REORDER records read, in time order: each of ORD's records as its time (`t`) and when the
 * work it did was due (`due`, Infinity: no time said), in two rings of numbers. A record goes in from
 * the back, past the later ones (a log in order: none), so a log in order costs no search and no
 * object per record; the earliest comes out first, records of one time in the order they were read.
 */
class ReorderWindow {
  private readonly ts = new Float64Array(REORDER + 1);
  private readonly dues = new Float64Array(REORDER + 1);
  private head = 0;
  size = 0;

  /** Puts a record in its place; returns false when the window is over REORDER (take the earliest out). */
  push(t: number, due: number): boolean {
    const { ts, dues } = this;
    const cap = ts.length;
    let j = this.size;
    // shift the records later than t one place back, from the back
    while (j > 0) {
      const prev = (this.head + j - 1) % cap;
      if (ts[prev]! <= t) break;
      const at = (this.head + j) % cap;
      ts[at] = ts[prev]!;
      dues[at] = dues[prev]!;
      j--;
    }
    const at = (this.head + j) % cap;
    ts[at] = t;
    dues[at] = due;
    this.size++;
    return this.size <= REORDER;
  }

  /** The earliest record's time and due, taken out (call only when size > 0). */
  shift(out: { t: number; due: number }): void {
    out.t = this.ts[this.head]!;
    out.due = this.dues[this.head]!;
    this.head = (this.head + 1) % this.ts.length;
    this.size--;
  }
}

const ORD_RELEASE = Buffer.from('ord_release');
const SCHEDULER = Buffer.from('scheduler');
const MISSED_TICK = /^"?missed tick of (\S+) \(cycle (\d+)\)/;
/** Schemas whose grid of ticks is followed (a run has a few; a forged log many). */
const GRIDS_FOLLOWED = 64;
const ORD_DEADLINE_MISS = Buffer.from('ord_deadline_miss');

/** The digits after `key` (`tick_ns=`) in line[from, to), or NaN. */
function numberAfter(line: Uint8Array, from: number, to: number, key: Buffer): number {
  const at = indexIn(line, key, from, to);
  if (at < 0) return NaN;
  let v = 0, digits = 0;
  for (let i = at + key.length; i < to; i++) {
    const c = line[i]!;
    if (c < 48 || c > 57) break;
    v = v * 10 + (c - 48);
    digits++;
  }
  return digits > 0 && digits <= 19 ? v : NaN;
}
const TICK_NS = Buffer.from('tick_ns=');
const CRITICAL_DELAY_NS = Buffer.from('critical_delay_ns=');
const CYCLE = Buffer.from('cycle=');
const SCHEMA = Buffer.from('schema=');

/** Where `key` begins in line[from, to), or -1 (searched within the line only: the chunk it is read in goes on). */
function indexIn(line: Uint8Array, key: Buffer, from: number, to: number): number {
  const first = key[0]!, n = key.length;
  for (let i = from; i + n <= to; i++) {
    if (line[i] !== first) continue;
    let j = 1;
    while (j < n && line[i + j] === key[j]) j++;
    if (j === n) return i;
  }
  return -1;
}

/** line[from, to) as text (a schema's name, a missed tick's line). */
function latin1(line: Uint8Array, from: number, to: number): string {
  return Buffer.from(line.buffer, line.byteOffset + from, to - from).toString('latin1');
}

/** Whether line[from, to) is `word`. */
function fieldIs(line: Uint8Array, from: number, to: number, word: Buffer): boolean {
  if (to - from !== word.length) return false;
  for (let i = 0; i < word.length; i++) if (line[from + i] !== word[i]) return false;
  return true;
}

/** A schema's ticks as its releases show them: a cycle's tick, and the period (0 until two cycles were seen); its name as text and bytes. */
interface Grid {
  name: string;
  bytes: Buffer;
  cycle: number;
  tick: number;
  periodNs: number;
}

/**
 * Reads ORD's CSV log as it is given, chunk by chunk (`add`), in bounded memory whatever its size
 * (a 256 MiB log is millions of records): of each line, its first LINE_HELD bytes, read in place:
 * its first field, mono_ns (a line whose first field is not 1 to 19 digits, the header, is
 * skipped), and for an `ord_release` or `ord_deadline_miss` when its work was due; the records put in
 * order through a window of REORDER records, and each silence of SILENCE_NS or more in which ORD had
 * work due DUE_NS or more before its end counted in the bin of the period's phase where it ended,
 * with its length: no text of the log, no list of its times.
 */
export class ThrottlingReader {
  private readonly bins: number;
  /** Silences ending in each bin, and their length in all. */
  private readonly count: Uint32Array;
  private readonly totalNs: Float64Array;
  private silences = 0;
  /** The records read and not yet measured (the earliest goes first). */
  private readonly pending = new ReorderWindow();
  /** The record taken out of the window to be measured (one object, reused). */
  private readonly next = { t: 0, due: Infinity };
  private last = -1;
  /** The last silence met, while the records after it may still say work was due in it. */
  private open: { from: number; to: number; dueFrom: number } | undefined;
  /** The line being read: its first LINE_HELD bytes. */
  private readonly line = new Uint8Array(LINE_HELD);
  /** The first seven commas of the line being read. */
  private readonly commas = new Int32Array(7);
  private len = 0;
  /** The most a throttled silence can last: the part of a period the budget does not give. */
  private readonly mostNs: number;
  /** Each schema's ticks (a few schemas: found by their name's bytes, no text made of a release line). */
  private readonly grids: Grid[] = [];

  /**
   * `periodNs`: the budget's period; `runtimeNs`: what it gives of each (a silence is counted for
   * at most the rest of the period, periodNs - runtimeNs).
   */
  constructor(private readonly periodNs: number, runtimeNs = 0) {
    this.bins = Math.max(1, Math.round(periodNs / PHASE_BIN_NS));
    this.count = new Uint32Array(this.bins);
    this.totalNs = new Float64Array(this.bins);
    this.mostNs = Math.max(0, periodNs - Math.max(0, runtimeNs));
  }

  /** The next bytes of the log (a line may go on in the next chunk). */
  add(chunk: Uint8Array): void {
    const n = chunk.length;
    for (let i = 0; i < n;) {
      const nl = chunk.indexOf(10, i);
      const end = nl < 0 ? n : nl;
      if (nl >= 0 && this.len === 0) {
        // a whole line in the chunk (the usual case): read in place
        this.endLine(chunk, i, Math.min(end, i + LINE_HELD));
        i = nl + 1;
        continue;
      }
      const take = Math.min(end - i, LINE_HELD - this.len);
      if (take > 0) {
        this.line.set(chunk.subarray(i, i + take), this.len);
        this.len += take;
      }
      if (nl < 0) return;
      this.endHeld();
      i = nl + 1;
    }
  }

  /** The line held (begun in an earlier chunk) is complete. */
  private endHeld(): void {
    const len = this.len;
    this.len = 0;
    this.endLine(this.line, 0, len);
  }

  /** The complete line line[from, len) (its first LINE_HELD bytes): its record, if it is one, taken. */
  private endLine(line: Uint8Array, from: number, len: number): void {
    let value = 0, i = from;
    for (; i < len; i++) {
      const c = line[i]!;
      if (c < 48 || c > 57) break;
      value = value * 10 + (c - 48);
    }
    // a 64-bit time, past 2^53 on a machine up for 105 days: a double then rounds it to a few ns, nothing to silences of milliseconds
    if (i === from || i - from > 19 || i >= len || line[i] !== 44 /* , */) return;
    // fields: mono_ns, wall_time, module, event, peer, port, size, detail
    const commas = this.commas;
    commas[0] = i;
    let found = 1;
    for (let j = i + 1; j < len && found < 7; j++) if (line[j] === 44) commas[found++] = j;
    let due = Infinity;
    if (found === 7) {
      const kindFrom = commas[2]! + 1, kindTo = commas[3]!, detailFrom = commas[6]! + 1;
      if (fieldIs(line, kindFrom, kindTo, ORD_RELEASE)) {
        const tick = numberAfter(line, detailFrom, len, TICK_NS);
        if (Number.isFinite(tick)) due = tick;
        this.followGrid(line, detailFrom, len, tick);
      } else if (fieldIs(line, kindFrom, kindTo, SCHEDULER) && line[detailFrom + (line[detailFrom] === 34 ? 1 : 0)] === 109 /* m */) {
        due = this.missedTickDue(latin1(line, detailFrom, len));
      } else if (fieldIs(line, kindFrom, kindTo, ORD_DEADLINE_MISS)) {
        const tick = numberAfter(line, detailFrom, len, TICK_NS), cd = numberAfter(line, detailFrom, len, CRITICAL_DELAY_NS);
        if (Number.isFinite(tick) && Number.isFinite(cd)) due = tick + cd;
      }
    }
    if (!this.pending.push(value, due)) this.measureNext();
  }

  /** An `ord_release`'s detail, line[from, to) (`schema=S cycle=k tick_ns=T ...`): its schema's grid of ticks followed. */
  private followGrid(line: Uint8Array, from: number, to: number, tick: number): void {
    const at = indexIn(line, SCHEMA, from, to);
    if (at < 0 || at > from + 1) return;
    const nameFrom = at + SCHEMA.length;
    let space = nameFrom;
    while (space < to && line[space] !== 32) space++;
    const cycle = numberAfter(line, from, to, CYCLE);
    if (space >= to || !Number.isFinite(cycle) || !Number.isFinite(tick)) return;
    const g = this.grids.find((x) => fieldIs(line, nameFrom, space, x.bytes));
    if (!g) {
      if (this.grids.length < GRIDS_FOLLOWED) {
        const bytes = Buffer.from(line.subarray(nameFrom, space));
        this.grids.push({ name: bytes.toString('latin1'), bytes, cycle, tick, periodNs: 0 });
      }
      return;
    }
    // a later cycle of the same activation gives the period; cycle 0 again (a new activation) keeps it
    if (cycle > g.cycle && tick > g.tick) g.periodNs = (tick - g.tick) / (cycle - g.cycle);
    g.cycle = cycle;
    g.tick = tick;
  }

  /** When the tick of a `missed tick of S (cycle k)` line was due, on S's grid (Infinity when it is not known). */
  private missedTickDue(detail: string): number {
    const m = MISSED_TICK.exec(detail);
    const g = m ? this.grids.find((x) => x.name === m[1]) : undefined;
    if (!g || g.periodNs <= 0) return Infinity;
    return g.tick + (Number(m![2]) - g.cycle) * g.periodNs;
  }

  /** The earliest record held, measured. */
  private measureNext(): void {
    this.pending.shift(this.next);
    this.measure(this.next.t, this.next.due);
  }

  /** The next record in order: the silence before it, when long enough, opened; the work it did, if due in the open silence, noted. */
  private measure(t: number, due: number): void {
    const last = this.last;
    this.last = t;
    if (last >= 0 && t - last >= SILENCE_NS) {
      this.close();
      this.open = { from: last, to: t, dueFrom: Infinity };
    }
    const o = this.open;
    if (o && due > o.from && due < o.to && due < o.dueFrom) o.dueFrom = due;
  }

  /** The open silence counted, if ORD had work due DUE_NS or more before its end. */
  private close(): void {
    const o = this.open;
    this.open = undefined;
    if (!o || !(o.to - o.dueFrom >= DUE_NS)) return;
    const bin = Math.floor((o.to % this.periodNs) / PHASE_BIN_NS) % this.bins;
    this.silences++;
    this.count[bin]!++;
    this.totalNs[bin]! += Math.min(o.to - o.dueFrom, this.mostNs);
  }

  /**
   * How often the log shows the run throttled by a real-time budget of the period, or undefined
   * when it does not: MIN_THROTTLES or more silences of ORD with work due that end within 1 ms of
   * one point of the period, and at least half of all such silences.
   */
  result(): Throttling | undefined {
    if (this.len > 0) this.endHeld();
    while (this.pending.size) this.measureNext();
    this.close();
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

/** ORD's whole log (`ordLog`, its CSV bytes or text) read by a ThrottlingReader for a budget of `runtimeNs` per period `periodNs`. */
export function budgetThrottling(ordLog: Uint8Array | string, periodNs: number, runtimeNs = 0): Throttling | undefined {
  const reader = new ThrottlingReader(periodNs, runtimeNs);
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
    `nothing of it ran for the rest of those periods (ORD silent with ticks due, ending each time at the same point of the period), so ORD's missed ticks ` +
    `and the deadline misses then are the budget's, not the modules'. ${THROTTLED_ADVICE}`;
}
