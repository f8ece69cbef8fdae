import { h } from '../util/dom.js';
import { fuzzyFilter } from './fuzzy.js';

export interface PickItem {
  /** Matched against the query and shown (matched characters highlighted). */
  label: string;
  /** Shown dimmed after the label (a folder, a command's group). */
  detail?: string;
  /** A shortcut shown at the right (`Ctrl+Shift+G`). */
  keybinding?: string;
}

const MAX_ROWS = 200;
let openPick: { close(): void } | undefined;

/**
 * A quick-pick box at the top of the window (quick open, command palette): type to filter
 * (fuzzy), ↑/↓ (PageUp/PageDown, Home/End) to move, Enter to pick, Escape to close. A combobox
 * with a listbox (WAI-ARIA combobox pattern); focus goes back where it was when it closes (what a picked item runs moves it on).
 * Resolves the picked item, or undefined.
 */
export function quickPick<T extends PickItem>(opts: { placeholder: string; label: string; items: readonly T[]; id: string }): Promise<T | undefined> {
  openPick?.close();
  const returnFocus = document.activeElement as HTMLElement | null;
  return new Promise((resolve) => {
    const listId = `${opts.id}-list`;
    const input = h('input', {
      class: 'quick-pick-input', placeholder: opts.placeholder, spellcheck: 'false', autocomplete: 'off',
      role: 'combobox', 'aria-expanded': 'true', 'aria-controls': listId, 'aria-autocomplete': 'list', 'aria-label': opts.label,
    });
    const list = h('div', { class: 'quick-pick-list', role: 'listbox', id: listId, 'aria-label': opts.label });
    const box = h('div', { class: 'quick-pick', id: opts.id, role: 'dialog', 'aria-label': opts.label }, input, list);
    const overlay = h('div', { class: 'quick-pick-overlay' }, box);
    let shown: T[] = [];
    let index = 0;
    let done = false;
    const finish = (item: T | undefined) => {
      if (done) return;
      done = true;
      overlay.remove();
      if (openPick === handle) openPick = undefined;
      // back where it was, a pick too: a command then opening a dialog gives the focus back there on
      // Escape (the list's removal had left it on the page's body)
      if (returnFocus?.isConnected) returnFocus.focus();
      resolve(item);
    };
    const handle = { close: () => finish(undefined) };
    openPick = handle;
    const select = (i: number) => {
      index = Math.max(0, Math.min(shown.length - 1, i));
      list.querySelectorAll('[aria-selected="true"]').forEach((r) => r.setAttribute('aria-selected', 'false'));
      const row = list.children[index] as HTMLElement | undefined;
      if (row?.getAttribute('role') === 'option') {
        row.setAttribute('aria-selected', 'true');
        row.scrollIntoView({ block: 'nearest' });
        input.setAttribute('aria-activedescendant', row.id);
      } else input.removeAttribute('aria-activedescendant');
    };
    const render = () => {
      const results = fuzzyFilter(input.value, opts.items, (i) => i.label).slice(0, MAX_ROWS);
      shown = results.map((r) => r.item);
      list.replaceChildren(...(results.length ? results.map(({ item, match }, i) => {
        const hit = new Set(match.positions);
        const label = h('span', { class: 'qp-label' }, ...[...item.label].map((ch, k) => (hit.has(k) ? h('mark', {}, ch) : ch)));
        return h('div', { class: 'quick-pick-row', role: 'option', id: `${opts.id}-opt-${i}`, 'aria-selected': 'false', onmousedown: (e: Event) => e.preventDefault(), onclick: () => finish(item) },
          label, item.detail ? h('span', { class: 'qp-detail' }, item.detail) : null, item.keybinding ? h('kbd', { class: 'qp-key' }, item.keybinding) : null);
      }) : [h('div', { class: 'quick-pick-empty muted', role: 'presentation' }, 'No match')]));
      select(0);
    };
    input.addEventListener('input', render);
    input.addEventListener('keydown', (e) => {
      const page = Math.max(1, Math.floor(list.clientHeight / 26));
      const moves: Record<string, number> = { ArrowDown: index + 1, ArrowUp: index - 1, PageDown: index + page, PageUp: index - page };
      if (e.key in moves) select(moves[e.key]!);
      else if (e.key === 'Enter') finish(shown[index]);
      else if (e.key === 'Escape') finish(undefined);
      else return;
      e.preventDefault();
      e.stopPropagation();
    });
    input.addEventListener('blur', () => setTimeout(() => !done && !box.contains(document.activeElement) && finish(undefined), 0));
    overlay.addEventListener('mousedown', (e) => e.target === overlay && finish(undefined));
    document.body.append(overlay);
    render();
    input.focus();
  });
}
