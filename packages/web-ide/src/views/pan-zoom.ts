/**
 * Zoom and pan of an SVG drawing inside its pane (the architecture diagram): the wheel zooms at the
 * pointer (in a scrolled panel: with Ctrl, or once the drawing has the focus), a drag pans, +/- zoom,
 * arrows pan, F or 0 fits. The drawing is laid out at its natural
 * size; the automatic view never scales it below a readable font (docs/ide.md "Architecture").
 */
export interface View {
  scale: number;
  x: number;
  y: number;
}

export interface Size {
  width: number;
  height: number;
}

export const MIN_SCALE = 0.15;
export const MAX_SCALE = 4;
const clampScale = (s: number) => Math.min(MAX_SCALE, Math.max(MIN_SCALE, s));

/** Zooms by `factor` keeping the drawing point under (px, py) (pane coordinates) where it is. */
export function zoomAt(v: View, factor: number, px: number, py: number): View {
  const scale = clampScale(v.scale * factor);
  const k = scale / v.scale;
  return { scale, x: px - (px - v.x) * k, y: py - (py - v.y) * k };
}

/** The whole drawing in the pane, centred, never magnified beyond `maxScale`. */
export function fitView(content: Size, pane: Size, margin = 16, maxScale = 1.5): View {
  const scale = clampScale(Math.min(maxScale, (pane.width - 2 * margin) / Math.max(1, content.width), (pane.height - 2 * margin) / Math.max(1, content.height)));
  return { scale, x: (pane.width - content.width * scale) / 2, y: Math.max(margin, (pane.height - content.height * scale) / 2) };
}

/**
 * The first view of a drawing: fitted when that keeps the smallest text at `minFontPx` or more,
 * else at the readable scale, anchored at the top left (the user pans to the rest).
 */
export function readableView(content: Size, pane: Size, smallestFontPx: number, minFontPx: number, margin = 16): View {
  const fit = fitView(content, pane, margin, 1);
  const readable = minFontPx / smallestFontPx;
  if (fit.scale >= readable) return fit;
  return { scale: readable, x: margin, y: margin };
}

export class PanZoom {
  view: View = { scale: 1, x: 0, y: 0 };
  private content: Size = { width: 0, height: 0 };
  /** True while (and just after) the pointer dragged: the click that ends a drag does not go to a definition. */
  private dragged = false;

  constructor(
    private readonly pane: HTMLElement,
    private readonly apply: (v: View) => void,
    private readonly opts: { smallestFontPx: number; minFontPx: number; wheelScrollsPage?: boolean },
    /** Called before a fit (button, F, 0): the pane's owner brings the pane whole on screen. */
    private readonly beforeFit?: () => void,
  ) {
    pane.addEventListener('wheel', (e) => {
      // in a scrolled panel (the Monitor) a plain wheel scrolls the panel: the diagram coming under the
      // pointer must not take the wheel and shrink to nothing; Ctrl (a pinch) or the focus in the diagram zooms
      if (this.opts.wheelScrollsPage && !e.ctrlKey && !e.metaKey && !pane.contains(document.activeElement)) {
        this.hintWheel();
        return;
      }
      e.preventDefault();
      const r = pane.getBoundingClientRect();
      this.set(zoomAt(this.view, Math.exp(-e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015)), e.clientX - r.left, e.clientY - r.top));
    }, { passive: false });
    pane.addEventListener('pointerdown', (e) => {
      if (e.button !== 0) return;
      const start = { x: e.clientX, y: e.clientY, vx: this.view.x, vy: this.view.y };
      this.dragged = false;
      const move = (ev: PointerEvent) => {
        const dx = ev.clientX - start.x;
        const dy = ev.clientY - start.y;
        if (!this.dragged && Math.hypot(dx, dy) < 4) return;
        if (!this.dragged) pane.setPointerCapture(e.pointerId);
        this.dragged = true;
        pane.classList.add('panning');
        this.set({ ...this.view, x: start.vx + dx, y: start.vy + dy });
      };
      const up = () => {
        pane.removeEventListener('pointermove', move);
        pane.removeEventListener('pointerup', up);
        pane.removeEventListener('pointercancel', up);
        pane.classList.remove('panning');
      };
      pane.addEventListener('pointermove', move);
      pane.addEventListener('pointerup', up);
      pane.addEventListener('pointercancel', up);
    });
    pane.addEventListener('click', (e) => {
      if (!this.dragged) return;
      this.dragged = false;
      e.stopPropagation();
      e.preventDefault();
    }, { capture: true });
    pane.addEventListener('keydown', (e) => {
      if (e.ctrlKey || e.metaKey || e.altKey || e.target !== pane) return;
      const r = pane.getBoundingClientRect();
      const step = 60;
      const keys: Record<string, () => void> = {
        '+': () => this.set(zoomAt(this.view, 1.25, r.width / 2, r.height / 2)),
        '=': () => this.set(zoomAt(this.view, 1.25, r.width / 2, r.height / 2)),
        '-': () => this.set(zoomAt(this.view, 0.8, r.width / 2, r.height / 2)),
        f: () => this.fit(),
        '0': () => this.fit(),
        ArrowLeft: () => this.set({ ...this.view, x: this.view.x + step }),
        ArrowRight: () => this.set({ ...this.view, x: this.view.x - step }),
        ArrowUp: () => this.set({ ...this.view, y: this.view.y + step }),
        ArrowDown: () => this.set({ ...this.view, y: this.view.y - step }),
      };
      const k = keys[e.key.length === 1 ? e.key.toLowerCase() : e.key];
      if (!k) return;
      e.preventDefault();
      k();
    });
  }

  /** The drawing's size; `reset`: a new drawing, shown in the readable first view (else the view is kept). */
  setContent(content: Size, reset: boolean): void {
    this.content = content;
    if (reset) this.set(readableView(content, this.paneSize(), this.opts.smallestFontPx, this.opts.minFontPx));
    else this.set(this.view);
  }

  /** The whole drawing in the pane. */
  fit(): void {
    this.beforeFit?.();
    this.set(fitView(this.content, this.paneSize()));
  }

  zoom(factor: number): void {
    const p = this.paneSize();
    this.set(zoomAt(this.view, factor, p.width / 2, p.height / 2));
  }

  private hintTimer: ReturnType<typeof setTimeout> | undefined;

  /** Says, for a moment, how the wheel zooms here (CSS .arch-canvas[data-wheel-hint]). */
  private hintWheel(): void {
    this.pane.dataset.wheelHint = '';
    clearTimeout(this.hintTimer);
    this.hintTimer = setTimeout(() => delete this.pane.dataset.wheelHint, 1500);
  }

  set(v: View): void {
    if (this.pane.dataset.wheelHint !== undefined) (clearTimeout(this.hintTimer), delete this.pane.dataset.wheelHint); // zoomed or panned: said enough
    this.view = v;
    this.apply(v);
  }

  private paneSize(): Size {
    const r = this.pane.getBoundingClientRect();
    return { width: r.width || 600, height: r.height || 400 };
  }
}
