import './styles.css';
import { monaco } from './editor/monaco.js';
import { registerCactalLanguage, defineStudioTheme } from './editor/cactal-language.js';
import { createLayout } from './app/layout.js';
import { Workspace } from './workspace/workspace.js';
import { Explorer } from './panels/explorer.js';
import { EditorArea } from './editor/editor-area.js';
import { OutlinePanel } from './panels/outline.js';
import { ProblemsPanel } from './panels/problems.js';
import { LspClient } from './lsp/lsp-client.js';
import { BuildPanel } from './build/build-panel.js';
import { GeneratePanel } from './build/generate-panel.js';
import { api } from './api.js';
import { toast } from './util/toast.js';
import { isContract } from './workspace/file-kinds.js';
import { toRange } from './lsp/lsp-convert.js';
import { ConflictView } from './editor/conflict-view.js';
import { LayoutPersistence, layoutKey } from './app/layout-state.js';
import { MonitorController } from './monitor/monitor-controller.js';
import { SimulateController } from './simulate/simulate-controller.js';
import { showSaveStatus } from './app/save-status.js';
import { connectProblems } from './app/problems-controller.js';
import { followActiveFile } from './app/active-file-panels.js';
import { FileOperations } from './app/file-operations.js';
import { watchExternalChanges } from './app/external-changes.js';
import { followSharedRuns } from './app/shared-runs.js';
import { GenerateController } from './app/generate-controller.js';
import { RunController } from './app/run-controller.js';
import { ViewsController } from './app/views-controller.js';
import { carryRenamesToGenerated } from './app/rename-carryover.js';
import { registerIdeCommands } from './app/ide-commands.js';
import type { IdeHook } from './app/ide-hook.js';

/** Builds the IDE: the parts (src/panels, src/editor, ...), the feature controllers (src/app) and the start-up sequence. */
async function main(): Promise<void> {
  performance.mark('ide:main');
  registerCactalLanguage();
  defineStudioTheme();
  const ui = createLayout(document.getElementById('app')!);
  const workspace = new Workspace();
  const explorer = new Explorer(ui.explorerBody);
  const editors = new EditorArea(ui.editorRoot, workspace);
  const lsp = new LspClient();
  // the language worker boots (its own thread) while the UI and the workspace load
  const lspStarted = lsp.start().then(() => performance.mark('ide:lsp-initialized'));
  const problems = new ProblemsPanel(document.createElement('div'));
  const build = new BuildPanel();
  const generatePanel = new GeneratePanel((path, line) => void editors.open(path, line ? { lineNumber: line, column: 1 } : undefined));
  ui.addPanel('problems', 'Problems', problems.root);
  ui.addPanel('output', 'Build & Run', build.element);
  ui.addPanel('generate', 'Generate', generatePanel.element);
  ui.showPanel('problems');
  const outline = new OutlinePanel(ui.outlineBody, (uri) => lsp.documentSymbols(uri), (range) => {
    editors.editor.setSelection(toRange(range));
    editors.editor.revealRangeInCenter(toRange(range));
    editors.editor.focus();
  });
  outline.show(undefined);

  workspace.onNotice.on((n) => toast(n.level, n.text));
  new ConflictView(workspace); // overlapping edits of a file: side by side until the user chose
  lsp.onMessage.on((m) => toast(m.type === 1 ? 'error' : m.type === 2 ? 'warning' : 'info', String(m.message).slice(0, 500)));
  const files = new FileOperations({ workspace, editors, explorer, lsp });
  workspace.onTree.on((entries) => {
    explorer.setEntries(entries);
    lsp.setProjectLayout(workspace.projectLayout()); // names and project-wide checks per project
    editors.closeMissing((p) => workspace.hasFile(p) || files.isRenaming(p));
  });
  // the file of the active tab left the workspace (another tab's rename, a delete): said, with the tab now shown
  editors.onActiveClosed.on((path) => toast('warning', `${path} is no longer in the workspace (renamed, moved or deleted, perhaps by another tab): its tab was closed${editors.active ? `; ${editors.active} is shown now, the keyboard out of it (click in it to type there)` : ''}`));
  showSaveStatus(workspace, ui.status.save);

  ui.toolbar.newFile.addEventListener('click', () => void files.newEntry('file'));
  ui.toolbar.newFolder.addEventListener('click', () => void files.newEntry('dir'));
  ui.toolbar.newProject.addEventListener('click', () => void files.newProject());
  // the project of the active file by the rule the CLI follows too (docs/codegen.md "Where a project is")
  const currentProject = () => workspace.projectRootOf(editors.active && !editors.active.startsWith('view:') ? editors.active : explorer.selected?.path ?? '').root;

  const runs = new RunController({ workspace, build, toolbar: ui.toolbar, jobStatus: ui.status.job, showPanel: ui.showPanel, project: currentProject });
  connectProblems({ problems, workspace, editors, lsp, build, statusEl: ui.status.problems, showPanel: ui.showPanel, buildProject: () => runs.project });
  followActiveFile({ editors, workspace, explorer, outline, langEl: ui.status.lang, cursorEl: ui.status.cursor });
  followSharedRuns(watchExternalChanges(workspace, lsp), runs);
  const generator = new GenerateController({ workspace, explorer, problems, panel: generatePanel, button: ui.toolbar.generate, showPanel: ui.showPanel, project: currentProject });

  // the Monitor: live during a run (trace events), then the job's CSV logs as a recorded run
  const monitor = new MonitorController({ editors, lsp, workspace, build, button: ui.toolbar.monitor, project: () => currentProject(), projectOf: (path) => workspace.projectRootOf(path).root });
  // a trace file (`contract run --trace`: *.jsonl) opens in the Monitor as the run it records; any other file in its editor
  explorer.onOpen.on((path) => void (path.endsWith('.jsonl') ? monitor.openTraceFile(path) : editors.open(path)));
  // Simulate: supervisors in virtual time, shown in its panel and in the Monitor (docs/simulation.md "In the IDE")
  const simulate = new SimulateController({ lsp, workspace, monitor, project: () => currentProject(), reveal: () => ui.showPanel('simulate') });
  // its functions read when it is shown (also by the layout restored after a reload), and the session this browser kept grown again
  ui.addPanel('simulate', 'Simulate', simulate.panel.element, () => void simulate.refreshFunctions());
  const views = new ViewsController({ editors, lsp, workspace, toolbar: ui.toolbar, project: currentProject });
  runs.onLostRun.on(({ jobId }) => void monitor.listLost(jobId));
  runs.onRunLogs.on(({ jobId, logs }) => {
    void monitor.showRecorded(jobId, logs);
    views.showRun(logs);
  });
  carryRenamesToGenerated({ lsp, workspace, editors, project: currentProject, generate: () => generator.generate() });

  // shortcuts, quick open and the command palette (docs/ide.md "Keyboard")
  const commands = registerIdeCommands({
    workspace, editors, explorer, outline, problems, files, generator, runs, views, openMonitor: () => monitor.open(),
    openSimulate: () => {
      ui.showPanel('simulate');
      simulate.panel.focus();
    },
    showPanel: ui.showPanel, focusPanelTabs: ui.focusPanelTabs,
  });
  ui.onPanelEscape(() => editors.focusActive());
  simulate.panel.onEscape = () => editors.focusActive();
  window.addEventListener('beforeunload', () => void workspace.saveAll());

  // ---- start
  try {
    await workspace.load();
    performance.mark('ide:workspace-loaded');
  } catch (e) {
    toast('error', `Cannot load the workspace: ${(e as Error).message}`);
    return;
  }
  ui.workspaceName.textContent = workspace.name;
  const info = api.info().then((i) => {
    if (!i.buildAvailable) runs.disable(i.buildService);
    return i;
  }).catch(() => undefined);
  document.title = `${workspace.name} — ContrACT Studio`;
  explorer.setEntries(workspace.entries);
  await lspStarted;
  ui.status.lsp.textContent = '● Cactal language server';
  ui.status.lsp.classList.add('ok');
  // tabs, cursors, sizes and views of the last session of this workspace (app/layout-state.ts)
  const viewButtons: Record<string, HTMLButtonElement> = { 'view:architecture': ui.toolbar.arch, 'view:timeline': ui.toolbar.timeline };
  const layout = new LayoutPersistence({
    key: layoutKey(workspace.root), editors, hasFile: (p) => workspace.hasFile(p), showPanel: ui.showPanel,
    openView: async (id) => {
      viewButtons[id]?.click();
      for (let i = 0; viewButtons[id] && i < 200 && !editors.isOpen(id); i++) await new Promise((r) => setTimeout(r, 50));
      return editors.isOpen(id);
    },
  });
  const first = workspace.allFiles().find((p) => p.endsWith('supervisor.contract')) ?? workspace.allFiles().find(isContract);
  if (!(await layout.restore()) && first) await editors.open(first);
  ui.refreshResizers();
  layout.start();
  // a run this tab started before a reload goes on in the build service: follow it again
  // then the workspace log folder or trace file this tab's Monitor showed, read again (it comes back on top)
  void info.then(async (i) => {
    if (i?.buildAvailable) await runs.resume().catch(() => false);
    await monitor.restore();
  });
  performance.mark('ide:editor-open');
  // ready: the first full validation of the workspace published and shown (its counts in the status bar)
  await lsp.workspaceValidated();
  problems.renderIfPending();
  performance.mark('ide:ready');
  document.body.dataset.ready = 'true';
  // ELK's worker warmed up while nothing else runs (architecture-view.ts warmUpLayout): the first
  // diagram (the Monitor that Build & Run opens, the Architecture tab) no longer compiles it then
  const whenIdle = window.requestIdleCallback ?? ((run: () => void) => setTimeout(run, 1000));
  whenIdle(() => void import('./views/architecture-view.js').then((m) => m.warmUpLayout()).catch(() => undefined));
  // the test hook of the browser tests (app/ide-hook.ts)
  const hook: IdeHook = { workspace, editors, lsp, problems, build, monaco, monitor, simulate, commands, views };
  window.__ide = hook;
}

void main();
