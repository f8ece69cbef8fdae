import type { EditorArea } from '../editor/editor-area.js';
import type { Explorer } from '../panels/explorer.js';
import type { OutlinePanel } from '../panels/outline.js';
import type { ProblemsPanel } from '../panels/problems.js';
import type { Workspace } from '../workspace/workspace.js';
import { toast } from '../util/toast.js';
import { CommandRegistry, type Command } from './commands.js';
import type { FileOperations } from './file-operations.js';
import type { GenerateController } from './generate-controller.js';
import type { RunController } from './run-controller.js';
import type { ViewsController } from './views-controller.js';
import { openCommandPalette, openQuickOpen } from './palette-controller.js';

export interface IdeParts {
  workspace: Workspace;
  editors: EditorArea;
  explorer: Explorer;
  outline: OutlinePanel;
  problems: ProblemsPanel;
  files: FileOperations;
  generator: GenerateController;
  runs: RunController;
  views: ViewsController;
  /** Shows the Monitor (it stays shown if it was) and puts the keyboard focus in it. */
  openMonitor(): Promise<void>;
  /** Shows the Simulate panel and puts the keyboard focus on its supervisor function. */
  openSimulate(): void;
  showPanel(id: string): void;
  focusPanelTabs(): void;
}

/**
 * The IDE's commands and shortcuts (docs/ide.md "Keyboard"): quick open, the command palette, Generate
 * All, Build & Run, Stop, the views, the panels, file operations. Escape in any list goes back to the editor.
 */
export function registerIdeCommands(p: IdeParts): CommandRegistry {
  const { workspace, editors, explorer } = p;
  const registry = new CommandRegistry();
  const activeFile = () => (editors.active && !editors.active.startsWith('view:') ? editors.active : undefined);
  const focusPanel = (id: string, focusList: () => boolean) => {
    p.showPanel(id);
    if (!focusList()) p.focusPanelTabs();
  };
  const commands: Command[] = [
    { id: 'quickOpen', label: 'Go to File…', keys: ['Ctrl+P'], run: () => openQuickOpen(workspace, editors) },
    { id: 'commandPalette', label: 'Show All Commands', keys: ['F1', 'Ctrl+Shift+P'], inPalette: false, run: () => openCommandPalette(registry, editors) },
    { id: 'generate', label: 'Generate All', keys: ['Ctrl+Shift+G'], run: () => p.generator.generate() },
    { id: 'run', label: 'Build & Run', keys: ['Ctrl+Shift+B'], run: () => p.runs.run() },
    { id: 'stop', label: 'Stop the running job', keys: ['Alt+Shift+S'], run: () => p.runs.stop() },
    { id: 'runSettings', label: 'Run settings: duration, start request, init time, CPUs, stdin, real-time', run: () => p.runs.editSettings() },
    { id: 'architecture', label: 'Open Architecture diagram', keys: ['Alt+Shift+D'], run: () => p.views.openArchitectureFocused() },
    { id: 'timeline', label: 'Open Timeline', keys: ['Alt+Shift+T'], run: () => p.views.openTimeline() },
    { id: 'monitor', label: 'Open Monitor', keys: ['Alt+Shift+M'], run: () => p.openMonitor() },
    { id: 'simulate', label: 'Open Simulate panel', keys: ['Alt+Shift+U'], run: () => p.openSimulate() },
    { id: 'problems', label: 'Show Problems', keys: ['Ctrl+Shift+M'], run: () => focusPanel('problems', () => p.problems.focus()) },
    { id: 'output', label: 'Show Build & Run output', keys: ['Alt+Shift+B'], run: () => focusPanel('output', () => false) },
    { id: 'explorer', label: 'Focus Explorer', keys: ['Ctrl+Shift+E'], run: () => explorer.focus() },
    { id: 'outline', label: 'Focus Outline', keys: ['Alt+Shift+O'], run: () => p.outline.focus() || toast('info', 'The outline is empty: open a Cactal file') },
    { id: 'tabs', label: 'Focus open tabs', keys: ['Alt+Shift+W'], run: () => editors.focusTabs() },
    { id: 'newFile', label: 'New File…', keys: ['Alt+Shift+N'], run: () => p.files.newEntry('file') },
    { id: 'newFolder', label: 'New Folder…', run: () => p.files.newEntry('dir') },
    { id: 'newProject', label: 'New Project… (the report\'s six templates)', run: () => p.files.newProject() },
    {
      id: 'renameFile', label: 'Rename File…', keys: ['Alt+Shift+R'], run: () => {
        const entry = explorer.entryOf(activeFile() ?? '') ?? explorer.selected;
        if (!entry) return toast('info', 'No file to rename: open one or select it in the explorer');
        return p.files.rename(entry);
      },
    },
    {
      id: 'reload', label: 'Reload from disk (discard unsaved edits)', keys: ['Alt+Shift+L'], run: () => {
        if (!activeFile()) return toast('info', 'Reload from disk works on the active file: open one first');
        return editors.editor.getAction('contract.reloadFromDisk')?.run();
      },
    },
  ];
  registry.add(...commands);
  for (const list of [explorer, p.outline, p.problems]) list.onEscape.on(() => editors.focusActive());
  return registry;
}
