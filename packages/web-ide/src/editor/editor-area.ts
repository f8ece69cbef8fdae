import { monaco } from './monaco.js';
import { h } from '../util/dom.js';
import { Emitter } from '../util/emitter.js';
import type { Workspace, FileState } from '../workspace/workspace.js';
import { isGeneratedC } from '../workspace/file-kinds.js';
import { GeneratedGuard } from './generated-guard.js';
import { toast } from '../util/toast.js';
import { confirmAction } from '../util/dialog.js';
import { RovingFocus } from '../util/roving-focus.js';
import { fitActionMenus } from './action-menu-width.js';


/** What the editor says of a keystroke in a generated file outside its regions. */
const GENERATED_READ_ONLY = 'Generated code: only the content of PROTECTED REGIONs can be edited.';

/** Why a file whose bytes are not all UTF-8 is shown read-only. */
function undecodableMessage(path: string, line: number): string {
  return `${path} holds bytes that are not UTF-8 (from line ${line}: Latin-1 or binary), shown as \uFFFD: it is read-only here, so that a save cannot replace them. Convert it to UTF-8 (iconv -f latin1 -t utf-8) to edit it in the IDE.`;
}

/** A non-file tab (architecture, timeline) rendered by its owner into `element`. */
export interface ViewTab {
  id: string;
  title: string;
  icon: string;
  element: HTMLElement;
  onShow?(): void;
}

/**
 * Tabs + the single Monaco editor. File tabs swap models in and out of the editor (keeping each
 * tab's view state); view tabs show their own element instead. Generated C gets a GeneratedGuard.
 */
export class EditorArea {
  readonly editor: monaco.editor.IStandaloneCodeEditor;
  readonly onActiveChanged = new Emitter<string | undefined>();
  /** Tabs opened, closed, renamed or reordered (the layout store saves them: app/layout-state.ts). */
  readonly onTabsChanged = new Emitter<void>();
  /** The side pane shows another element, or none (dock). */
  readonly onDocked = new Emitter<HTMLElement | undefined>();
  private readonly tabsEl: HTMLElement;
  private readonly editorHost: HTMLElement;
  private readonly viewHost: HTMLElement;
  private readonly emptyEl: HTMLElement;
  private readonly stack: HTMLElement;
  private readonly sidePane: HTMLElement;
  private readonly tabs: string[] = [];
  private readonly views = new Map<string, ViewTab>();
  private readonly viewStates = new Map<string, monaco.editor.ICodeEditorViewState | null>();
  private readonly guards = new Map<string, GeneratedGuard>();
  private readonly tabFocus: RovingFocus;
  active: string | undefined;

  constructor(
    readonly root: HTMLElement,
    private readonly workspace: Workspace,
  ) {
    this.tabsEl = h('div', { class: 'tabs', role: 'tablist', 'aria-label': 'Open files and views' });
    // the tabs: a WAI-ARIA tablist (←/→ move, Enter shows the tab and focuses its editor, Delete closes, Escape back to the editor)
    this.tabFocus = new RovingFocus(this.tabsEl, {
      orientation: 'horizontal',
      items: () => [...this.tabsEl.querySelectorAll<HTMLElement>('.tab')],
      keyOf: (tab) => tab.dataset.path ?? '',
      current: () => this.tabsEl.querySelector<HTMLElement>('.tab.active') ?? undefined,
      onActivate: (tab) => this.show(tab.dataset.path!),
      onEscape: () => this.focusActive(),
      onKey: (tab, e) => {
        if (e.key !== 'Delete') return false;
        this.close(tab.dataset.path!);
        // the last tab closed: the keyboard goes to the empty editor's hint (Ctrl+P from there), not the page's body
        if (!this.tabFocus.focus()) this.emptyEl.focus();
        return true;
      },
    });
    // monaco-component: Monaco's theme colours (CSS variables) are set on .monaco-editor and
    // .monaco-component; the right-click menu is drawn in a shadow root beside the editor, under
    // this host, and had none of them (a transparent menu, black text over the code)
    this.editorHost = h('div', { class: 'editor-host monaco-component' });
    this.viewHost = h('div', { class: 'view-host hidden' });
    this.emptyEl = h('div', { class: 'editor-empty', tabindex: -1 }, h('div', { class: 'empty-logo' }, '◈'), h('div', {}, 'Open a file from the explorer, or Ctrl+P'),
      h('div', { class: 'muted' }, 'F1 all commands · Ctrl+S saves now · F12 go to definition · F2 rename · Ctrl+Shift+I format'));
    this.sidePane = h('div', { class: 'side-pane hidden' });
    this.stack = h('div', { class: 'editor-stack' }, this.editorHost, this.viewHost, this.emptyEl, this.sidePane);
    // Escape in a view (the Monitor, the Timeline, the architecture diagram) that did not use it
    // goes back as in the panels: from the side pane to the editor beside it, from a view tab to the tab strip
    const escape = (e: KeyboardEvent, back: () => unknown) => {
      if (e.key !== 'Escape' || e.defaultPrevented || (e.target as HTMLElement | null)?.closest('.monaco-editor, .dialog, .quick-pick')) return;
      e.preventDefault();
      back();
    };
    this.sidePane.addEventListener('keydown', (e) => escape(e, () => (this.active && !this.views.has(this.active) ? this.editor.focus() : this.focusTabs())));
    this.viewHost.addEventListener('keydown', (e) => escape(e, () => this.focusTabs()));
    root.append(this.tabsEl, this.stack);
    this.editor = monaco.editor.create(this.editorHost, {
      theme: 'contract-dark',
      automaticLayout: true,
      fontSize: 13,
      fontFamily: "'JetBrains Mono', 'Fira Code', 'DejaVu Sans Mono', monospace",
      minimap: { enabled: false },
      scrollBeyondLastLine: false,
      renderLineHighlight: 'all',
      smoothScrolling: true,
      fixedOverflowWidgets: true,
      model: null,
      tabSize: 4,
      'semanticHighlighting.enabled': true,
      readOnlyMessage: { value: GENERATED_READ_ONLY },
    });
    fitActionMenus(this.editor);
    this.editor.onDidChangeCursorSelection(() => this.updateReadOnly());
    workspace.onEncodingChanged.on((path) => path === this.active && this.updateReadOnly());
    this.editor.addCommand(monaco.KeyMod.CtrlCmd | monaco.KeyCode.KeyS, () => {
      // (the keybinding is the page's: only when this editor has the focus, not the conflict view's editors)
      if (!this.editor.hasTextFocus() || !this.active || this.views.has(this.active)) return;
      // overlapping edits waiting for a choice: Ctrl+S shows the side-by-side view again
      if (!this.workspace.showConflict(this.active)) void this.workspace.save(this.active);
    });
    this.editor.addAction({
      id: 'contract.reloadFromDisk',
      label: 'Reload from disk (discard unsaved edits)',
      contextMenuGroupId: '9_reload',
      run: async () => {
        const path = this.active && !this.views.has(this.active) ? this.active : undefined;
        const fs = path ? this.workspace.files.get(path) : undefined;
        if (!path || !fs) return;
        if (fs.state !== 'saved' && !(await confirmAction(`Reload ${path} from disk?`, 'Your unsaved edits of this file (also the copy kept in this browser) are dropped.', 'Reload'))) return;
        await this.workspace.revertToDisk(path).catch((e: Error) => toast('error', `Cannot reload ${path}: ${e.message}`));
      },
    });
    workspace.onFileState.on((fs) => this.renderTabState(fs));
    monaco.editor.registerEditorOpener({
      openCodeEditor: (_source, resource, selectionOrPosition) => {
        const path = this.workspace.pathOf(resource);
        if (!path) return false;
        void this.open(path, selectionOrPosition);
        return true;
      },
    });
    this.render();
  }

  isOpen(id: string): boolean {
    return this.tabs.includes(id);
  }

  /** The open tabs in order, the active one, and each file tab's cursor and scroll (Monaco view state). */
  tabsState(): { tabs: string[]; active?: string; viewStates: Record<string, monaco.editor.ICodeEditorViewState> } {
    const viewStates: Record<string, monaco.editor.ICodeEditorViewState> = {};
    for (const id of this.tabs) {
      const vs = id === this.active && !this.views.has(id) && this.editor.getModel() ? this.editor.saveViewState() : this.viewStates.get(id);
      if (vs) viewStates[id] = vs;
    }
    return { tabs: [...this.tabs], active: this.active, viewStates };
  }

  /** The cursor and scroll a file tab gets when it is next shown (a restored layout). */
  presetViewState(id: string, state: monaco.editor.ICodeEditorViewState): void {
    this.viewStates.set(id, state);
  }

  /**
   * Opens (or focuses) a file tab, optionally revealing a position or range. With `focus: false`
   * the keyboard focus stays where it is (a step that finishes late must not take it from a dialog
   * or list the user opened meanwhile).
   */
  async open(path: string, where?: monaco.IRange | monaco.IPosition, opts: { focus?: boolean } = {}): Promise<void> {
    let fs: FileState;
    try {
      fs = await this.workspace.ensureModel(path);
    } catch (e) {
      toast('error', `Cannot open ${path}: ${(e as Error).message}`);
      return;
    }
    if (isGeneratedC(path) && !this.guards.has(path)) {
      // after every text change (typing, undo, a reload or merge from disk): the regions as they are
      // now give the decorations and whether the cursor may type (a reload can move the regions
      // under a cursor that stays put, or carry the cursor into a region)
      const onRescan = () => {
        if (this.active !== path || this.editor.getModel() !== fs.model) return;
        this.guards.get(path)?.decorate(this.editor);
        this.updateReadOnly();
      };
      this.guards.set(path, new GeneratedGuard(fs.model, (msg) => toast('warning', msg), () => this.workspace.applyingExternal, onRescan));
    }
    if (!this.tabs.includes(path)) this.tabs.push(path);
    this.activate(path);
    if (where) {
      const range = 'startLineNumber' in where ? where : new monaco.Range(where.lineNumber, where.column, where.lineNumber, where.column);
      this.editor.setSelection(range);
      this.editor.revealRangeInCenter(range);
      // a restored view state may scroll after us: reveal again once laid out
      requestAnimationFrame(() => this.editor.getModel() === this.workspace.files.get(path)?.model && this.editor.revealRangeInCenterIfOutsideViewport(range));
    }
    if (opts.focus !== false) this.editor.focus();
  }

  /** Opens (or focuses) a view tab. */
  openView(view: ViewTab): void {
    this.views.set(view.id, view);
    if (!this.tabs.includes(view.id)) this.tabs.push(view.id);
    this.activate(view.id);
  }

  /** What the side pane shows (the docked architecture diagram, the Monitor), if anything. */
  get docked(): HTMLElement | undefined {
    return (this.sidePane.firstElementChild as HTMLElement | null) ?? undefined;
  }

  /** Shows `element` in a pane at the right of the editor (side by side), or removes the pane. */
  dock(element: HTMLElement | undefined): void {
    if (!element) this.sidePane.replaceChildren();
    // the element docked already stays where it is: moved again, it would lose the keyboard focus it holds
    else if (this.docked !== element || this.sidePane.childElementCount !== 1) this.sidePane.replaceChildren(element);
    this.sidePane.classList.toggle('hidden', !element);
    this.stack.classList.toggle('docked', !!element);
    this.onDocked.fire(element);
  }

  /** Shows a tab (a click, Enter on it) and puts the keyboard focus in it: Ctrl+Z then undoes in that file. */
  show(id: string): void {
    this.activate(id);
    this.focusActive();
  }

  /** Focuses the active tab's content: the editor for a file, the view's element otherwise. */
  focusActive(): void {
    if (!this.active) return;
    const view = this.views.get(this.active);
    if (!view) return this.editor.focus();
    const target = view.element.querySelector<HTMLElement>('[data-autofocus]') ?? view.element;
    if (target.tabIndex < 0 && !target.hasAttribute('tabindex')) target.tabIndex = -1;
    target.focus();
  }

  /** Moves the keyboard focus to the tab strip (the active tab). */
  focusTabs(): boolean {
    return this.tabFocus.focus();
  }

  guardOf(path: string): GeneratedGuard | undefined {
    return this.guards.get(path);
  }

  private activate(id: string): void {
    if (this.active && !this.views.has(this.active) && this.editor.getModel()) this.viewStates.set(this.active, this.editor.saveViewState());
    this.active = id;
    const view = this.views.get(id);
    if (view) {
      this.viewHost.replaceChildren(view.element);
      view.onShow?.();
    } else {
      const fs = this.workspace.files.get(id);
      if (fs && this.editor.getModel() !== fs.model) {
        this.editor.setModel(fs.model);
        const vs = this.viewStates.get(id);
        try {
          if (vs) this.editor.restoreViewState(vs);
        } catch {
          // a stored view state from an older layout that Monaco cannot read: the top of the file
        }
      }
      this.guards.get(id)?.decorate(this.editor);
      this.updateReadOnly();
      if (fs?.undecodableLine !== undefined) toast('warning', undecodableMessage(id, fs.undecodableLine));
      const guard = this.guards.get(id);
      if (guard?.malformed.length) toast('error', `${id} has malformed protected regions: ${guard.malformed.join('; ')}`);
    }
    this.render();
    this.onActiveChanged.fire(id);
  }

  close(id: string): void {
    const i = this.tabs.indexOf(id);
    if (i < 0) return;
    this.tabs.splice(i, 1);
    this.viewStates.delete(id);
    if (this.active === id) {
      const next = this.tabs[Math.min(i, this.tabs.length - 1)];
      this.active = undefined;
      if (next) this.activate(next);
      else {
        this.editor.setModel(null);
        this.render();
        this.onActiveChanged.fire(undefined);
      }
    } else this.render();
  }

  /** Keeps tabs pointing at the right files after a rename/move in the explorer. */
  renamePath(from: string, to: string): void {
    for (let i = 0; i < this.tabs.length; i++) {
      const t = this.tabs[i]!;
      if (t === from || t.startsWith(from + '/')) this.tabs[i] = to + t.slice(from.length);
    }
    if (this.active && (this.active === from || this.active.startsWith(from + '/'))) this.active = to + this.active.slice(from.length);
    this.render();
  }

  /**
   * Closes the tabs of files no longer in the workspace (deleted or moved: by this tab, another tab,
   * a command outside the IDE); the active one is said, so that typing does not go on, unnoticed,
   * into the file shown next (a generated module.c whose module another tab renamed closed silently).
   * Returns the paths closed.
   */
  closeMissing(exists: (p: string) => boolean): string[] {
    const gone = this.tabs.filter((t) => !this.views.has(t) && !exists(t));
    const wasActive = this.active !== undefined && gone.includes(this.active) ? this.active : undefined;
    // typing into the closed file must not go on into the one shown next: the keyboard leaves the
    // editor, for no element (not the tab strip either: a space there shows the tab and types on),
    // before the model changes (Monaco keeps the focus it had through setModel); a click, or Tab
    // to the tab strip then Enter, brings it back
    if (wasActive !== undefined && (this.editor.hasTextFocus() || this.editorHost.contains(document.activeElement))) (document.activeElement as HTMLElement | null)?.blur();
    for (const t of gone) this.close(t);
    if (wasActive) this.onActiveClosed.fire(wasActive);
    return gone;
  }

  /** The active tab was closed because its file left the workspace (closeMissing). */
  readonly onActiveClosed = new Emitter<string>();

  private updateReadOnly(): void {
    const guard = this.active ? this.guards.get(this.active) : undefined;
    const badLine = this.active ? this.workspace.files.get(this.active)?.undecodableLine : undefined;
    if (badLine !== undefined) {
      // bytes that are not UTF-8: a save would write U+FFFD over them (server/undecodable.ts)
      this.editor.updateOptions({ readOnly: true, readOnlyMessage: { value: undecodableMessage(this.active!, badLine) } });
      return;
    }
    const selections = this.editor.getSelections();
    const readOnly = !!guard && !!selections && !guard.selectionsEditable(selections);
    this.editor.updateOptions({ readOnly, readOnlyMessage: { value: GENERATED_READ_ONLY } });
  }

  private renderTabState(fs: FileState): void {
    const tab = this.tabsEl.querySelector(`[data-path="${CSS.escape(fs.path)}"]`);
    if (tab) tab.setAttribute('data-state', fs.state);
  }

  private render(): void {
    this.onTabsChanged.fire();
    this.tabsEl.replaceChildren(
      ...this.tabs.map((id) => {
        const view = this.views.get(id);
        const fs = this.workspace.files.get(id);
        const name = view ? view.title : id.split('/').pop()!;
        const icon = view ? view.icon : id.endsWith('.contract') ? '◈' : /\.(c|h)$/.test(id) ? 'C' : '≡';
        return h('div', {
          class: `tab${id === this.active ? ' active' : ''}${isGeneratedC(id) ? ' generated' : ''}`,
          role: 'tab', title: id, 'data-path': id, 'data-state': fs?.state ?? 'saved', 'aria-selected': String(id === this.active), tabindex: -1,
          onclick: () => this.show(id),
          onmousedown: (e: Event) => (e as MouseEvent).button === 1 && this.close(id),
        },
          h('span', { class: 'tab-icon', 'aria-hidden': 'true' }, icon), h('span', { class: 'tab-name' }, name),
          h('span', { class: 'tab-dirty', title: 'unsaved', 'aria-hidden': 'true' }, '●'),
          h('span', { class: 'tab-close', title: 'Close (Delete)', 'aria-hidden': 'true', onclick: (e: Event) => { e.stopPropagation(); this.close(id); } }, '×'));
      }),
    );
    this.tabFocus.forget(); // the tab stop is the active tab
    this.tabFocus.refresh();
    // the active tab is always visible in the strip (many tabs scroll)
    this.tabsEl.querySelector('.tab.active')?.scrollIntoView({ block: 'nearest', inline: 'nearest' });
    const isView = !!this.active && this.views.has(this.active);
    this.editorHost.classList.toggle('hidden', !this.active || isView);
    this.viewHost.classList.toggle('hidden', !isView);
    this.emptyEl.classList.toggle('hidden', !!this.active);
  }
}
