/**
 * Draws a periodic schema's response-time histogram (the model's log buckets, monitor-state.ts)
 * on a canvas, against its CRITICAL_DELAY (red line: beyond it ORD sends ORD:0) and PERIOD
 * (grey line), over four decades around CRITICAL_DELAY. When the two are one (PERIOD =
 * CRITICAL_DELAY, as in a control loop), one line and one label say so. The labels never cover each
 * other nor the other line (histogramMarkers); the canvas's tooltip says both lines with their values.
 */
import { durationText } from '@contract-studio/build-service/trace';
import { bucketStartNs, HIST_BUCKETS, HIST_PER_DECADE, histogramBucket } from './monitor-state.js';

export function drawHistogram(canvas: HTMLCanvasElement, histogram: readonly number[], criticalNs?: number, periodNs?: number): void {
  const ctx = canvas.getContext('2d');
  if (!ctx) return;
  const w = canvas.width;
  const hgt = canvas.height;
  ctx.clearRect(0, 0, w, hgt);
  const ref = criticalNs ?? periodNs ?? 1e6;
  // buckets shown: 3 decades below the reference to 1 above it; the rest clamps to the edges
  const lo = Math.max(0, histogramBucket(ref / 1000));
  const hi = Math.min(HIST_BUCKETS - 1, Math.max(lo, histogramBucket(ref * 10)));
  const n = hi - lo + 1;
  const counts = new Array<number>(n).fill(0);
  histogram.forEach((c, b) => (counts[Math.min(n - 1, Math.max(0, b - lo))]! += c));
  const max = Math.max(1, ...counts);
  const bw = (w - 4) / n;
  const base = hgt - 14;
  ctx.fillStyle = '#61afef';
  counts.forEach((c, i) => {
    if (!c) return;
    const bh = Math.max(1, (Math.log1p(c) / Math.log1p(max)) * (base - 4));
    ctx.fillRect(2 + i * bw, base - bh, Math.max(1, bw - 1), bh);
  });
  const xOf = (ns: number) => 2 + ((Math.log10(ns / bucketStartNs(lo || 1)) * HIST_PER_DECADE) / n) * (w - 4);
  ctx.font = '10px sans-serif';
  const said = [criticalNs ? `red line: CRITICAL_DELAY ${fmtNs(criticalNs)}` : '', periodNs ? `grey line: PERIOD ${fmtNs(periodNs)}` : ''].filter(Boolean).join(' · ');
  if (canvas.title !== said) canvas.title = said;
  for (const m of histogramMarkers(criticalNs, periodNs, xOf, w, (text) => ctx.measureText(text).width)) {
    ctx.fillStyle = m.color;
    ctx.fillRect(Math.round(m.x) - 1, 0, 2, base); // on whole pixels: crisp over the bars
    // on the canvas's own background: readable over the bars
    const y = 10 + m.row * LABEL_ROW_PX;
    ctx.fillStyle = 'rgba(17, 20, 25, 0.85)';
    ctx.fillRect(m.labelX - 1, y - 9, ctx.measureText(m.label).width + 2, 12);
    ctx.fillStyle = m.color;
    ctx.fillText(m.label, m.labelX, y);
  }
  ctx.fillStyle = '#7f8796';
  ctx.fillText(fmtNs(bucketStartNs(lo || 1)), 2, hgt - 2);
  ctx.textAlign = 'right';
  ctx.fillText(fmtNs(bucketStartNs(hi + 1)), w - 2, hgt - 2);
  ctx.textAlign = 'left';
}

export interface HistogramMarker {
  /** The line's x, its colour, and its label's text, left x and row (0: top, 1: under it, LABEL_ROW_PX lower). */
  x: number;
  color: string;
  label: string;
  labelX: number;
  row: number;
}

/** CRITICAL_DELAY's line and label (PERIOD's are grey). */
const CD_COLOR = '#e06c75';
/** Lines closer than this (px) are one line. */
const SAME_LINE_PX = 2;
/** A label's distance from its line, and the least room between two labels or a label and another line (px). */
const LABEL_GAP_PX = 3;
/** From one label row to the next (px): a label's box is 12 px high, 2 px between rows. */
export const LABEL_ROW_PX = 14;
/** Half the width of a drawn line (px). */
const LINE_PX = 1.5;
/** A label's background beyond its text, each side (px; drawHistogram). */
const BG_PX = 1;
/** The short labels, used only when the whole ones find no place (the canvas's tooltip says them whole). */
const SHORT: Record<string, string> = { CRITICAL_DELAY: 'CD', PERIOD: 'P' };

/**
 * The lines of CRITICAL_DELAY (red) and PERIOD (grey) on a histogram `w` px wide (`xOf`: ns -> x;
 * `measure`: a label's width). Equal (or on the same pixels): one red line labelled
 * `PERIOD = CRITICAL_DELAY`. Otherwise each label is whole on the canvas and covers neither the
 * other label nor the other line, whatever the two values: both on the top row, each on the far side
 * of its line (away from the other), when there is room there; else on the near side, beyond the
 * other line, or on the row under it (the nearest such places); only when no place is free do the
 * labels shorten to `CD` and `P` (the canvas's tooltip says them whole).
 */
export function histogramMarkers(criticalNs: number | undefined, periodNs: number | undefined, xOf: (ns: number) => number, w: number, measure: (text: string) => number): HistogramMarker[] {
  const xAt = (ns: number) => Math.min(w - 1, Math.max(1, xOf(ns)));
  const cd = criticalNs || undefined;
  const period = periodNs || undefined;
  const lines: Array<{ x: number; color: string; label: string }> = [];
  if (cd !== undefined && period !== undefined && (cd === period || Math.abs(xAt(cd) - xAt(period)) < SAME_LINE_PX)) {
    lines.push({ x: xAt(cd), color: CD_COLOR, label: cd === period ? 'PERIOD = CRITICAL_DELAY' : 'PERIOD ≈ CRITICAL_DELAY' });
  } else {
    if (period !== undefined) lines.push({ x: xAt(period), color: '#9aa3b2', label: 'PERIOD' });
    if (cd !== undefined) lines.push({ x: xAt(cd), color: CD_COLOR, label: 'CRITICAL_DELAY' });
  }
  return placeLabels(lines, w, measure) ?? placeLabels(lines.map((l) => ({ ...l, label: SHORT[l.label] ?? l.label })), w, measure)
    ?? placeLabels(lines, w, measure, true)!;
}

/** Where a label goes: beside its own line on the far side (away from the other line) or the near side, or beyond the other line. */
type Place = 'far' | 'near' | 'beyond';

/**
 * Each line's label placed (a place and a row) so that no two labels' boxes meet, no label covers
 * another line and each is whole on the canvas; undefined when no such places exist (unless
 * `anyway`: then the first candidate).
 */
function placeLabels(lines: ReadonlyArray<{ x: number; color: string; label: string }>, w: number, measure: (text: string) => number, anyway = false): HistogramMarker[] | undefined {
  const widths = lines.map((l) => measure(l.label));
  const other = (i: number) => lines[1 - i];
  const labelXOf = (i: number, place: Place) => {
    const { x } = lines[i]!;
    const o = other(i);
    // a lone line's far side is its right; the far side of two lines is away from the other
    const farRight = !o || o.x < x;
    if (place === 'beyond') return farRight ? o!.x - LABEL_GAP_PX - widths[i]! : o!.x + LABEL_GAP_PX;
    const right = place === 'far' ? farRight : !farRight;
    return right ? x + LABEL_GAP_PX : x - LABEL_GAP_PX - widths[i]!;
  };
  const places: Place[] = lines.length > 1 ? ['far', 'near', 'beyond'] : ['far', 'near'];
  // CRITICAL_DELAY's label (red: beyond it ORD sends ORD:0) keeps its place before PERIOD's when both cannot
  const weight = (i: number) => (lines[i]!.color === CD_COLOR ? 1.1 : 1);
  const each = lines.map((_, i) => places.flatMap((place, rank) => [0, 1].map((row) => ({ place, row, cost: (rank + row * 2) * weight(i) }))));
  const candidates: Array<Array<{ place: Place; row: number; cost: number }>> = [];
  const combine = (i: number, acc: Array<{ place: Place; row: number; cost: number }>): void => {
    if (i === lines.length) candidates.push(acc);
    else for (const c of each[i]!) combine(i + 1, [...acc, c]);
  };
  combine(0, []);
  // the nearest to their lines, on the fewest rows
  const cost = (c: ReadonlyArray<{ cost: number }>) => c.reduce((n, p) => n + p.cost, 0);
  candidates.sort((a, b) => cost(a) - cost(b));
  const span = (i: number, place: Place) => [labelXOf(i, place) - BG_PX, labelXOf(i, place) + widths[i]! + BG_PX] as const;
  const fits = (c: ReadonlyArray<{ place: Place; row: number }>) => c.every((p, i) => {
    const [x0, x1] = span(i, p.place);
    if (x0 < 0 || x1 > w) return false;
    return lines.every((line, j) => {
      if (j !== i && line.x + LINE_PX >= x0 && line.x - LINE_PX <= x1) return false; // covers another line
      if (j === i || c[j]!.row !== p.row) return true;
      const [o0, o1] = span(j, c[j]!.place);
      return o1 + LABEL_GAP_PX <= x0 || x1 + LABEL_GAP_PX <= o0;
    });
  });
  const chosen = candidates.find(fits) ?? (anyway ? candidates[0] : undefined);
  if (!chosen) return undefined;
  return lines.map((l, i) => ({ x: l.x, color: l.color, label: l.label, labelX: Math.max(1, Math.min(w - 1 - widths[i]!, labelXOf(i, chosen[i]!.place))), row: chosen[i]!.row }));
}

/** A response time as the Monitor shows it: `2.5 ms` (`contract trace`'s words, duration-text.ts). */
export const fmtNs = durationText;

/** `1s`, `10ms`, `500us`, `3ns` (the model's time literals) -> ns. */
export function timeNs(t: string | undefined): number | undefined {
  const m = t?.match(/^([\d.]+)\s*(ns|us|µs|ms|s)$/);
  if (!m) return undefined;
  const v = Number(m[1]) * ({ ns: 1, us: 1e3, 'µs': 1e3, ms: 1e6, s: 1e9 } as Record<string, number>)[m[2]!]!;
  return Number.isFinite(v) && v > 0 ? v : undefined;
}
