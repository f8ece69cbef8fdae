import { monaco } from './monaco.js';
import { h } from '../util/dom.js';
import type { Conflict, Workspace } from '../workspace/workspace.js';
import { languageOf } from '../workspace/file-kinds.js';

/**
 * Overlapping edits of one file, side by side (Monaco's diff editor): on the left the text on disk
 * (read-only), on the right the user's (editable). The user keeps theirs, takes the disk's, or
 * edits the merge (both sides between markers) and saves it; nothing is written before that, and
 * the user's text stays in the browser copy until then (docs/ide.md, "Saves, versions and merges").
 * One conflict at a time; others wait in order.
 */
export class ConflictView {
  private readonly queue: Conflict[] = [];
  private current: { conflict: Conflict; diff: monaco.editor.IStandaloneDiffEditor; overlay: HTMLElement; models: monaco.editor.ITextModel[] } | undefined;

  constructor(private readonly workspace: Workspace) {
    workspace.onConflict.on((c) => this.add(c));
    // resolved elsewhere (reload from disk, a newer disk text that merged): the view closes
    workspace.onFileState.on((fs) => {
      if (this.current?.conflict.path === fs.path && fs.state !== 'conflict') this.next();
    });
  }

  private add(conflict: Conflict): void {
    const i = this.queue.findIndex((c) => c.path === conflict.path);
    if (i >= 0) this.queue.splice(i, 1);
    if (this.current?.conflict.path === conflict.path) {
      this.close();
      this.open(conflict);
      return;
    }
    this.queue.push(conflict);
    if (!this.current) this.next();
  }

  private next(): void {
    this.close();
    const c = this.queue.shift();
    if (c) this.open(c);
  }

  private open(conflict: Conflict): void {
    const host = h('div', { class: 'conflict-diff' });
    const choose = (text: () => string) => () => {
      const t = text();
      this.close();
      this.workspace.resolveConflict(conflict.path, t);
      this.next();
    };
    const original = monaco.editor.createModel(conflict.theirs, languageOf(conflict.path));
    const modified = monaco.editor.createModel(conflict.mine, languageOf(conflict.path));
    const overlay = h('div', { class: 'conflict-overlay', 'data-path': conflict.path, role: 'dialog' },
      h('div', { class: 'conflict-head' },
        h('div', { class: 'conflict-title' }, `${conflict.path}: your edits and a change made elsewhere overlap`),
        h('div', { class: 'dialog-hint' }, 'Left: the file on disk now. Right: your text (editable). Nothing is written until you choose; your text is kept in this browser meanwhile.')),
      host,
      h('div', { class: 'dialog-buttons' },
        h('button', { class: 'btn', id: 'conflict-edit-merge', title: 'Put both versions of each overlapping block, between markers, on the right', onclick: () => modified.setValue(conflict.marked) }, 'Edit the merge'),
        h('button', { class: 'btn', id: 'conflict-take-theirs', onclick: choose(() => conflict.theirs) }, 'Take theirs (disk)'),
        // the tab's text now (the user may have typed in it since the view opened)
        h('button', { class: 'btn', id: 'conflict-keep-mine', onclick: choose(() => this.tabText(conflict)) }, 'Keep mine'),
        h('button', { class: 'btn primary', id: 'conflict-save-right', onclick: choose(() => modified.getValue()) }, 'Save the right side')));
    document.body.append(overlay);
    const diff = monaco.editor.createDiffEditor(host, {
      theme: 'contract-dark', automaticLayout: true, originalEditable: false, readOnly: false,
      renderSideBySide: true, minimap: { enabled: false }, fontSize: 13, scrollBeyondLastLine: false,
    });
    diff.setModel({ original, modified });
    this.current = { conflict, diff, overlay, models: [original, modified] };
  }

  private tabText(conflict: Conflict): string {
    const model = this.workspace.files.get(conflict.path)?.model;
    return model && !model.isDisposed() ? model.getValue() : conflict.mine;
  }

  private close(): void {
    const c = this.current;
    if (!c) return;
    this.current = undefined;
    c.diff.setModel(null);
    c.diff.dispose();
    // a diff the editor worker is still computing fails ("no diff result available") if its models
    // are gone before it answers: they are dropped a little later
    setTimeout(() => c.models.forEach((m) => m.dispose()), 3000);
    c.overlay.remove();
  }
}
