import { h, debounce } from '../util/dom.js';
import type * as lsp from 'vscode-languageserver-protocol';
import { SYMBOL_ICONS } from '../lsp/lsp-convert.js';
import { RovingFocus } from '../util/roving-focus.js';
import { Emitter } from '../util/emitter.js';

/**
 * Outline of the active Cactal file (LSP document symbols); clicking reveals the symbol. Keyboard:
 * a WAI-ARIA tree (↑/↓, Home/End, Enter reveals the symbol in the editor, Escape back to the editor).
 */
export class OutlinePanel {
  private readonly list: HTMLElement;
  private readonly caption: HTMLElement;
  /** Shown instead of the tree when it is empty (outside it: a tree holds tree items only). */
  private readonly empty: HTMLElement;
  private uri: string | undefined;
  readonly refresh: () => void;
  /** Escape in the outline: the owner focuses the editor. */
  readonly onEscape = new Emitter<void>();
  private readonly roving: RovingFocus;

  constructor(
    root: HTMLElement,
    private readonly fetchSymbols: (uri: string) => Promise<lsp.DocumentSymbol[] | null>,
    private readonly reveal: (range: lsp.Range) => void,
  ) {
    this.list = h('div', { class: 'outline', role: 'tree', 'aria-label': 'Outline of the active file' });
    this.caption = h('div', { class: 'muted pad small hidden' }, 'Protected regions (editable)');
    this.empty = h('div', { class: 'muted pad hidden' });
    root.append(this.caption, this.list, this.empty);
    this.refresh = debounce(() => void this.load(), 250);
    this.roving = new RovingFocus(this.list, {
      orientation: 'vertical',
      items: () => [...this.list.querySelectorAll<HTMLElement>('.outline-row')],
      keyOf: (row) => `${row.dataset.name}@${row.dataset.index}`,
      onActivate: (row) => row.click(),
      onEscape: () => this.onEscape.fire(),
    });
  }

  /** Moves the keyboard focus into the outline; false when it has no entry. */
  focus(): boolean {
    return this.roving.focus();
  }

  private setRows(rows: HTMLElement[], empty: string, regions = false): void {
    this.caption.classList.toggle('hidden', !regions);
    this.list.setAttribute('aria-label', regions ? 'Protected regions (editable) of the generated file' : 'Outline of the active file');
    rows.forEach((r, i) => {
      r.dataset.index = String(i);
      r.tabIndex = -1;
    });
    this.list.replaceChildren(...rows);
    this.empty.textContent = empty;
    this.empty.classList.toggle('hidden', rows.length > 0);
    this.roving.refresh();
  }

  /** For generated C: the protected regions (editable parts) of the file, click to reveal. */
  showRegions<R extends { id: string; line: number }>(regions: R[], reveal: (region: R) => void): void {
    this.uri = undefined;
    this.setRows(regions.map((r) => h('div', { class: 'outline-row', role: 'treeitem', 'aria-level': 1, 'aria-selected': 'false', 'data-name': r.id, style: 'padding-left:8px', onclick: () => reveal(r) },
      h('span', { class: 'sym-icon region', 'aria-hidden': 'true' }, '▍'), h('span', { class: 'sym-name' }, r.id), h('span', { class: 'sym-detail' }, `line ${r.line}`))),
    'No protected region', true);
  }

  show(uri: string | undefined): void {
    this.uri = uri;
    if (!uri) this.setRows([], 'No Cactal file active');
    else void this.load();
  }

  private async load(): Promise<void> {
    const uri = this.uri;
    if (!uri) return;
    let symbols: lsp.DocumentSymbol[] | null = null;
    try {
      symbols = await this.fetchSymbols(uri);
    } catch {
      symbols = null;
    }
    if (uri !== this.uri) return;
    const rows: HTMLElement[] = [];
    let more = 0;
    const walk = (list: lsp.DocumentSymbol[], depth: number) => {
      for (const s of list) {
        // a file of 60,000 datatypes: the first MAX_ROWS, the others counted (a row each crashed
        // the panel: too many arguments to replaceChildren, and the last file's symbols stayed)
        if (rows.length >= MAX_ROWS) {
          more += 1 + countSymbols(s.children ?? []);
          continue;
        }
        rows.push(h('div', {
          class: 'outline-row', role: 'treeitem', 'aria-level': depth + 1, 'aria-selected': 'false', style: `padding-left:${8 + depth * 14}px`, 'data-name': s.name,
          onclick: () => this.reveal(s.selectionRange),
        }, h('span', { class: `sym-icon k${s.kind}`, 'aria-hidden': 'true' }, SYMBOL_ICONS[s.kind] ?? '•'), h('span', { class: 'sym-name' }, s.name),
          s.detail ? h('span', { class: 'sym-detail' }, s.detail) : null));
        if (s.children?.length) walk(s.children, depth + 1);
      }
    };
    walk(symbols ?? [], 0);
    if (more) rows.push(h('div', { class: 'outline-more muted', role: 'note' }, `… ${more} more symbols: the outline lists the file's first ${MAX_ROWS} (go to a symbol with F12 or Shift+F12 from where it is used)`));
    this.setRows(rows, 'No symbols');
  }
}

/** Symbols the outline lists for one file; the rest are counted. */
const MAX_ROWS = 5000;

function countSymbols(list: readonly lsp.DocumentSymbol[]): number {
  let n = 0;
  for (const s of list) n += 1 + countSymbols(s.children ?? []);
  return n;
}
