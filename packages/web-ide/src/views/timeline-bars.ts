/**
 * The bars of one Timeline lane, for the part of it on screen: a long run has hundreds of thousands
 * of activations (a 1 kHz schema, 60 s, four modules: 240,000), far more than an SVG can hold or
 * a screen can show. Activations closer than a pixel are drawn as one bar that says how many it
 * holds; only the bars within the visible range are made. Pure: used by timeline-view.ts and tests.
 */
import type { Activation } from './activation-log.js';

export interface LaneBar {
  x1: number;
  x2: number;
  /** Activations drawn as this bar (1: a single activation). */
  count: number;
  first: Activation;
  last: Activation;
  /** One of them was still running when its log stopped. */
  open: boolean;
}

/** Index of the first activation of `acts` (sorted by start) that starts at or after `t`. */
export function firstStartingAt(acts: readonly Activation[], t: number): number {
  let lo = 0;
  let hi = acts.length;
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (acts[mid]!.start < t) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/** The latest end (or start, for one still running) of `acts`, without spreading them as arguments. */
export function lastTime(acts: readonly Activation[]): number {
  let t = -Infinity;
  for (const a of acts) t = Math.max(t, a.end ?? a.start);
  return t;
}

/**
 * Bars of one module's activations `acts` (sorted by start) between pixels `fromPx` and `toPx`,
 * with `x` mapping a time to a pixel and `tEnd` the end drawn for an activation still running.
 * A bar is at least `minWidth` wide; an activation starting within a pixel of the bar before it
 * joins that bar.
 */
export function laneBars(
  acts: readonly Activation[],
  x: (t: number) => number,
  invX: (px: number) => number,
  tEnd: number,
  fromPx: number,
  toPx: number,
  minWidth = 2,
): LaneBar[] {
  const bars: LaneBar[] = [];
  // a module's activations do not overlap (its next run_started ends the one before): only the
  // one before the first that starts in the range can reach into it
  let i = Math.max(0, firstStartingAt(acts, invX(fromPx)) - 1);
  let bar: LaneBar | undefined;
  for (; i < acts.length; i++) {
    const a = acts[i]!;
    const x1 = x(a.start);
    if (x1 > toPx) break;
    const x2 = Math.max(x1 + minWidth, x(a.end ?? tEnd));
    if (x2 < fromPx) continue;
    if (bar && x1 <= bar.x2 + 1) {
      bar.x2 = Math.max(bar.x2, x2);
      bar.count++;
      bar.last = a;
      bar.open ||= a.end === undefined;
    } else {
      bar = { x1, x2, count: 1, first: a, last: a, open: a.end === undefined };
      bars.push(bar);
    }
  }
  return bars;
}

/**
 * The Timeline's lanes: the modules the activations name, sorted, `max` at most, and each one's
 * activations in the order given; what a module past them had is counted, not drawn.
 */
export function lanesOf(acts: readonly Activation[], max: number): { modules: string[]; lanes: Activation[][]; leftOutModules: number; leftOutActs: number } {
  const named = [...new Set(acts.map((a) => a.module))].sort();
  const modules = named.slice(0, max);
  const laneOf = new Map(modules.map((m, i) => [m, i]));
  const lanes = modules.map((): Activation[] => []);
  let leftOutActs = 0;
  for (const a of acts) {
    const i = laneOf.get(a.module);
    if (i === undefined) leftOutActs++;
    else lanes[i]!.push(a);
  }
  return { modules, lanes, leftOutModules: named.length - modules.length, leftOutActs };
}
