import { h } from '../util/dom.js';
import type { TreeEntry } from '../api.js';
import { Emitter } from '../util/emitter.js';

/**
 * The project explorer: a collapsible tree of the workspace. Emits open/select; the owner runs
 * file operations (create, rename, delete) through the server.
 */
export class Explorer {
  readonly onOpen = new Emitter<string>();
  readonly onContextAction = new Emitter<{ action: 'rename' | 'delete' | 'new-file' | 'new-folder'; entry: TreeEntry }>();
  selected: TreeEntry | undefined;
  private readonly expanded = new Set<string>();
  private entries: TreeEntry[] = [];
  private active: string | undefined;
  private readonly list: HTMLElement;

  constructor(readonly root: HTMLElement) {
    this.list = h('div', { class: 'tree', role: 'tree' });
    root.append(this.list);
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

  private render(): void {
    const rows: HTMLElement[] = [];
    const walk = (entries: TreeEntry[], depth: number) => {
      for (const e of entries) {
        const isDir = e.type === 'dir';
        const open = this.expanded.has(e.path);
        const icon = isDir ? (open ? '▾' : '▸') : '';
        const kind = isDir ? (e.name === 'src-gen' ? 'gen-folder' : 'folder') : e.name.endsWith('.contract') ? 'cactal' : /\.(c|h)$/.test(e.name) ? 'c' : 'other';
        const glyph = isDir ? '' : kind === 'cactal' ? '◈' : kind === 'c' ? 'C' : '≡';
        const row = h('div', {
          class: `tree-row ${kind}${e.path === this.active ? ' active' : ''}${e === this.selected || e.path === this.selected?.path ? ' selected' : ''}`,
          role: 'treeitem', 'data-path': e.path, title: e.path, style: `padding-left:${8 + depth * 14}px`,
          onclick: () => {
            this.selected = e;
            if (isDir) {
              if (open) this.expanded.delete(e.path);
              else this.expanded.add(e.path);
              this.render();
            } else {
              this.onOpen.fire(e.path);
            }
          },
        },
          h('span', { class: 'twisty' }, icon), h('span', { class: `file-glyph ${kind}` }, glyph), h('span', { class: 'tree-name' }, e.name),
          h('span', { class: 'row-actions' },
            isDir ? h('span', { class: 'row-action', title: 'New file here', 'data-action': 'new-file', onclick: (ev: Event) => { ev.stopPropagation(); this.selected = e; this.onContextAction.fire({ action: 'new-file', entry: e }); } }, '+') : null,
            h('span', { class: 'row-action', title: 'Rename', 'data-action': 'rename', onclick: (ev: Event) => { ev.stopPropagation(); this.selected = e; this.onContextAction.fire({ action: 'rename', entry: e }); } }, '✎'),
            h('span', { class: 'row-action', title: 'Delete', 'data-action': 'delete', onclick: (ev: Event) => { ev.stopPropagation(); this.selected = e; this.onContextAction.fire({ action: 'delete', entry: e }); } }, '✕')));
        rows.push(row);
        if (isDir && open && e.children) walk(e.children, depth + 1);
      }
    };
    walk(this.entries, 0);
    this.list.replaceChildren(...(rows.length ? rows : [h('div', { class: 'muted pad' }, 'Empty workspace: use New Project')]));
  }
}
