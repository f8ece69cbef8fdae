import { visibleText } from '@contract-studio/conventions';
import { h, debounce } from '../util/dom.js';
import { Emitter } from '../util/emitter.js';
import { RovingFocus } from '../util/roving-focus.js';

export type Severity = 'error' | 'warning' | 'info' | 'hint';

export interface Problem {
  path: string;
  line: number;
  column: number;
  severity: Severity;
  message: string;
  source: string;
}

const ORDER: Record<Severity, number> = { error: 0, warning: 1, info: 2, hint: 3 };
const ICON: Record<Severity, string> = { error: '✖', warning: '⚠', info: 'ℹ', hint: '✧' };

/**
 * Problems of the whole workspace, from several producers (the language server per file, gcc per
 * build). Grouped by file; clicking opens the file at the position. Keyboard: a WAI-ARIA listbox
 * (↑/↓, Home/End, Enter opens the problem's position, Escape back to the editor).
 */
export class ProblemsPanel {
  readonly onCounts = new Emitter<{ errors: number; warnings: number }>();
  readonly onOpen = new Emitter<Problem>();
  private readonly sets = new Map<string, Problem[]>();
  private readonly list: HTMLElement;
  private readonly scheduleRender = debounce(() => this.renderIfPending(), 30);
  private pending = false;
  /** Escape in the list: the owner focuses the editor. */
  readonly onEscape = new Emitter<void>();
  private readonly roving: RovingFocus;
  private shown: Problem[] = [];
  /** Shown instead of the list when it is empty (outside it: a listbox holds options only). */
  private readonly empty: HTMLElement;

  constructor(readonly root: HTMLElement) {
    this.list = h('div', { class: 'problems', role: 'listbox', 'aria-label': 'Problems of the workspace' });
    this.empty = h('div', { class: 'muted pad hidden' }, '✓ No problems in the workspace');
    root.append(this.list, this.empty);
    this.roving = new RovingFocus(this.list, {
      orientation: 'vertical',
      items: () => [...this.list.querySelectorAll<HTMLElement>('.problem-row')],
      keyOf: (row) => row.dataset.key ?? '',
      onActivate: (row) => this.open(row),
      onEscape: () => this.onEscape.fire(),
    });
    this.list.addEventListener('focusin', (e) => {
      for (const r of this.list.querySelectorAll('.problem-row')) r.setAttribute('aria-selected', String(r === e.target));
    });
    this.render();
  }

  /** Moves the keyboard focus to the problems list (the last focused problem, else the first). */
  focus(): boolean {
    return this.roving.focus();
  }

  private open(row: HTMLElement): void {
    const p = this.shown[Number(row.dataset.index)];
    if (p) this.onOpen.fire(p);
  }

  /** Replaces the problems of one producer key (e.g. `cactal:file.contract` or `gcc`). */
  set(key: string, problems: Problem[]): void {
    if (problems.length) this.sets.set(key, problems);
    else this.sets.delete(key);
    this.pending = true;
    this.scheduleRender();
  }

  /** Shows now the problems set since the last render (instead of within 30 ms): the ready mark comes after. */
  renderIfPending(): void {
    if (this.pending) this.render();
  }

  all(): Problem[] {
    return [...this.sets.values()].flat();
  }

  private render(): void {
    this.pending = false;
    const all = this.all();
    const byFile = new Map<string, Problem[]>();
    for (const p of all) (byFile.get(p.path) ?? byFile.set(p.path, []).get(p.path)!).push(p);
    const rows: HTMLElement[] = [];
    this.shown = [];
    for (const path of [...byFile.keys()].sort()) {
      const ps = byFile.get(path)!.sort((a, b) => ORDER[a.severity] - ORDER[b.severity] || a.line - b.line || a.column - b.column);
      const options: HTMLElement[] = [];
      for (const p of ps) {
        const index = this.shown.push(p) - 1;
        options.push(h('div', {
          class: `problem-row ${p.severity}`, role: 'option', 'aria-selected': 'false', tabindex: -1, 'data-path': p.path, 'data-line': p.line, 'data-index': index,
          'data-key': `${p.path}:${p.line}:${p.column}:${p.message}`, onclick: () => this.onOpen.fire(p),
        },
          h('span', { class: 'sev', role: 'img', 'aria-label': p.severity }, ICON[p.severity]), h('span', { class: 'msg' }, visibleText(p.message)),
          h('span', { class: 'src' }, p.source), h('span', { class: 'pos' }, `[${p.line}:${p.column}]`)));
      }
      const label = `${path}: ${ps.length} problem${ps.length > 1 ? 's' : ''}`;
      rows.push(h('div', { role: 'group', 'aria-label': label },
        h('div', { class: 'problem-file', 'aria-hidden': 'true' }, h('span', { class: 'file-glyph' }, path.endsWith('.contract') ? '◈' : 'C'), path, h('span', { class: 'badge' }, String(ps.length))),
        ...options));
    }
    this.list.replaceChildren(...rows);
    this.empty.classList.toggle('hidden', rows.length > 0);
    this.roving.refresh();
    this.onCounts.fire({ errors: all.filter((p) => p.severity === 'error').length, warnings: all.filter((p) => p.severity === 'warning').length });
  }
}
