import { monaco } from '../editor/monaco.js';
import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import type { ArchitectureView, CursorAt } from '../views/architecture-view.js';
import type { ArchLocation } from '../lsp/architecture-model.js';
import type { TimelineView } from '../views/timeline-view.js';
import type { RunLogs } from '../views/run-logs.js';
import type { ModelModules } from '../views/activation-log.js';
import { readSupervisorSymbols } from '../monitor/supervisor-symbols.js';
import { isContract } from '../workspace/file-kinds.js';
import { debounce } from '../util/dom.js';

/**
 * The Architecture diagram (in a tab or docked beside the editor) and the Timeline; both load lazily
 * (elkjs and the timeline cost nothing until first opened).
 */
export class ViewsController {
  arch: ArchitectureView | undefined;
  private archDocked = false;
  private timeline: TimelineView | undefined;
  private lastRunLogs: RunLogs | undefined;

  constructor(private readonly d: {
    editors: EditorArea; lsp: LspClient; workspace: Workspace;
    toolbar: { arch: HTMLButtonElement; timeline: HTMLButtonElement }; project(): string;
  }) {
    d.toolbar.arch.addEventListener('click', () => void this.openArchitecture());
    d.toolbar.timeline.addEventListener('click', () => void this.openTimeline());
    const archRefresh = debounce(() => {
      if (this.arch && (this.archDocked || d.editors.active === 'view:architecture')) void this.arch.update();
    }, 400);
    // an edit, a file loaded (opened, or made on disk by another program: external-changes.ts) or dropped
    monaco.editor.onDidCreateModel((m) => {
      m.onDidChangeContent(() => archRefresh());
      archRefresh();
    });
    monaco.editor.onWillDisposeModel(() => archRefresh());
    for (const m of monaco.editor.getModels()) m.onDidChangeContent(() => archRefresh());
    // the diagram shows the schema the editor's cursor is in
    const follow = debounce(() => this.arch?.follow(this.cursor()), 150);
    d.editors.editor.onDidChangeCursorPosition(follow);
    d.editors.onActiveChanged.on(follow);
  }

  /** The active editor's cursor (0-based), when a file tab is active. */
  private cursor(): CursorAt | undefined {
    const { editors } = this.d;
    const model = editors.editor.getModel();
    const pos = editors.editor.getPosition();
    if (!model || !pos || !editors.active || editors.active.startsWith('view:')) return undefined;
    return { uri: model.uri.toString(), line: pos.lineNumber - 1, character: pos.column - 1 };
  }

  /** A click on the diagram: the definition in its file, beside the docked diagram or in place of the diagram's tab. */
  private async goTo(where: ArchLocation): Promise<void> {
    const path = this.d.workspace.pathOf(where.uri);
    if (!path) return;
    await this.d.editors.open(path, { lineNumber: where.line + 1, column: where.character + 1 });
  }

  private archTab() {
    return { id: 'view:architecture', title: 'Architecture', icon: '⬡', element: this.arch!.element, onShow: () => void this.arch!.update() };
  }

  private toggleDock(): void {
    const { editors } = this.d;
    this.archDocked = !this.archDocked;
    if (this.archDocked) {
      editors.close('view:architecture');
      editors.dock(this.arch!.element);
      void this.arch!.update();
    } else {
      editors.dock(undefined);
      editors.openView(this.archTab());
    }
  }

  async openArchitecture(): Promise<void> {
    const { editors } = this.d;
    if (!this.arch) {
      const { ArchitectureView } = await import('../views/architecture-view.js');
      this.arch = new ArchitectureView(() => this.d.lsp.architecture(), () => this.toggleDock(), (where) => void this.goTo(where));
      this.arch.follow(this.cursor());
    }
    if (this.archDocked) {
      editors.dock(this.arch.element); // the Monitor may have taken the side pane since
      void this.arch.update();
    } else editors.openView(this.archTab());
  }

  /**
   * The Architecture command (Alt+Shift+D, the palette): opens the diagram and puts the keyboard
   * focus in it (it stayed on the page's body), as Open Timeline does. The toolbar button and a
   * reload's restored layout open it without taking the focus from the editor.
   */
  async openArchitectureFocused(): Promise<void> {
    await this.openArchitecture();
    if (this.archDocked) this.arch?.element.querySelector<HTMLElement>('[data-autofocus]')?.focus({ focusVisible: true } as FocusOptions);
    else this.d.editors.focusActive();
  }

  /**
   * The project's supervisors and other modules, from the language server's symbols (the Monitor's
   * reading, supervisor-symbols.ts); undefined when it does not answer within 2 s or names none.
   */
  private async modelModules(): Promise<ModelModules | undefined> {
    const project = this.d.project();
    const files = this.d.workspace.allFiles().filter((p) => isContract(p) && (!project || p.startsWith(`${project}/`)));
    let timer: ReturnType<typeof setTimeout> | undefined;
    const late = new Promise<undefined>((r) => (timer = setTimeout(() => r(undefined), 2000)));
    const symbols = await Promise.race([readSupervisorSymbols(files.map((p) => this.d.workspace.uriOf(p).toString()), (uri) => this.d.lsp.documentSymbols(uri)).catch(() => undefined), late]);
    clearTimeout(timer);
    if (!symbols || (!symbols.catalogue.size && !symbols.modules.size)) return undefined;
    return { supervisors: new Set(symbols.catalogue.keys()), modules: new Set(symbols.modules.keys()) };
  }

  async openTimeline(): Promise<void> {
    if (!this.timeline) {
      const { TimelineView } = await import('../views/timeline-view.js');
      this.timeline = new TimelineView(() => this.d.project(), this.d.workspace, () => this.modelModules());
      if (this.lastRunLogs) this.timeline.showRun(this.lastRunLogs);
    }
    const timeline = this.timeline;
    this.d.editors.openView({ id: 'view:timeline', title: 'Timeline', icon: '▤', element: timeline.element, onShow: () => void timeline.update() });
    this.d.editors.focusActive(); // the keyboard goes to the timeline (arrows, Home, End)
  }

  /** A finished run's logs: the Timeline shows its activations (now if open, else when opened). */
  showRun(logs: RunLogs): void {
    this.lastRunLogs = logs;
    this.timeline?.showRun(logs);
  }
}
