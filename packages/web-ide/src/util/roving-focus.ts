/**
 * Roving tabindex (WAI-ARIA tree, listbox and tablist patterns): the list is one Tab stop, its
 * current item holds tabindex 0 and the others -1; arrows, Home and End move the focus, Enter and
 * Space activate, Escape leaves (back to the editor). Lists that re-render their rows call
 * `refresh()` afterwards: the item with the same key keeps the focus.
 */
export interface RovingOptions {
  /** The items, in order (visible ones only). */
  items(): HTMLElement[];
  /** Identifies an item across re-renders (e.g. its path). */
  keyOf(item: HTMLElement): string;
  orientation: 'vertical' | 'horizontal';
  /** The item that holds the Tab stop when none was focused yet (the selected/active one). */
  current?(): HTMLElement | undefined;
  /** Enter or Space on an item. */
  onActivate?(item: HTMLElement, e: KeyboardEvent): void;
  /** Arrows move the focus; with `followFocus`, moving also activates (panel tabs). */
  followFocus?: boolean;
  /** Other keys (ArrowLeft/Right in a tree, Delete on a tab): true when handled. */
  onKey?(item: HTMLElement, e: KeyboardEvent): boolean;
  onEscape?(): void;
}

export class RovingFocus {
  private key: string | undefined;
  private hasFocus = false;

  constructor(private readonly container: HTMLElement, private readonly opts: RovingOptions) {
    container.addEventListener('focusin', (e) => {
      const item = this.itemOf(e.target);
      if (!item) return;
      this.hasFocus = true;
      this.key = opts.keyOf(item);
      for (const i of opts.items()) i.tabIndex = i === item ? 0 : -1;
    });
    container.addEventListener('focusout', (e) => {
      const to = e.relatedTarget as Node | null;
      if (to) this.hasFocus = container.contains(to);
      // no target: the focused row was re-rendered away (refresh() puts the focus back) or the page was clicked
      else setTimeout(() => (this.hasFocus = container.contains(document.activeElement)), 0);
    });
    container.addEventListener('keydown', (e) => this.onKeyDown(e));
  }

  /** Re-applies the tab stop after the items were re-rendered; keeps the focus on the same item. */
  refresh(): void {
    const items = this.opts.items();
    const target = items.find((i) => this.opts.keyOf(i) === this.key) ?? this.opts.current?.() ?? items[0];
    for (const i of items) i.tabIndex = i === target ? 0 : -1;
    if (this.hasFocus && target && !this.container.contains(document.activeElement)) target.focus();
  }

  /** The tab stop goes back to the selected item (`current`) at the next refresh: a tab list after its active tab changed. */
  forget(): void {
    this.key = undefined;
  }

  /** Focuses the current item (the last focused one, else the selected one, else the first). */
  focus(): boolean {
    this.key = this.key && this.opts.items().some((i) => this.opts.keyOf(i) === this.key) ? this.key : undefined;
    const items = this.opts.items();
    const target = items.find((i) => this.opts.keyOf(i) === this.key) ?? this.opts.current?.() ?? items[0];
    if (!target) return false;
    this.moveTo(target);
    return true;
  }

  /** Focuses `item` (it becomes the tab stop). */
  moveTo(item: HTMLElement): void {
    this.key = this.opts.keyOf(item);
    for (const i of this.opts.items()) i.tabIndex = i === item ? 0 : -1;
    item.focus();
    item.scrollIntoView({ block: 'nearest', inline: 'nearest' });
  }

  private itemOf(target: EventTarget | null): HTMLElement | undefined {
    const items = this.opts.items();
    let el = target as HTMLElement | null;
    while (el && el !== this.container) {
      if (items.includes(el)) return el;
      el = el.parentElement;
    }
    return undefined;
  }

  private onKeyDown(e: KeyboardEvent): void {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const item = this.itemOf(e.target);
    if (!item || e.target !== item) return; // keys typed into a control inside a row are its own
    const items = this.opts.items();
    const at = items.indexOf(item);
    const [prev, next] = this.opts.orientation === 'vertical' ? ['ArrowUp', 'ArrowDown'] : ['ArrowLeft', 'ArrowRight'];
    let to: HTMLElement | undefined;
    if (this.opts.onKey?.(item, e)) {
      e.preventDefault();
      return;
    }
    if (e.key === next) to = items[Math.min(items.length - 1, at + 1)];
    else if (e.key === prev) to = items[Math.max(0, at - 1)];
    else if (e.key === 'Home') to = items[0];
    else if (e.key === 'End') to = items[items.length - 1];
    else if ((e.key === 'Enter' || e.key === ' ') && this.opts.onActivate) {
      e.preventDefault();
      this.opts.onActivate(item, e);
      return;
    } else if (e.key === 'Escape' && this.opts.onEscape) {
      e.preventDefault();
      this.opts.onEscape();
      return;
    } else return;
    e.preventDefault();
    if (!to) return;
    this.moveTo(to);
    if (this.opts.followFocus) this.opts.onActivate?.(to, e);
  }
}
