/**
 * Draws a periodic schema's response-time histogram (the model's log buckets, monitor-state.ts)
 * on a canvas, against its CRITICAL_DELAY (red line: beyond it ORD sends ORD:0) and PERIOD
 * (grey line), over four decades around CRITICAL_DELAY. When the two are one (PERIOD =
 * CRITICAL_DELAY, as in a control loop), one line and one label say so.
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
  for (const m of histogramMarkers(criticalNs, periodNs, xOf, w, (text) => ctx.measureText(text).width)) {
    ctx.fillStyle = m.color;
    ctx.fillRect(m.x, 0, 1.5, base);
    // on the canvas's own background: readable over the bars
    const y = 10 + m.row * 12;
    ctx.fillStyle = 'rgba(17, 20, 25, 0.85)';
    ctx.fillRect(m.labelX - 1, y - 9, ctx.measureText(m.label).width + 2, 11);
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
  /** The line's x, its colour, and its label's text, left x and row (0: top, 1: under it). */
  x: number;
  color: string;
  label: string;
  labelX: number;
  row: number;
}

/** Lines closer than this (px) are one line. */
const SAME_LINE_PX = 2;

/**
 * The lines of CRITICAL_DELAY (red, top row) and PERIOD (grey, the row under it) on a histogram
 * `w` px wide (`xOf`: ns -> x; `measure`: a label's width). Equal (or on the same pixels): one
 * red line labelled `PERIOD = CRITICAL_DELAY`. A label goes right of its line, or left of it
 * when it would pass the edge; it never covers the line.
 */
export function histogramMarkers(criticalNs: number | undefined, periodNs: number | undefined, xOf: (ns: number) => number, w: number, measure: (text: string) => number): HistogramMarker[] {
  const xAt = (ns: number) => Math.min(w - 1, Math.max(1, xOf(ns)));
  const marker = (ns: number, color: string, label: string, row: number): HistogramMarker => {
    const x = xAt(ns);
    const width = measure(label);
    const labelX = x + 3 + width <= w - 1 ? x + 3 : Math.max(1, x - 3 - width);
    return { x, color, label, labelX, row };
  };
  const cd = criticalNs || undefined;
  const period = periodNs || undefined;
  if (cd !== undefined && period !== undefined && (cd === period || Math.abs(xAt(cd) - xAt(period)) < SAME_LINE_PX)) {
    return [marker(cd, '#e06c75', cd === period ? 'PERIOD = CRITICAL_DELAY' : 'PERIOD ≈ CRITICAL_DELAY', 0)];
  }
  const out: HistogramMarker[] = [];
  if (period !== undefined) out.push(marker(period, '#9aa3b2', 'PERIOD', 1));
  if (cd !== undefined) out.push(marker(cd, '#e06c75', 'CRITICAL_DELAY', 0));
  return out;
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
