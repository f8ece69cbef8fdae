import { monaco } from '../editor/monaco.js';
import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import type { ArchitectureView } from '../views/architecture-view.js';
import type { TimelineView } from '../views/timeline-view.js';
import type { RunLogs } from '../views/run-logs.js';
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
    monaco.editor.onDidCreateModel((m) => m.onDidChangeContent(() => archRefresh()));
    for (const m of monaco.editor.getModels()) m.onDidChangeContent(() => archRefresh());
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
      this.arch = new ArchitectureView(() => this.d.lsp.architecture(), () => this.toggleDock());
    }
    if (this.archDocked) {
      editors.dock(this.arch.element); // the Monitor may have taken the side pane since
      void this.arch.update();
    } else editors.openView(this.archTab());
  }

  async openTimeline(): Promise<void> {
    if (!this.timeline) {
      const { TimelineView } = await import('../views/timeline-view.js');
      this.timeline = new TimelineView(() => this.d.project(), this.d.workspace);
      if (this.lastRunLogs) this.timeline.showRun(this.lastRunLogs);
    }
    const timeline = this.timeline;
    this.d.editors.openView({ id: 'view:timeline', title: 'Timeline', icon: '▤', element: timeline.element, onShow: () => void timeline.update() });
  }

  /** A finished run's logs: the Timeline shows its activations (now if open, else when opened). */
  showRun(logs: RunLogs): void {
    this.lastRunLogs = logs;
    this.timeline?.showRun(logs);
  }
}
