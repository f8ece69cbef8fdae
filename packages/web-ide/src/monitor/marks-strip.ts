/**
 * The monitor's timeline strip: the whole run on one canvas, a tick per mark (rule changes,
 * schema activations, deadline misses, overruns, function starts/stops, the modules' own records,
 * the run's errors, the events no one received (a port's first), the modules' crashes, the requests a
 * supervisor kept for a full mailbox: when it began and ended)
 * and the time cursor.
 * Clicking or dragging moves the cursor. A canvas: the marks are first binned by pixel column
 * (per row, the latest mark of a column sets its colour, but a crash's stays), then each row is drawn as runs of one
 * colour, so a frame costs at most a few rectangles per column however many marks there are (a
 * 1 kHz schema missing its deadlines for a minute reaches the model's 20,000).
 * Hovering it, its tooltip says the marks under the pointer (markTooltip): a deadline miss names
 * what its cycle was still waiting for.
 */
import type { Mark } from './model-view.js';
import { marksIn } from './model-view.js';
import { fmtT } from './panel-text.js';
import { visibleText } from '@contract-studio/conventions';

/** Colours by index (0: no mark); a rule switched off is grey. */
const PALETTE = ['', '#98c379', '#5c6370', '#61afef', '#e06c75', '#d19a66', '#c678dd', '#e5c07b', '#ff6ac1', '#56b6c2', '#ffffff'];
const COLOR: Record<Mark['kind'], number> = { rule: 1, schema: 3, miss: 4, late: 4, overrun: 5, function: 6, user: 7, error: 8, unheard: 8, kept: 9, waited: 9, crash: 10 };
const RULE_OFF = 2;
const ROW: Record<Mark['kind'], number> = { function: 0, user: 0, error: 0, unheard: 0, kept: 0, waited: 0, crash: 0, rule: 1, schema: 2, miss: 3, late: 3, overrun: 3 };
const ROWS = 4;
/** Marks a tooltip names (the rest counted), and how far from the pointer a mark is under it (px). */
const TOOLTIP_MARKS = 6;
const TOOLTIP_PX = 3;

/** The tooltip of the marks `under` the pointer: one line each, `+2.210000 s velocityLoop: deadline miss (ORD:0) cycle 220 (not finished: VEL)`. */
export function markTooltip(under: readonly Mark[]): string {
  // a mark's place and label say a record's names and values: written visibly (conventions' visibleText)
  const lines = under.slice(0, TOOLTIP_MARKS).map((m) => `${fmtT(m.t)} ${visibleText(`${m.where}: ${m.label}`)}`);
  if (under.length > TOOLTIP_MARKS) lines.push(`… and ${under.length - TOOLTIP_MARKS} more mark(s) here`);
  return lines.join('\n');
}

export class MarksStrip {
  readonly canvas: HTMLCanvasElement;
  /** The canvas's CSS width, kept by a ResizeObserver: reading clientWidth while drawing would force a layout every frame. */
  private width = 600;
  /** Colour index per row and pixel column, reused from frame to frame. */
  private bins = new Uint8Array(0);
  /** What the last draw showed (the tooltip reads it). */
  private shown: { marks: readonly Mark[]; end: number; w: number } = { marks: [], end: 0, w: 600 };

  constructor(onSeek: (fraction: number) => void) {
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'monitor-strip';
    this.canvas.height = 44;
    this.canvas.setAttribute('role', 'img');
    this.canvas.setAttribute('aria-label', 'Run timeline: function starts and stops (purple), the modules\' own records (yellow), errors and events no one received (pink), module crashes (white), requests kept for a full mailbox and their end (cyan), rule changes (green), schema activations (blue), deadline misses and cycles ORD itself released past their CRITICAL_DELAY (red), overruns (orange); click to move the cursor');
    let dragging = false;
    const seek = (e: PointerEvent) => {
      const r = this.canvas.getBoundingClientRect();
      onSeek(Math.min(1, Math.max(0, (e.clientX - r.left) / Math.max(1, r.width))));
    };
    this.canvas.addEventListener('pointerdown', (e) => {
      dragging = true;
      this.canvas.setPointerCapture?.(e.pointerId);
      seek(e);
    });
    this.canvas.addEventListener('pointermove', (e) => (dragging ? seek(e) : this.hover(e)));
    this.canvas.addEventListener('pointerup', () => (dragging = false));
    new ResizeObserver((entries) => (this.width = Math.floor(entries[0]?.contentRect.width || this.width))).observe(this.canvas);
  }

  /** The tooltip: the marks within TOOLTIP_PX of the pointer (read when it moves, not at every frame). */
  private hover(e: PointerEvent): void {
    const { marks, end, w } = this.shown;
    const r = this.canvas.getBoundingClientRect();
    const px = ((e.clientX - r.left) / Math.max(1, r.width)) * w;
    const span = Math.max(1, end);
    const tOf = (x: number) => ((x - 1) / (w - 3)) * span;
    const under = marksIn(marks, tOf(px - TOOLTIP_PX), tOf(px + TOOLTIP_PX));
    const title = under.length ? markTooltip(under) : '';
    if (this.canvas.title !== title) this.canvas.title = title;
  }

  draw(marks: readonly Mark[], end: number, cursor: number): void {
    const c = this.canvas;
    const w = Math.max(100, this.width);
    const shown = this.shown;
    shown.marks = marks;
    shown.end = end;
    shown.w = w;
    if (c.width !== w) c.width = w;
    const ctx = c.getContext('2d');
    if (!ctx) return;
    ctx.clearRect(0, 0, w, c.height);
    const span = Math.max(1, end);
    const x = (t: number) => 1 + (t / span) * (w - 3);
    ctx.fillStyle = '#20242c';
    ctx.fillRect(0, 0, w, c.height);
    const bins = this.bins.length === ROWS * w ? this.bins.fill(0) : (this.bins = new Uint8Array(ROWS * w));
    for (const m of marks) {
      const col = Math.floor(x(m.t));
      const at = ROW[m.kind] * w + col;
      // a crash keeps its column: the errors that follow it (requests to the dead module) would hide it
      if (col >= 0 && col < w && bins[at] !== COLOR.crash) bins[at] = m.kind === 'rule' && m.on === false ? RULE_OFF : COLOR[m.kind];
    }
    for (let row = 0; row < ROWS; row++) {
      const base = row * w;
      for (let i = 0; i < w; ) {
        const colour = bins[base + i]!;
        let j = i + 1;
        while (j < w && bins[base + j] === colour) j++;
        if (colour) {
          ctx.fillStyle = PALETTE[colour]!;
          ctx.fillRect(i, 3 + row * 10, j - i + 1, 8); // a mark is 2 px wide
        }
        i = j;
      }
    }
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(Math.floor(x(Math.min(cursor, span))), 0, 2, c.height);
  }
}
