import { h, debounce } from '../util/dom.js';
import { Emitter } from '../util/emitter.js';

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
 * build). Grouped by file; clicking opens the file at the position.
 */
export class ProblemsPanel {
  readonly onCounts = new Emitter<{ errors: number; warnings: number }>();
  readonly onOpen = new Emitter<Problem>();
  private readonly sets = new Map<string, Problem[]>();
  private readonly list: HTMLElement;
  private readonly scheduleRender = debounce(() => this.render(), 30);

  constructor(readonly root: HTMLElement) {
    this.list = h('div', { class: 'problems' });
    root.append(this.list);
    this.render();
  }

  /** Replaces the problems of one producer key (e.g. `cactal:file.contract` or `gcc`). */
  set(key: string, problems: Problem[]): void {
    if (problems.length) this.sets.set(key, problems);
    else this.sets.delete(key);
    this.scheduleRender();
  }

  all(): Problem[] {
    return [...this.sets.values()].flat();
  }

  private render(): void {
    const all = this.all();
    const byFile = new Map<string, Problem[]>();
    for (const p of all) (byFile.get(p.path) ?? byFile.set(p.path, []).get(p.path)!).push(p);
    const rows: HTMLElement[] = [];
    for (const path of [...byFile.keys()].sort()) {
      const ps = byFile.get(path)!.sort((a, b) => ORDER[a.severity] - ORDER[b.severity] || a.line - b.line || a.column - b.column);
      rows.push(h('div', { class: 'problem-file' }, h('span', { class: 'file-glyph' }, path.endsWith('.contract') ? '◈' : 'C'), path, h('span', { class: 'badge' }, String(ps.length))));
      for (const p of ps) {
        rows.push(h('div', { class: `problem-row ${p.severity}`, 'data-path': p.path, 'data-line': p.line, onclick: () => this.onOpen.fire(p) },
          h('span', { class: 'sev' }, ICON[p.severity]), h('span', { class: 'msg' }, p.message),
          h('span', { class: 'src' }, p.source), h('span', { class: 'pos' }, `[${p.line}:${p.column}]`)));
      }
    }
    this.list.replaceChildren(...(rows.length ? rows : [h('div', { class: 'muted pad' }, '✓ No problems in the workspace')]));
    this.onCounts.fire({ errors: all.filter((p) => p.severity === 'error').length, warnings: all.filter((p) => p.severity === 'warning').length });
  }
}
