import './styles.css';
import { monaco } from './editor/monaco.js';
import { registerCactalLanguage, defineStudioTheme } from './editor/cactal-language.js';
import { createLayout } from './app/layout.js';
import { Workspace } from './workspace/workspace.js';
import { Explorer } from './panels/explorer.js';
import { EditorArea } from './editor/editor-area.js';
import { OutlinePanel } from './panels/outline.js';
import { ProblemsPanel, type Severity } from './panels/problems.js';
import { LspClient } from './lsp/lsp-client.js';
import { BuildPanel } from './build/build-panel.js';
import { GeneratePanel } from './build/generate-panel.js';
import { api, ApiError } from './api.js';
import { askText, askFields, confirmAction } from './util/dialog.js';
import { toast, dismissToasts } from './util/toast.js';
import { debounce } from './util/dom.js';
import { isContract, projectOf } from './workspace/file-kinds.js';
import { toRange } from './lsp/lsp-convert.js';
import { scanProtectedRegions } from './editor/protected-regions.js';
import { ConflictView } from './editor/conflict-view.js';
import { LayoutPersistence, layoutKey } from './app/layout-state.js';
import type { ArchitectureView } from './views/architecture-view.js';
import type { TimelineView } from './views/timeline-view.js';
import type { RunLogs } from './views/run-logs.js';
import { MonitorController } from './monitor/monitor-controller.js';
import { SimulateController } from './simulate/simulate-controller.js';
import { STEP_INPUT_FILE } from './simulate/step-input.js';

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
  workspace.onTree.on((entries) => {
    explorer.setEntries(entries);
    editors.closeMissing((p) => workspace.hasFile(p));
  });
  const updateSaveStatus = () => {
    const states = [...workspace.files.values()];
    const failed = states.filter((f) => f.state === 'error');
    const pending = states.filter((f) => f.state === 'dirty' || f.state === 'saving');
    const conflicts = states.filter((f) => f.state === 'conflict');
    ui.status.save.textContent = failed.length ? `✖ Save failed (${failed.length}) — kept locally`
      : conflicts.length ? `⚠ Overlapping edits (${conflicts.length}) — choose in the side-by-side view`
      : pending.length ? `● Saving ${pending.length}…` : '✓ All saved';
    ui.status.save.className = `status-item ${failed.length ? 'error' : conflicts.length || pending.length ? 'pending' : ''}`;
  };
  workspace.onFileState.on(updateSaveStatus);
  // a new save attempt (or one that went through) makes the last "could not save, retrying" notice out of date
  workspace.onFileState.on((fs) => (fs.state === 'saved' || fs.state === 'saving') && dismissToasts(`Could not save ${fs.path}:`));

  const rootHasContracts = () => workspace.entries.some((e) => e.type === 'file' && isContract(e.path));
  const currentProject = () => projectOf(editors.active && !editors.active.startsWith('view:') ? editors.active : explorer.selected?.path ?? '', rootHasContracts());

  // ---- problems: language server + gcc
  const sevOf = (s: number | undefined): Severity => (s === 1 ? 'error' : s === 2 ? 'warning' : s === 3 ? 'info' : 'hint');
  lsp.onDiagnostics.on(({ uri, diagnostics }) => {
    const path = workspace.pathOf(uri);
    if (!path || path.endsWith(STEP_INPUT_FILE)) return; // the Simulate panel's step field: checked in place
    problems.set(`cactal:${path}`, diagnostics.map((d) => ({
      path, line: d.range.start.line + 1, column: d.range.start.character + 1, severity: sevOf(d.severity), message: d.message, source: 'cactal',
    })));
  });
  problems.onCounts.on(({ errors, warnings }) => {
    ui.status.problems.innerHTML = '';
    ui.status.problems.append(`✖ ${errors}  ⚠ ${warnings}`);
    ui.status.problems.dataset.errors = String(errors);
    ui.status.problems.dataset.warnings = String(warnings);
  });
  ui.status.problems.addEventListener('click', () => ui.showPanel('problems'));
  problems.onOpen.on((p) => void editors.open(p.path, { lineNumber: p.line, column: p.column }));
  // gcc diagnostics also become squiggles in the generated files (owner 'gcc'), when they are open
  let gccMarked = new Set<string>();
  const applyGccMarkers = () => {
    const byPath = new Map<string, monaco.editor.IMarkerData[]>();
    for (const p of problems.all().filter((q) => q.source === 'gcc')) {
      const list = byPath.get(p.path) ?? byPath.set(p.path, []).get(p.path)!;
      const sev = p.severity === 'error' ? monaco.MarkerSeverity.Error : p.severity === 'warning' ? monaco.MarkerSeverity.Warning : monaco.MarkerSeverity.Info;
      list.push({ severity: sev, message: p.message, source: 'gcc', startLineNumber: p.line, startColumn: p.column, endLineNumber: p.line, endColumn: p.column + 1 });
    }
    for (const path of new Set([...gccMarked, ...byPath.keys()])) {
      const model = workspace.files.get(path)?.model;
      if (model && !model.isDisposed()) monaco.editor.setModelMarkers(model, 'gcc', byPath.get(path) ?? []);
    }
    gccMarked = new Set(byPath.keys());
  };
  problems.onCounts.on(() => applyGccMarkers());
  editors.onActiveChanged.on(() => applyGccMarkers());
  build.onDiagnostics.on((diags) => {
    const srcGen = `${currentBuildProject ? `${currentBuildProject}/` : ''}src-gen/`;
    problems.set('gcc', diags.map((d) => ({
      path: srcGen + d.file, line: d.line, column: d.column || 1,
      severity: d.severity === 'note' ? 'info' : d.severity, message: d.message + (d.protectedRegion ? ` (in region ${d.protectedRegion.id})` : ''), source: 'gcc',
    })));
    if (diags.some((d) => d.severity === 'error')) ui.showPanel('problems');
  });

  // ---- explorer and file operations
  explorer.onOpen.on((path) => void editors.open(path));
  editors.onActiveChanged.on((id) => {
    const isFile = id && !id.startsWith('view:');
    explorer.setActive(isFile ? id : undefined);
    const fs = isFile ? workspace.files.get(id) : undefined;
    const guard = isFile ? editors.guardOf(id) : undefined;
    if (fs && guard) showRegionOutline(fs.model);
    else outline.show(fs && isContract(id!) ? fs.model.uri.toString() : undefined);
    ui.status.lang.textContent = fs ? (fs.model.getLanguageId() === 'c' ? 'C (generated)' : 'Cactal') : '';
  });
  const showRegionOutline = (model: monaco.editor.ITextModel) =>
    outline.showRegions(
      scanProtectedRegions(model.getValue()).regions.map((r) => ({ id: r.id, line: model.getPositionAt(r.start).lineNumber, offset: r.start })),
      (region) => {
        const pos = model.getPositionAt(region.offset);
        editors.editor.setPosition(pos);
        editors.editor.revealPositionInCenter(pos);
        editors.editor.focus();
      },
    );
  editors.editor.onDidChangeModelContent(() => {
    const model = editors.editor.getModel();
    if (model && editors.active && editors.guardOf(editors.active)) showRegionOutline(model);
    else outline.refresh();
  });
  editors.editor.onDidChangeCursorPosition((e) => (ui.status.cursor.textContent = `Ln ${e.position.lineNumber}, Col ${e.position.column}`));

  const report = (e: unknown) => toast('error', e instanceof ApiError ? e.message : String(e));
  const join = (dir: string, name: string) => (dir ? `${dir}/${name}` : name);
  const newEntry = async (type: 'file' | 'dir', folder = explorer.targetFolder()) => {
    const name = await askText(type === 'file' ? 'New file' : 'New folder', type === 'file' ? 'new.contract' : 'folder', `in ${folder || 'the workspace root'}`);
    if (!name) return;
    try {
      const { path } = await api.create(join(folder, name), type);
      await workspace.refreshTree();
      if (type === 'file') await editors.open(path);
      else explorer.expand(path);
    } catch (e) {
      report(e);
    }
  };
  ui.toolbar.newFile.addEventListener('click', () => void newEntry('file'));
  ui.toolbar.newFolder.addEventListener('click', () => void newEntry('dir'));
  ui.toolbar.newProject.addEventListener('click', async () => {
    const hint = rootHasContracts()
      ? 'Folder to create. This workspace already holds a project and the language server checks all files together: to work on the new project alone, open its folder with `contract serve <folder>`.'
      : 'Folder to create (empty = the workspace root). Creates datatype, module1, module2, schema, sched and supervisor .contract files.';
    const folder = await askText('New project from the report templates', rootHasContracts() ? 'my-robot' : '', hint);
    if (folder === null && rootHasContracts()) return;
    try {
      const r = await api.newProject(folder ?? '');
      await workspace.refreshTree();
      await Promise.all(r.files.map((f) => workspace.ensureModel(f)));
      lsp.revalidateAll();
      await editors.open(r.files.find((f) => f.endsWith('supervisor.contract')) ?? r.files[0]!);
      toast('info', `Project created in ${r.folder || 'the workspace root'}`);
    } catch (e) {
      report(e);
    }
  });
  explorer.onContextAction.on(async ({ action, entry }) => {
    try {
      if (action === 'new-file') return void newEntry('file', entry.path);
      if (action === 'new-folder') return void newEntry('dir', entry.path);
      if (action === 'delete') {
        if (!(await confirmAction(`Delete ${entry.path}?`, entry.type === 'dir' ? 'The folder and everything in it will be deleted from disk.' : 'The file will be deleted from disk.'))) return;
        await api.remove(entry.path);
        for (const p of [...workspace.files.keys()]) if (p === entry.path || p.startsWith(entry.path + '/')) workspace.dropFile(p);
        await workspace.refreshTree();
        lsp.revalidateAll();
      }
      if (action === 'rename') {
        const name = await askText(`Rename ${entry.path}`, entry.name);
        if (!name || name === entry.name) return;
        const dir = entry.path.includes('/') ? entry.path.slice(0, entry.path.lastIndexOf('/')) : '';
        const to = join(dir, name);
        await workspace.saveAll();
        await api.rename(entry.path, to);
        const moved = [...workspace.files.keys()].filter((p) => p === entry.path || p.startsWith(entry.path + '/'));
        for (const p of moved) workspace.dropFile(p);
        editors.renamePath(entry.path, to);
        await workspace.refreshTree();
        for (const p of moved) {
          const np = to + p.slice(entry.path.length);
          if (isContract(np)) await workspace.ensureModel(np);
        }
        lsp.revalidateAll();
        if (editors.active && workspace.hasFile(editors.active)) await editors.open(editors.active);
      }
    } catch (e) {
      report(e);
    }
  });

  // ---- external changes
  const refreshTree = debounce(() => void workspace.refreshTree().then(async () => {
    let changed = false;
    for (const p of workspace.allFiles().filter(isContract)) {
      if (!workspace.files.has(p)) {
        await workspace.ensureModel(p).catch(() => undefined);
        changed = true;
      }
    }
    for (const p of [...workspace.files.keys()]) {
      if (!workspace.hasFile(p) && workspace.files.get(p)!.state === 'saved') {
        workspace.dropFile(p);
        changed = true;
      }
    }
    if (changed) lsp.revalidateAll();
  }).catch(() => undefined), 150); // server unreachable: the reconnect ('hello') refreshes again
  const events = new EventSource('/api/events');
  events.addEventListener('change', (e) => {
    const { paths } = JSON.parse((e as MessageEvent).data) as { paths: string[] };
    refreshTree();
    for (const p of paths) void workspace.externalChange(p);
  });
  let wasDisconnected = false;
  events.onerror = () => {
    if (!wasDisconnected) toast('warning', 'Lost the connection to the IDE server: edits are kept in this browser until it is back');
    wasDisconnected = true;
  };
  events.addEventListener('hello', () => {
    if (wasDisconnected) {
      wasDisconnected = false;
      toast('info', 'Reconnected to the IDE server: saving pending edits');
      void workspace.saveAll();
      refreshTree();
    }
  });

  // ---- Generate All
  const generate = async (): Promise<boolean> => {
    ui.showPanel('generate');
    generatePanel.showRunning();
    ui.toolbar.generate.disabled = true;
    try {
      await workspace.saveAll();
      const project = currentProject();
      const r = await api.generate(project);
      generatePanel.show(r);
      problems.set('gcc', []); // the generated files changed: the last build's diagnostics are stale
      await workspace.refreshTree();
      explorer.expand(`${r.srcGen}/generated/architecture/modules`);
      for (const p of [...workspace.files.keys()]) if (p.startsWith(`${r.srcGen}/`)) void workspace.externalChange(p);
      if (r.errors.length) toast('error', `Generate All: ${r.errors.length} error(s) — see the Generate panel`);
      else if (r.orphaned.length) toast('warning', `Generate All: ${r.orphaned.length} orphaned region(s) moved to ${r.srcGen}/orphans`);
      return r.errors.length === 0;
    } catch (e) {
      generatePanel.showError(e instanceof ApiError ? e.message : String(e));
      return false;
    } finally {
      ui.toolbar.generate.disabled = false;
    }
  };
  ui.toolbar.generate.addEventListener('click', () => void generate());

  // ---- Build & Run / Stop
  let currentBuildProject = '';
  const RUN_SETTINGS_KEY = 'contract-studio:run-settings';
  type RunSettings = { duration: number; start?: string; cpus?: string; realtime?: boolean };
  const runSettings = (): RunSettings => {
    try {
      const v = JSON.parse(localStorage.getItem(RUN_SETTINGS_KEY) ?? '{}') as Partial<RunSettings>;
      return { duration: v.duration ?? 10, start: v.start || undefined, cpus: v.cpus || undefined, realtime: v.realtime === true || undefined };
    } catch {
      return { duration: 10 };
    }
  };
  ui.toolbar.runSettings.addEventListener('click', async () => {
    const cur = runSettings();
    const r = await askFields('Run settings', [
      { key: 'duration', label: 'Duration of a run (seconds, capped by the build service)', value: String(cur.duration) },
      { key: 'start', label: "Start request (START=), empty = the generator's default (first function of the top supervisor)", value: cur.start ?? '', hint: 'GLB.mission(consigne={1.0,2.0,3.0})' },
      { key: 'cpus', label: 'Pin every module to these CPUs (CPUS=; steadier periods), empty = the system places them', value: cur.cpus ?? '', hint: '1 or 0-1' },
      { key: 'realtime', label: 'Real-time: modules take their SCHED_FIFO priorities in the sandbox, bounded (refused, saying why, where the host cannot grant it)', value: cur.realtime ? 'yes' : '', checkbox: true },
    ]);
    if (!r) return;
    const duration = Number(r.duration);
    if (!Number.isFinite(duration) || duration <= 0) return toast('error', `Duration must be a positive number of seconds, not "${r.duration}"`);
    const cpus = (r.cpus ?? '').trim();
    if (cpus && !/^\d+(-\d+)?(,\d+(-\d+)?)*$/.test(cpus)) return toast('error', `CPUs must be a list such as 1, 0-1 or 0,2, not "${cpus}"`);
    const realtime = r.realtime === 'yes';
    localStorage.setItem(RUN_SETTINGS_KEY, JSON.stringify({ duration, start: r.start, ...(cpus ? { cpus } : {}), ...(realtime ? { realtime } : {}) }));
    toast('info', `Runs last ${duration} s${r.start ? `, start ${r.start}` : ''}${cpus ? `, modules on CPUs ${cpus}` : ''}${realtime ? ', real-time priorities' : ''}`);
  });
  const run = async () => {
    ui.showPanel('output');
    try {
      await workspace.saveAll();
      currentBuildProject = currentProject();
      const settings = runSettings();
      await build.start(currentBuildProject ? `${workspace.root}/${currentBuildProject}` : workspace.root, 'run', settings.duration, settings.start, settings.cpus, settings.realtime);
    } catch (e) {
      report(e);
      build.append({ t: Date.now(), step: 'prepare', source: 'service', stream: 'system', line: `could not start: ${(e as Error).message}` });
    }
  };
  build.onStatus.on(({ status, message, running }) => {
    ui.toolbar.run.disabled = running;
    ui.toolbar.stop.disabled = !running;
    ui.status.job.textContent = `${running ? '⟳' : status === 'succeeded' ? '✓' : '■'} ${status}${message ? `: ${message}` : ''}`;
    ui.status.job.dataset.status = status;
  });
  // the Monitor: live during a run (trace events), then the job's CSV logs as a recorded run
  const monitor = new MonitorController({ editors, lsp, workspace, build, button: ui.toolbar.monitor, project: () => currentProject() });
  // Simulate: supervisors in virtual time, shown in its panel and in the Monitor (docs/simulation.md "In the IDE")
  const simulate = new SimulateController({ lsp, workspace, monitor, project: () => currentProject(), reveal: () => ui.showPanel('simulate') });
  ui.addPanel('simulate', 'Simulate', simulate.panel.element).addEventListener('click', () => void simulate.refreshFunctions());
  // a finished run's CSV logs (collected from the sandbox by the build service) feed the timeline
  build.onFinished.on(({ jobId, action }) => {
    if (action !== 'run') return;
    void (async () => {
      try {
        const { fetchJobLogs } = await import('./views/run-logs.js');
        const logs = await fetchJobLogs(jobId);
        for (const p of logs.problems) build.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `timeline: ${p}` });
        if (!logs.files.length) return;
        void monitor.showRecorded(jobId, logs);
        lastRunLogs = logs;
        timeline?.showRun(logs);
        toast('info', `Run logs of ${logs.files.length} module(s) ready: ▤ Timeline shows the run's activations`);
      } catch (e) {
        build.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `timeline: could not fetch the run's logs: ${(e as Error).message}` });
      }
    })();
  });
  ui.toolbar.run.addEventListener('click', () => void run());
  ui.toolbar.stop.addEventListener('click', () => void build.stop());

  // ---- views (lazy: elkjs and the timeline load on first use)
  let arch: ArchitectureView | undefined;
  let archDocked = false;
  const archTab = () => ({ id: 'view:architecture', title: 'Architecture', icon: '⬡', element: arch!.element, onShow: () => void arch!.update() });
  const archRefresh = debounce(() => {
    if (arch && (archDocked || editors.active === 'view:architecture')) void arch.update();
  }, 400);
  const toggleDock = () => {
    archDocked = !archDocked;
    if (archDocked) {
      editors.close('view:architecture');
      editors.dock(arch!.element);
      void arch!.update();
    } else {
      editors.dock(undefined);
      editors.openView(archTab());
    }
  };
  ui.toolbar.arch.addEventListener('click', async () => {
    if (!arch) {
      const { ArchitectureView } = await import('./views/architecture-view.js');
      arch = new ArchitectureView(() => lsp.architecture(), toggleDock);
    }
    if (archDocked) {
      editors.dock(arch.element); // the Monitor may have taken the side pane since
      void arch.update();
    }
    else editors.openView(archTab());
  });
  monaco.editor.onDidCreateModel((m) => m.onDidChangeContent(() => archRefresh()));
  for (const m of monaco.editor.getModels()) m.onDidChangeContent(() => archRefresh());
  let timeline: TimelineView | undefined;
  let lastRunLogs: RunLogs | undefined;
  ui.toolbar.timeline.addEventListener('click', async () => {
    if (!timeline) {
      const { TimelineView } = await import('./views/timeline-view.js');
      timeline = new TimelineView(() => currentProject(), workspace);
      if (lastRunLogs) timeline.showRun(lastRunLogs);
    }
    editors.openView({ id: 'view:timeline', title: 'Timeline', icon: '▤', element: timeline.element, onShow: () => void timeline!.update() });
  });

  // ---- rename refactoring carries generated files and region IDs over
  lsp.onRename.on(({ oldName: old, newName, topLevel }) => {
    if (!old || old === newName || !topLevel) return; // ports, variables, labels: nothing generated is named after them
    void (async () => {
      await new Promise((r) => setTimeout(r, 50));
      await workspace.saveAll();
      const project = currentProject();
      const r = await api.renameEntity(project, old, newName);
      if (r.movedPaths.length || r.regionIds.length) {
        toast('info', `Renamed ${old} → ${newName}: ${r.movedPaths.length} generated path(s) and ${r.regionIds.length} protected region(s) carried over`);
        await workspace.refreshTree();
        for (const m of r.movedPaths) {
          const base = `${project ? `${project}/` : ''}src-gen/`;
          const from = base + m.from;
          if (workspace.files.has(from) || [...workspace.files.keys()].some((p) => p.startsWith(from + '/'))) {
            for (const p of [...workspace.files.keys()]) if (p === from || p.startsWith(from + '/')) workspace.dropFile(p);
            editors.renamePath(from, base + m.to);
          }
        }
        if (editors.active?.includes('/src-gen/') || editors.active?.startsWith('src-gen/')) await editors.open(editors.active);
        await generate();
      }
    })().catch(report);
  });

  // ---- shortcuts
  window.addEventListener('keydown', (e) => {
    if ((e.ctrlKey || e.metaKey) && e.shiftKey && e.key.toLowerCase() === 'g') {
      e.preventDefault();
      void generate();
    }
    if ((e.ctrlKey || e.metaKey) && e.shiftKey && e.key.toLowerCase() === 'b') {
      e.preventDefault();
      void run();
    }
  });
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
  void api.info().then((info) => {
    if (info.buildAvailable) return;
    ui.toolbar.run.disabled = true;
    ui.toolbar.run.title = `Build & Run unavailable: ${info.buildService}`;
    ui.status.job.textContent = '■ build service unavailable';
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
  layout.start();
  performance.mark('ide:editor-open');
  await lsp.workspaceBuilt();
  performance.mark('ide:ready');
  document.body.dataset.ready = 'true';
  (window as unknown as { __ide: unknown }).__ide = { workspace, editors, lsp, problems, build, monaco, monitor, simulate };
}

void main();
