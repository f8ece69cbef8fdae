import { h } from '../util/dom.js';
import type { GenerateReport } from '../api.js';
import { ORPHANS_HOLD } from '@contract-studio/conventions';

interface Problem {
  file: string;
  line?: number;
  message: string;
}

/**
 * Shows what Generate All did: counts, the generated tree (click opens the file), orphaned user
 * code and malformed files (click opens them at the line).
 */
/** An entry that opens its file: a click, or Enter / Space from the keyboard (each is a tab stop). */
function openable(open: () => void): Record<string, unknown> {
  return {
    role: 'button', tabindex: 0, onclick: open,
    onkeydown: (e: Event) => {
      const key = (e as KeyboardEvent).key;
      if (key !== 'Enter' && key !== ' ') return;
      e.preventDefault();
      open();
    },
  };
}

export class GeneratePanel {
  readonly element: HTMLElement;

  constructor(private readonly open: (path: string, line?: number) => void) {
    this.element = h('div', { class: 'generate-panel' }, h('div', { class: 'muted pad' }, 'Run Generate All (Ctrl+Shift+G) to produce the C tree under src-gen/.'));
  }

  showRunning(): void {
    this.element.replaceChildren(h('div', { class: 'pad' }, h('span', { class: 'spinner' }), ' Generating…'));
  }

  showError(message: string): void {
    this.element.replaceChildren(h('div', { class: 'pad gen-error' }, `✖ Generate All failed: ${message}`));
  }

  show(r: GenerateReport): void {
    const base = r.srcGen ? `${r.srcGen}/` : '';
    const fileLink = (rel: string, cls = '', line?: number) =>
      h('div', { class: `gen-file ${cls}`, 'data-path': base + rel, ...openable(() => this.open(base + rel, line)) }, h('span', { class: 'file-glyph', 'aria-hidden': 'true' }, /\.(c|h)$/.test(rel) ? 'C' : '≡'), pathName(rel));
    const problems = (title: string, list: Problem[], cls: string) =>
      list.length
        ? h('div', { class: `gen-section ${cls}` }, h('div', { class: 'gen-title' }, `${title} (${list.length})`),
            ...list.map((p) => h('div', { class: 'gen-problem', 'data-path': base + p.file, ...openable(() => this.open(base + p.file, p.line)) },
              h('span', { class: 'sev' }, cls === 'errors' ? '✖' : '⚠'), h('span', { class: 'mono' }, `${p.file}${p.line ? `:${p.line}` : ''}`), ' ', p.message)))
        : null;
    const generated = [...r.created.map((f) => [f, 'created']), ...r.updated.map((f) => [f, 'updated']), ...r.unchanged.map((f) => [f, 'unchanged'])]
      .filter(([f]) => !f!.startsWith('.'))
      .sort((a, b) => a[0]!.localeCompare(b[0]!));
    this.element.replaceChildren(
      h('div', { class: 'gen-summary' },
        h('span', { class: r.errors.length ? 'pill error' : 'pill ok' }, r.errors.length ? '✖ with errors' : '✓ generated'),
        h('span', { class: 'pill' }, `${r.created.length} created`), h('span', { class: 'pill' }, `${r.updated.length} updated`),
        h('span', { class: 'pill' }, `${r.unchanged.length} unchanged`),
        h('span', { class: r.orphaned.length ? 'pill warning' : 'pill' }, `${r.orphaned.length} orphaned`), h('span', { class: 'muted' }, `${r.ms} ms`)),
      r.layoutWarnings?.length ? h('div', { class: 'gen-section warnings layout-warnings' }, h('div', { class: 'gen-title' }, `Project layout (${r.layoutWarnings.length})`),
        ...r.layoutWarnings.map((w) => h('div', { class: 'gen-problem' }, h('span', { class: 'sev' }, '⚠'), ' ', w))) : '',
      problems('Errors — files left untouched', r.errors as Problem[], 'errors') ?? '',
      r.orphaned.length ? h('div', { class: 'gen-section warnings' }, h('div', { class: 'gen-title' }, `Copied to orphans/ (${r.orphaned.length}) — ${ORPHANS_HOLD}; never deleted`), ...r.orphaned.map((f) => fileLink(f, 'orphan'))) : '',
      problems('Warnings', r.warnings as Problem[], 'warnings') ?? '',
      h('div', { class: 'gen-section' }, h('div', { class: 'gen-title' }, `Generated tree: ${base || './'}`),
        h('div', { class: 'gen-tree' }, ...generated.map(([f, state]) => fileLink(f!, state!)))),
    );
  }
}

/**
 * A path in a narrow column: its folders give way first (cut at their end, `generated/archi…`), the
 * file name stays whole (`SharedTypes.h`); the whole path is the tooltip and the text read out.
 */
function pathName(rel: string): HTMLElement {
  const slash = rel.lastIndexOf('/') + 1;
  return h('span', { class: 'gen-name', title: rel },
    slash ? h('span', { class: 'gen-dir' }, rel.slice(0, slash)) : null, h('span', { class: 'gen-base' }, rel.slice(slash)));
}
