/**
 * A pane resizer (the line between the sidebar and the editor, the one between the editor and the
 * bottom panel): dragged with the mouse, or focused (it is a Tab stop) and moved with the arrow
 * keys — 10 px a press, 50 px with Shift, Home / End to the smallest / largest size. A WAI-ARIA
 * focusable separator: `role="separator"`, `aria-orientation` (a vertical line moves left and
 * right), `aria-valuenow` the size of the pane it resizes, in CSS pixels, between `aria-valuemin`
 * and `aria-valuemax`. A drag selects no text of the page. Each change is announced to the page
 * as a `pane-resized` event on `window` (the layout kept for the next load listens to it).
 */
export interface PaneResizerSpec {
  /** `vertical`: a vertical line between panes side by side (← →); `horizontal`: a line between panes above and below (↑ ↓). */
  orientation: 'vertical' | 'horizontal';
  label: string;
  /** The id of the pane it resizes (`aria-controls`). */
  controls: string;
  min(): number;
  max(): number;
  /** The pane's size as laid out now. */
  size(): number;
  setSize(px: number): void;
  /** +1 when moving the line right (down) makes the pane larger, -1 when it makes it smaller (the bottom panel). */
  direction: 1 | -1;
}

export const PANE_RESIZED = 'pane-resized';

export function makePaneResizer(handle: HTMLElement, spec: PaneResizerSpec): { refresh(): void } {
  handle.setAttribute('role', 'separator');
  handle.setAttribute('aria-orientation', spec.orientation);
  handle.setAttribute('aria-label', spec.label);
  handle.setAttribute('aria-controls', spec.controls);
  handle.tabIndex = 0;
  const refresh = () => {
    handle.setAttribute('aria-valuemin', String(Math.round(spec.min())));
    handle.setAttribute('aria-valuemax', String(Math.round(spec.max())));
    handle.setAttribute('aria-valuenow', String(Math.round(spec.size())));
  };
  const resizeTo = (px: number) => {
    const lo = spec.min();
    const hi = Math.max(lo, spec.max());
    spec.setSize(Math.round(Math.max(lo, Math.min(hi, px))));
    refresh();
    window.dispatchEvent(new Event(PANE_RESIZED));
  };
  const [less, more] = spec.orientation === 'vertical' ? ['ArrowLeft', 'ArrowRight'] : ['ArrowUp', 'ArrowDown'];
  handle.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.altKey || e.metaKey) return;
    const step = e.shiftKey ? 50 : 10;
    let to: number | undefined;
    if (e.key === less) to = spec.size() - step * spec.direction;
    else if (e.key === more) to = spec.size() + step * spec.direction;
    else if (e.key === 'Home') to = spec.min();
    else if (e.key === 'End') to = spec.max();
    if (to === undefined) return;
    e.preventDefault();
    e.stopPropagation();
    resizeTo(to);
  });
  handle.addEventListener('focus', refresh);
  handle.addEventListener('mousedown', (e) => {
    if (e.button !== 0) return;
    e.preventDefault(); // no text selected by the drag (and the focus stays where it was)
    const start = spec.orientation === 'vertical' ? e.clientX : e.clientY;
    const from = spec.size();
    document.body.classList.add(spec.orientation === 'vertical' ? 'resizing-columns' : 'resizing-rows');
    const onMove = (ev: MouseEvent) => {
      ev.preventDefault();
      const at = spec.orientation === 'vertical' ? ev.clientX : ev.clientY;
      resizeTo(from + (at - start) * spec.direction);
    };
    const onUp = () => {
      document.body.classList.remove('resizing-columns', 'resizing-rows');
      window.removeEventListener('mousemove', onMove);
      window.removeEventListener('mouseup', onUp);
    };
    window.addEventListener('mousemove', onMove);
    window.addEventListener('mouseup', onUp);
  });
  window.addEventListener('resize', refresh);
  refresh();
  return { refresh };
}
