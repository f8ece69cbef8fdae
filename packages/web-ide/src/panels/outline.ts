import { h, debounce } from '../util/dom.js';
import type * as lsp from 'vscode-languageserver-protocol';
import { SYMBOL_ICONS } from '../lsp/lsp-convert.js';

/** Outline of the active Cactal file (LSP document symbols); clicking reveals the symbol. */
export class OutlinePanel {
  private readonly list: HTMLElement;
  private uri: string | undefined;
  readonly refresh: () => void;

  constructor(
    root: HTMLElement,
    private readonly fetchSymbols: (uri: string) => Promise<lsp.DocumentSymbol[] | null>,
    private readonly reveal: (range: lsp.Range) => void,
  ) {
    this.list = h('div', { class: 'outline', role: 'tree' });
    root.append(this.list);
    this.refresh = debounce(() => void this.load(), 250);
  }

  /** For generated C: the protected regions (editable parts) of the file, click to reveal. */
  showRegions<R extends { id: string; line: number }>(regions: R[], reveal: (region: R) => void): void {
    this.uri = undefined;
    this.list.replaceChildren(
      h('div', { class: 'muted pad small' }, 'Protected regions (editable)'),
      ...regions.map((r) => h('div', { class: 'outline-row', role: 'treeitem', 'data-name': r.id, style: 'padding-left:8px', onclick: () => reveal(r) },
        h('span', { class: 'sym-icon region' }, '▍'), h('span', { class: 'sym-name' }, r.id), h('span', { class: 'sym-detail' }, `line ${r.line}`))),
    );
  }

  show(uri: string | undefined): void {
    this.uri = uri;
    if (!uri) this.list.replaceChildren(h('div', { class: 'muted pad' }, 'No Cactal file active'));
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
    const walk = (list: lsp.DocumentSymbol[], depth: number) => {
      for (const s of list) {
        rows.push(h('div', {
          class: 'outline-row', role: 'treeitem', style: `padding-left:${8 + depth * 14}px`, 'data-name': s.name,
          onclick: () => this.reveal(s.selectionRange),
        }, h('span', { class: `sym-icon k${s.kind}` }, SYMBOL_ICONS[s.kind] ?? '•'), h('span', { class: 'sym-name' }, s.name),
          s.detail ? h('span', { class: 'sym-detail' }, s.detail) : null));
        if (s.children?.length) walk(s.children, depth + 1);
      }
    };
    walk(symbols ?? [], 0);
    this.list.replaceChildren(...(rows.length ? rows : [h('div', { class: 'muted pad' }, 'No symbols')]));
  }
}
