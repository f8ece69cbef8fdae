import { h } from '../util/dom.js';
import type { TreeEntry } from '../api.js';
import { Emitter } from '../util/emitter.js';
import { RovingFocus } from '../util/roving-focus.js';
import { visibleText } from '@contract-studio/conventions';

/**
 * The project explorer: a collapsible tree of the workspace. Emits open/select; the owner runs
 * file operations (create, rename, delete) through the server. Keyboard: a WAI-ARIA tree (↑/↓,
 * → expands or enters a folder, ← collapses or goes to the parent, Enter opens, F2 renames,
 * Delete deletes, Escape back to the editor).
 */
export class Explorer {
  readonly onOpen = new Emitter<string>();
  readonly onContextAction = new Emitter<{ action: 'rename' | 'delete' | 'new-file' | 'new-folder'; entry: TreeEntry }>();
  /** Escape in the tree: the owner focuses the editor. */
  readonly onEscape = new Emitter<void>();
  selected: TreeEntry | undefined;
  private readonly expanded = new Set<string>();
  private entries: TreeEntry[] = [];
  private active: string | undefined;
  private readonly list: HTMLElement;
  private readonly byPath = new Map<string, TreeEntry>();
  /** The rows drawn last, by path, with what they show (render keeps those that show the same). */
  private drawn = new Map<string, { look: string; row: HTMLElement }>();
  /** Shown instead of the tree when it is empty (outside it: a tree holds tree items only). */
  private readonly empty: HTMLElement;
  private readonly roving: RovingFocus;

  constructor(readonly root: HTMLElement) {
    this.list = h('div', { class: 'tree', role: 'tree', 'aria-label': 'Files of the workspace' });
    this.empty = h('div', { class: 'muted pad hidden' }, 'Empty workspace: use New Project');
    root.append(this.list, this.empty);
    const rows = () => [...this.list.querySelectorAll<HTMLElement>('.tree-row')];
    const rowOf = (path: string | undefined) => rows().find((r) => r.dataset.path === path);
    this.roving = new RovingFocus(this.list, {
      orientation: 'vertical',
      items: rows,
      keyOf: (row) => row.dataset.path ?? '',
      current: () => rowOf(this.selected?.path) ?? rowOf(this.active),
      onActivate: (row) => this.byPath.get(row.dataset.path!) && this.click(this.byPath.get(row.dataset.path!)!),
      onEscape: () => this.onEscape.fire(),
      onKey: (row, e) => {
        const entry = this.byPath.get(row.dataset.path!);
        if (!entry) return false;
        const open = this.expanded.has(entry.path);
        if (e.key === 'ArrowRight' && entry.type === 'dir') {
          if (!open) this.toggle(entry);
          else if (entry.children?.length) this.roving.moveTo(rowOf(entry.children[0]!.path)!);
          return true;
        }
        if (e.key === 'ArrowLeft') {
          if (entry.type === 'dir' && open) this.toggle(entry);
          else if (entry.path.includes('/')) this.roving.moveTo(rowOf(entry.path.slice(0, entry.path.lastIndexOf('/')))!);
          return true;
        }
        if (e.key === 'F2' || e.key === 'Delete') {
          this.selected = entry;
          this.onContextAction.fire({ action: e.key === 'F2' ? 'rename' : 'delete', entry });
          return true;
        }
        return false;
      },
    });
  }

  /** Moves the keyboard focus into the tree (the selected or active file). */
  focus(): boolean {
    return this.roving.focus();
  }

  /** The entry of a path, when it is in the tree. */
  entryOf(path: string): TreeEntry | undefined {
    return this.byPath.get(path);
  }

  private toggle(e: TreeEntry): void {
    if (this.expanded.has(e.path)) this.expanded.delete(e.path);
    else this.expanded.add(e.path);
    this.render();
  }

  private click(e: TreeEntry): void {
    this.selected = e;
    if (e.type === 'dir') this.toggle(e);
    else {
      this.render();
      this.onOpen.fire(e.path);
    }
  }

  setEntries(entries: TreeEntry[]): void {
    this.entries = entries;
    this.render();
  }

  setActive(path: string | undefined): void {
    this.active = path;
    if (path) {
      const parts = path.split('/');
      for (let i = 1; i < parts.length; i++) this.expanded.add(parts.slice(0, i).join('/'));
    }
    this.render();
  }

  expand(path: string): void {
    const parts = path.split('/');
    for (let i = 1; i <= parts.length; i++) this.expanded.add(parts.slice(0, i).join('/'));
    this.render();
  }

  /** The folder new entries go into: the selected folder, or the selected file's folder. */
  targetFolder(): string {
    const s = this.selected;
    if (!s) return '';
    if (s.type === 'dir') return s.path;
    const i = s.path.lastIndexOf('/');
    return i < 0 ? '' : s.path.slice(0, i);
  }

  /**
   * Draws the rows. A row whose look is unchanged (same entry name, depth, kind, open, active,
   * selected) is the same element as before, and rows are only moved, added or removed where the
   * tree changed: a refresh that changes nothing (each file event, Generate All's writes, a tab
   * switch) leaves the rows in place, so a click whose press and release straddle it still lands
   * on its row (a row replaced between them lost the click: its release fell on a new element).
   */
  private render(): void {
    const rows: HTMLElement[] = [];
    const drawn = new Map<string, { look: string; row: HTMLElement }>();
    this.byPath.clear();
    const walk = (entries: TreeEntry[], depth: number) => {
      for (const e of entries) {
        this.byPath.set(e.path, e);
        const isDir = e.type === 'dir';
        const open = this.expanded.has(e.path);
        const active = e.path === this.active;
        const selected = e === this.selected || e.path === this.selected?.path;
        const look = JSON.stringify([e.name, e.type, e.truncated ?? false, !!e.children?.length, depth, open, active, selected]);
        const before = this.drawn.get(e.path);
        const row = before?.look === look ? before.row : this.row(e, depth, open, active, selected);
        drawn.set(e.path, { look, row });
        rows.push(row);
        if (isDir && open && e.children) walk(e.children, depth + 1);
      }
    };
    walk(this.entries, 0);
    this.drawn = drawn;
    let at = this.list.firstElementChild;
    for (const row of rows) {
      if (row === at) at = at.nextElementSibling;
      else this.list.insertBefore(row, at);
    }
    while (at) {
      const next = at.nextElementSibling;
      at.remove();
      at = next;
    }
    this.empty.classList.toggle('hidden', rows.length > 0);
    this.roving.refresh();
  }

  /** One row; its handlers find its entry by path when they run (a kept row outlives the entry it was drawn from). */
  private row(e: TreeEntry, depth: number, open: boolean, active: boolean, selected: boolean): HTMLElement {
    const path = e.path;
    const entry = () => this.byPath.get(path) ?? e;
    const isDir = e.type === 'dir';
    const icon = isDir ? (open ? '▾' : '▸') : '';
    const kind = isDir ? (e.name === 'src-gen' ? 'gen-folder' : 'folder') : e.name.endsWith('.contract') ? 'cactal' : /\.(c|h)$/.test(e.name) ? 'c' : e.name.endsWith('.jsonl') ? 'trace' : 'other';
    const glyph = isDir ? '' : kind === 'cactal' ? '◈' : kind === 'c' ? 'C' : kind === 'trace' ? '◉' : '≡'; // a trace file opens in the ◉ Monitor
    const action = (name: 'rename' | 'delete' | 'new-file') => (ev: Event) => { ev.stopPropagation(); this.selected = entry(); this.onContextAction.fire({ action: name, entry: entry() }); };
    return h('div', {
      class: `tree-row ${kind}${active ? ' active' : ''}${selected ? ' selected' : ''}`,
      role: 'treeitem', 'data-path': path, title: visibleText(e.truncated ? (e.children?.length ? `${path}: not all of its content is listed (past the listing's 50,000 entries)` : `${path}: its content is not listed (deeper than 64 folders, or past 50,000 entries)`) : path), style: `padding-left:${8 + depth * 14}px`, tabindex: -1,
      'aria-level': depth + 1, 'aria-selected': active ? 'true' : 'false', 'aria-expanded': isDir ? String(open) : undefined,
      onclick: () => this.click(entry()),
    },
      h('span', { class: 'twisty', 'aria-hidden': 'true' }, icon), h('span', { class: `file-glyph ${kind}`, 'aria-hidden': 'true' }, glyph), h('span', { class: 'tree-name' }, visibleText(e.name)),
      h('span', { class: 'row-actions', 'aria-hidden': 'true' },
        isDir ? h('span', { class: 'row-action', title: 'New file here', 'data-action': 'new-file', onclick: action('new-file') }, '+') : null,
        h('span', { class: 'row-action', title: 'Rename', 'data-action': 'rename', onclick: action('rename') }, '✎'),
        h('span', { class: 'row-action', title: 'Delete', 'data-action': 'delete', onclick: action('delete') }, '✕')));
  }
}
