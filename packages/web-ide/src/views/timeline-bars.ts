/**
 * The bars of one Timeline lane, for the part of it on screen: a long run has hundreds of thousands
 * of activations (a 1 kHz schema, 60 s, four modules: 240,000), far more than an SVG can hold or
 * a screen can show. Activations closer than a pixel are drawn as one bar that says how many it
 * holds; only the bars within the visible range are made, each with its tooltip (barTitle). Pure:
 * used by timeline-view.ts and tests.
 */
import type { Activation } from './activation-log.js';
import { visibleText } from '@contract-studio/conventions';

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

/** A bar's tooltip (its module, times and the records' words), written visibly (visibleText: a record's `\u202e` as its escape). */
export function barTitle(b: LaneBar, t0: number): string {
  return visibleText(barWords(b, t0), { keepNewlines: true });
}

function barWords(b: LaneBar, t0: number): string {
  const ms = (t: number) => `${((t - t0) / 1e6).toFixed(3)} ms`;
  const a = b.first;
  if (b.count === 1 && a.event) return `${a.module} handled an event from ${a.event.from} at ${ms(a.start)}: ${handlerEnd(a)}`;
  if (b.count === 1) return `${a.module} ${ms(a.start)} → ${a.end !== undefined ? `${((a.end - a.start) / 1e6).toFixed(3)} ms` : 'running'} ${a.detail}${a.gone ? ` · gone at ${ms(a.end!)}: ${a.gone}` : ''}`;
  const end = b.last.end;
  const what = b.first.event && b.last.event ? 'events handled' : 'activations';
  return `${a.module}: ${b.count} ${what} from ${ms(a.start)} to ${end !== undefined ? ms(end) : `${ms(b.last.start)} (running)`} (zoom in to see each)`;
}

/** What the records say of an event handler's end. */
function handlerEnd(a: Activation): string {
  const e = a.event!;
  const took = `${((a.end! - a.start) / 1e6).toFixed(3)} ms`;
  const wrote = e.records ? `, ${e.records} record(s) written` : '';
  if (e.ended) return `handled in ${took}${wrote}`;
  // a log of a runtime that wrote no event_handled: the handler's own records bound it
  if (!e.records) return 'its end is not in the log (no event_handled, no record of the handler): the bar marks the reception';
  return `its end is not in the log (no event_handled): its handler's last record (${e.last}${wrote}) ${took} later`;
}
