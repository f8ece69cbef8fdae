import { monaco } from './monaco.js';
import { h } from '../util/dom.js';
import { openModal, type FocusStop, type Modal } from '../util/modal.js';
import type { Conflict, Workspace } from '../workspace/workspace.js';
import { findConflictMarker, threeWayMerge } from '../workspace/three-way-merge.js';
import { languageOf } from '../workspace/file-kinds.js';

let views = 0;

/** The choices' buttons, named by what each keeps (docs/ide.md "Saves, versions and merges"). */
export const CONFLICT_BUTTONS = {
  theirs: 'Keep the version on disk (saved elsewhere)',
  mine: 'Keep my version (this tab)',
  right: 'Save the right side as edited here',
} as const;

/** The one line under the title that says what each choice keeps. */
export const CONFLICT_CHOICES =
  `${CONFLICT_BUTTONS.mine}: your text wins, the other change is lost. ${CONFLICT_BUTTONS.theirs}: the change made elsewhere ` +
  '(another tab, Generate All, git) wins, your edits are lost. Edit the merge puts both in the right side: keep what you want, then save it.';

/**
 * Overlapping edits of one file, side by side (Monaco's diff editor): on the left the text on disk
 * (read-only), on the right the user's (editable). The user keeps theirs, takes the disk's, or
 * edits the merge (both sides between markers) and saves it; nothing is written before that, and
 * the user's text stays in the browser copy until then (docs/ide.md, "Saves, versions and merges").
 * One conflict at a time; others wait in order.
 *
 * The view is a modal dialog (util/modal.ts): the page behind is inert (keys never reach the
 * hidden editor), Tab and Shift+Tab go round the two sides and the buttons, Escape closes it
 * without choosing (the tab stays "Overlapping edits", nothing written; Ctrl+S in the tab shows it
 * again), and the focus goes back to the editor. The buttons say what each keeps (CONFLICT_BUTTONS),
 * a line under the title too; long lines wrap on both sides. "Save the right side as edited here" refuses a text with
 * conflict markers left, naming the line.
 */
export class ConflictView {
  private readonly queue: Conflict[] = [];
  private current: {
    conflict: Conflict; diff: monaco.editor.IStandaloneDiffEditor; viewModel: monaco.editor.IDiffEditorViewModel; overlay: HTMLElement; modal: Modal;
    models: monaco.editor.ITextModel[]; listeners: monaco.IDisposable[];
  } | undefined;

  constructor(
    private readonly workspace: Workspace,
    /** Where the focus goes when the view closes and nothing had it before: the IDE's editor (editor-area.ts). */
    private readonly focusEditor: () => void = () => monaco.editor.getEditors().find((e) => e.getContainerDomNode().closest('.editor-host'))?.focus(),
  ) {
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
      if (this.current.conflict === conflict) return; // asked again while shown
      // the disk changed again while shown: its newest text on the left. What the user made of the
      // right side so far (their merge in progress) is kept, with the disk's new change merged into
      // it when the two do not overlap; unedited, the right side is their tab's text now
      const right = this.current.models[1]!.getValue();
      const shown = this.current.conflict;
      this.close();
      if (right === shown.mine) this.open(conflict, {});
      else {
        const merged = threeWayMerge(shown.theirs, right, conflict.theirs);
        this.open(conflict, merged.clean ? { right: merged.text, merged: true } : { right });
      }
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

  /**
   * `again`: the view replaces one of the same file (the disk changed again); `again.right`, the
   * right side's text when it is not the tab's (a merge in progress carried over), `merged` when the
   * disk's new change was merged into it.
   */
  private open(conflict: Conflict, again?: { right?: string; merged?: boolean }): void {
    const right = again?.right;
    const n = ++views;
    const host = h('div', { class: 'conflict-diff monaco-component' }); // the theme's colours for its right-click menu (editor-area.ts)
    const choose = (text: () => string) => () => {
      const t = text();
      this.close();
      this.workspace.resolveConflict(conflict.path, t);
      this.next();
    };
    // models of their own scheme: not workspace files (the language server does not open them)
    const original = monaco.editor.createModel(conflict.theirs, languageOf(conflict.path), monaco.Uri.from({ scheme: 'conflict', path: `/${n}/disk/${conflict.path}` }));
    const modified = monaco.editor.createModel(right ?? conflict.mine, languageOf(conflict.path), monaco.Uri.from({ scheme: 'conflict', path: `/${n}/yours/${conflict.path}` }));
    const error = h('div', { class: 'conflict-error hidden', role: 'alert' });
    const changedAgain = h('div', { class: `conflict-again${again ? '' : ' hidden'}`, role: 'status' },
      'The file on disk changed again while this view was open: the left side is its newest text' +
      (right === undefined ? '.' : again?.merged ? '; your right side is kept as you left it, with that new change merged in.' :
        '; your right side is kept as you left it (the new change overlaps your edits there: compare the two sides).'));
    const saveRight = () => {
      const text = modified.getValue();
      const marker = findConflictMarker(text);
      if (!marker) return choose(() => text)();
      error.textContent = `Not saved: line ${marker.line} of the right side still has the conflict marker "${marker.marker}". ` +
        'Keep what you want of each block and delete the <<<<<<< / ======= / >>>>>>> lines, then save again.';
      error.classList.remove('hidden');
      const right = diff.getModifiedEditor();
      right.setPosition({ lineNumber: marker.line, column: 1 });
      right.revealLineInCenter(marker.line);
      right.focus();
    };
    const titleId = `conflict-title-${n}`;
    const hintId = `conflict-hint-${n}`;
    const buttons = [
      h('button', { class: 'btn', id: 'conflict-edit-merge', title: 'Put both versions of each overlapping block, between markers, on the right', onclick: () => {
        // an undo step of its own on the right side: Ctrl+Z there brings the text before it back
        modified.pushStackElement();
        modified.pushEditOperations([], [{ range: modified.getFullModelRange(), text: conflict.marked }], () => null);
        modified.pushStackElement();
        const first = findConflictMarker(conflict.marked);
        if (first) diff.getModifiedEditor().revealLineInCenter(first.line);
      } }, 'Edit the merge'),
      h('button', { class: 'btn', id: 'conflict-take-theirs', title: 'Write the left side: the change made elsewhere stays, your edits in this tab are dropped', onclick: choose(() => conflict.theirs) }, CONFLICT_BUTTONS.theirs),
      // the tab's text now (the user may have typed in it before the view opened)
      h('button', { class: 'btn', id: 'conflict-keep-mine', title: 'Write your tab\'s text as you typed it: the change made elsewhere is dropped', onclick: choose(() => this.tabText(conflict)) }, CONFLICT_BUTTONS.mine),
      h('button', { class: 'btn primary', id: 'conflict-save-right', title: 'Write the right side as it is now in this view (your text, with what you edited here)', onclick: saveRight }, CONFLICT_BUTTONS.right),
    ];
    const overlay = h('div', { class: 'conflict-overlay', 'data-path': conflict.path, 'aria-labelledby': titleId, 'aria-describedby': hintId },
      h('div', { class: 'conflict-head' },
        h('div', { class: 'conflict-title', id: titleId }, `${conflict.path}: your edits and a change made elsewhere overlap`),
        h('div', { class: 'dialog-hint', id: hintId }, 'Left: the file on disk now. Right: your text (editable). Nothing is written until you choose; your text is kept in this browser meanwhile. ' +
          'Tab moves between the two sides and the buttons; Escape decides later (Ctrl+S in the tab shows this again).'),
        h('div', { class: 'dialog-hint conflict-choices' }, CONFLICT_CHOICES)),
      changedAgain, host, error,
      h('div', { class: 'dialog-buttons' }, ...buttons));
    // in the page before the editor is created (it measures its host), not yet a modal
    overlay.style.visibility = 'hidden';
    document.body.append(overlay);
    const diff = monaco.editor.createDiffEditor(host, {
      theme: 'contract-dark', automaticLayout: true, originalEditable: false, readOnly: false,
      renderSideBySide: true, minimap: { enabled: false }, fontSize: 13, scrollBeyondLastLine: false,
      // long lines wrap on both sides: half the dialog's width cut them on the right
      wordWrap: 'on', diffWordWrap: 'on',
      // no suggestion list: its widget, made on first use, could be asked for after the view is gone
      // (the language server does not know these models anyway)
      quickSuggestions: false, suggestOnTriggerCharacters: false,
      ariaLabel: `${conflict.path}: on disk (left) and yours (right)`,
      // each side named: a screen reader tells the disk's text from the user's
      originalAriaLabel: `${conflict.path} on disk now (read-only)`,
      modifiedAriaLabel: `${conflict.path}: your text, to edit into the merge`,
    });
    const viewModel = diff.createViewModel({ original, modified });
    diff.setModel(viewModel);
    restorePageDefaults(); // the diff editor's editors just took them over: see below
    const sideStop = (editor: monaco.editor.ICodeEditor): FocusStop => ({ el: editor.getContainerDomNode(), focus: () => editor.focus() });
    const listeners = [modified.onDidChangeContent(() => error.classList.add('hidden'))];
    overlay.style.visibility = '';
    const modal = openModal(overlay, overlay, {
      onEscape: () => this.cancel(),
      initialFocus: () => buttons[0]!.focus(),
      stops: () => [sideStop(diff.getOriginalEditor()), sideStop(diff.getModifiedEditor()), ...buttons.map((b) => ({ el: b, focus: () => b.focus() }))],
      fallbackFocus: this.focusEditor,
    });
    this.current = { conflict, diff, viewModel, overlay, modal, models: [original, modified], listeners };
  }

  /** Escape: closed without a choice. The conflict stays (nothing written); the next file's, if any, is shown. */
  private cancel(): void {
    this.next();
  }

  private tabText(conflict: Conflict): string {
    const model = this.workspace.files.get(conflict.path)?.model;
    return model && !model.isDisposed() ? model.getValue() : conflict.mine;
  }

  /**
   * Takes the view down in an order that leaves nothing of it alive: the focus leaves it first (to
   * the editor), its listeners go, the diff editor lets go of its models and is disposed while still
   * in the page, the overlay leaves the page; the models are disposed once the editor worker can no
   * longer be computing a diff of them (a result arriving for a disposed model fails in Monaco).
   */
  private close(): void {
    const c = this.current;
    if (!c) return;
    this.current = undefined;
    c.modal.close(() => {
      c.listeners.forEach((l) => l.dispose());
      c.diff.setModel(null);
      c.diff.dispose();
      c.viewModel.dispose();
    });
    setTimeout(() => c.models.forEach((m) => m.isDisposed() || m.dispose()), 3000);
  }
}

/**
 * Every standalone code editor Monaco builds installs page-wide defaults made with its own
 * instantiation service: the hover delegate factory (used lazily, the first time any list or
 * action bar needs a default hover) and the markdown code-block renderer. The diff editor's two
 * editors are built with the diff editor's child service, which its dispose() disposes; a default
 * made afterwards through it throws "InstantiationService has been disposed" (seen when a later
 * reload or merge in the tab first rendered a suggestion list). An editor built and disposed at
 * once with the page's own service puts the defaults back on that service, which lives as long as
 * the page.
 */
function restorePageDefaults(): void {
  const host = document.createElement('div');
  monaco.editor.create(host, { model: null, automaticLayout: false, minimap: { enabled: false } }).dispose();
}
