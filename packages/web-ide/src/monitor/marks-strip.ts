/**
 * The monitor's timeline strip: the whole run on one canvas, a tick per mark (rule changes,
 * schema activations, deadline misses, overruns, function starts/stops) and the time cursor.
 * Clicking or dragging moves the cursor. A canvas, so 20,000 marks cost one draw per frame.
 */
import type { Mark } from './monitor-model.js';

const COLOR: Record<Mark['kind'], string> = { rule: '#98c379', schema: '#61afef', miss: '#e06c75', overrun: '#d19a66', function: '#c678dd' };
const ROW: Record<Mark['kind'], number> = { function: 0, rule: 1, schema: 2, miss: 3, overrun: 3 };

export class MarksStrip {
  readonly canvas: HTMLCanvasElement;
  /** The canvas's CSS width, kept by a ResizeObserver: reading clientWidth while drawing would force a layout every frame. */
  private width = 600;

  constructor(onSeek: (fraction: number) => void) {
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'monitor-strip';
    this.canvas.height = 44;
    this.canvas.setAttribute('role', 'img');
    this.canvas.setAttribute('aria-label', 'Run timeline: rule changes (green), schema activations (blue), deadline misses (red), overruns (orange); click to move the cursor');
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
    this.canvas.addEventListener('pointermove', (e) => dragging && seek(e));
    this.canvas.addEventListener('pointerup', () => (dragging = false));
    new ResizeObserver((entries) => (this.width = Math.floor(entries[0]?.contentRect.width || this.width))).observe(this.canvas);
  }

  draw(marks: readonly Mark[], end: number, cursor: number): void {
    const c = this.canvas;
    const w = Math.max(100, this.width);
    if (c.width !== w) c.width = w;
    const ctx = c.getContext('2d');
    if (!ctx) return;
    ctx.clearRect(0, 0, w, c.height);
    const span = Math.max(1, end);
    const x = (t: number) => 1 + (t / span) * (w - 3);
    ctx.fillStyle = '#20242c';
    ctx.fillRect(0, 0, w, c.height);
    for (const m of marks) {
      ctx.fillStyle = m.kind === 'rule' && m.on === false ? '#5c6370' : COLOR[m.kind];
      ctx.fillRect(Math.floor(x(m.t)), 3 + ROW[m.kind] * 10, 2, 8);
    }
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(Math.floor(x(Math.min(cursor, span))), 0, 2, c.height);
  }
}
