import { h } from '../util/dom.js';
import type { LogLine, LogStore } from './log-store.js';
import { isLauncherNews } from './launcher-lines.js';
import { visibleText } from '@contract-studio/conventions';

const ROW = 18;
/** Rows drawn above and below the viewport. */
const MARGIN = 5;
/**
 * While lines stream in, the view redraws at most this often (ms); what the user does (scroll,
 * resize, filter, follow) redraws at the next frame. Hundreds of lines a second cannot be read as
 * they pass, and a redraw each frame scrolled and repainted the whole pane sixty times a second
 * beside the Monitor.
 */
export const STREAM_REDRAW_MS = 100;

/**
 * Virtualised log view: a spacer as tall as all visible lines and only the rows in the viewport
 * rendered, redrawn at most once per animation frame. Follow-tail keeps the end in view and turns
 * itself off when the user scrolls up.
 *
 * A run that prints hundreds of lines a second (a 1 kHz schema missing its deadlines) redraws
 * every frame, beside the Monitor, so a frame's draw stays small: the rows already shown are kept
 * (only the lines scrolled in are built), and following the tail writes the scroll position
 * from the known sizes instead of reading the layout (a read forces the page's layout in the
 * middle of the frame).
 */
export class LogView {
  readonly element: HTMLElement;
  private readonly viewport: HTMLElement;
  private readonly spacer: HTMLElement;
  private readonly rows: HTMLElement;
  follow = true;
  /** The rows shown: visible lines [first, first + rows.children.length) of store state `renumbered`. */
  private shown = { renumbered: -1, first: 0 };
  private spacerHeight = -1;
  /** The viewport's height (kept by a ResizeObserver), 0 until known. */
  private viewHeight = 0;
  /** The scrollTop this view last wrote (its own scroll events are not the user's). */
  private wroteTop = -1;
  private frame = 0;
  /** A redraw for streamed lines, due after STREAM_REDRAW_MS (0: none). */
  private streamTimer: ReturnType<typeof setTimeout> | 0 = 0;
  private lastDraw = -Infinity;
  onFollowChange: (follow: boolean) => void = () => undefined;

  constructor(private readonly store: LogStore) {
    this.spacer = h('div', { class: 'log-spacer' });
    this.rows = h('div', { class: 'log-rows' });
    this.viewport = h('div', { class: 'log-viewport', tabindex: 0 }, this.spacer, this.rows);
    this.element = this.viewport;
    this.viewport.addEventListener('scroll', () => {
      const top = this.viewport.scrollTop;
      if (this.follow && top === this.wroteTop) return; // the tail followed: drawn already
      const atEnd = top + this.viewport.clientHeight >= this.viewport.scrollHeight - ROW;
      if (this.follow !== atEnd) {
        this.follow = atEnd;
        this.onFollowChange(atEnd);
      }
      this.schedule();
    });
    if (typeof ResizeObserver !== 'undefined') {
      new ResizeObserver(() => {
        this.viewHeight = this.viewport.clientHeight;
        this.wroteTop = -1;
        this.schedule();
      }).observe(this.viewport);
    }
  }

  setFollow(follow: boolean): void {
    this.follow = follow;
    this.wroteTop = -1;
    this.schedule();
  }

  /** Redraws at the next frame (what the user did). */
  schedule(): void {
    if (this.streamTimer) {
      clearTimeout(this.streamTimer);
      this.streamTimer = 0;
    }
    if (!this.frame) this.frame = requestAnimationFrame(() => this.draw());
  }

  /** New lines in the store: redrawn at the next frame, or, while they stream, STREAM_REDRAW_MS after the last redraw. */
  scheduleAppend(): void {
    if (this.frame || this.streamTimer) return;
    const wait = this.lastDraw + STREAM_REDRAW_MS - performance.now();
    if (wait <= 0) this.frame = requestAnimationFrame(() => this.draw());
    else this.streamTimer = setTimeout(() => {
      this.streamTimer = 0;
      this.schedule();
    }, wait);
  }

  private draw(): void {
    this.frame = 0;
    this.lastDraw = performance.now();
    const n = this.store.visibleCount;
    const height = n * ROW;
    if (height !== this.spacerHeight) {
      this.spacer.style.height = `${height}px`;
      this.spacerHeight = height;
    }
    const viewHeight = this.viewHeight || this.viewport.clientHeight || 400;
    let scrollTop: number;
    if (this.follow) {
      scrollTop = Math.max(0, height - viewHeight);
      if (scrollTop !== this.wroteTop) {
        this.viewport.scrollTop = scrollTop;
        this.wroteTop = scrollTop;
      }
    } else scrollTop = this.viewport.scrollTop;
    const first = Math.max(0, Math.floor(scrollTop / ROW) - MARGIN);
    const end = Math.min(n, first + Math.ceil(viewHeight / ROW) + 2 * MARGIN);
    this.placeRows(first, end);
  }

  /** Shows visible lines [first, end): the rows still in that range are kept, the others built. */
  private placeRows(first: number, end: number): void {
    const rows = this.rows;
    const shown = this.shown;
    const shownEnd = shown.first + rows.children.length;
    if (shown.renumbered !== this.store.renumbered || first >= shownEnd || end <= shown.first) {
      const frag = document.createDocumentFragment();
      for (let i = first; i < end; i++) frag.append(this.row(this.store.visibleAt(i)!));
      rows.replaceChildren(frag);
    } else {
      for (let i = shown.first; i < first; i++) rows.firstElementChild!.remove();
      for (let i = shownEnd; i > end; i--) rows.lastElementChild!.remove();
      if (first < shown.first) {
        const frag = document.createDocumentFragment();
        for (let i = first; i < shown.first; i++) frag.append(this.row(this.store.visibleAt(i)!));
        rows.prepend(frag);
      }
      if (end > shownEnd) {
        const frag = document.createDocumentFragment();
        for (let i = Math.max(shownEnd, first); i < end; i++) frag.append(this.row(this.store.visibleAt(i)!));
        rows.append(frag);
      }
    }
    if (first !== shown.first || shown.renumbered !== this.store.renumbered) rows.style.transform = `translateY(${first * ROW}px)`;
    this.shown = { renumbered: this.store.renumbered, first };
  }

  private row(l: LogLine): HTMLElement {
    const time = new Date(l.t).toISOString().slice(11, 23);
    const news = l.source === 'launcher' && l.stream === 'stderr' && isLauncherNews(l.line);
    return h('div', { class: `log-row ${l.stream}${news ? ' news' : ''}`, 'data-source': l.source },
      h('span', { class: 'log-time' }, time), h('span', { class: `log-src src-${l.source.replace(/\W/g, '')}` }, l.source), h('span', { class: 'log-text' }, visibleText(l.line)));
  }
}
