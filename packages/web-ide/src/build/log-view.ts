import { h } from '../util/dom.js';
import type { LogStore } from './log-store.js';

const ROW = 18;

/**
 * Virtualised log view: a spacer as tall as all visible lines and only the rows in the viewport
 * rendered, redrawn at most once per animation frame. Follow-tail keeps the end in view and turns
 * itself off when the user scrolls up.
 */
export class LogView {
  readonly element: HTMLElement;
  private readonly viewport: HTMLElement;
  private readonly spacer: HTMLElement;
  private readonly rows: HTMLElement;
  follow = true;
  private drawnVersion = -1;
  private drawnTop = -1;
  private frame = 0;
  onFollowChange: (follow: boolean) => void = () => undefined;

  constructor(private readonly store: LogStore) {
    this.spacer = h('div', { class: 'log-spacer' });
    this.rows = h('div', { class: 'log-rows' });
    this.viewport = h('div', { class: 'log-viewport', tabindex: 0 }, this.spacer, this.rows);
    this.element = this.viewport;
    this.viewport.addEventListener('scroll', () => {
      const atEnd = this.viewport.scrollTop + this.viewport.clientHeight >= this.viewport.scrollHeight - ROW;
      if (this.follow !== atEnd) {
        this.follow = atEnd;
        this.onFollowChange(atEnd);
      }
      this.schedule();
    });
  }

  setFollow(follow: boolean): void {
    this.follow = follow;
    this.schedule();
  }

  schedule(): void {
    if (!this.frame) this.frame = requestAnimationFrame(() => this.draw());
  }

  private draw(): void {
    this.frame = 0;
    const n = this.store.visibleCount;
    this.spacer.style.height = `${n * ROW}px`;
    if (this.follow) this.viewport.scrollTop = this.viewport.scrollHeight;
    const top = Math.max(0, Math.floor(this.viewport.scrollTop / ROW) - 5);
    if (this.store.version === this.drawnVersion && top === this.drawnTop) return;
    this.drawnVersion = this.store.version;
    this.drawnTop = top;
    const count = Math.ceil((this.viewport.clientHeight || 400) / ROW) + 10;
    const frag = document.createDocumentFragment();
    for (let i = top; i < Math.min(n, top + count); i++) {
      const l = this.store.visibleAt(i)!;
      const time = new Date(l.t).toISOString().slice(11, 23);
      frag.append(h('div', { class: `log-row ${l.stream}`, 'data-source': l.source },
        h('span', { class: 'log-time' }, time), h('span', { class: `log-src src-${l.source.replace(/\W/g, '')}` }, l.source), h('span', { class: 'log-text' }, l.line)));
    }
    this.rows.style.transform = `translateY(${top * ROW}px)`;
    this.rows.replaceChildren(frag);
  }
}
