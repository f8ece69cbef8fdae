import { monaco } from '../editor/monaco.js';
import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { BuildPanel } from '../build/build-panel.js';
import type { ProblemsPanel, Severity } from '../panels/problems.js';
import type { Workspace } from '../workspace/workspace.js';
import { STEP_INPUT_FILE } from '../simulate/step-input.js';
import { BUILD_WITHOUT_FILE, gccProblems } from '../build/gcc-problems.js';

export interface ProblemsDeps {
  problems: ProblemsPanel;
  workspace: Workspace;
  editors: EditorArea;
  lsp: LspClient;
  build: BuildPanel;
  statusEl: HTMLElement;
  showPanel(id: string): void;
  /** The project folder of the last build (gcc paths are relative to its src-gen/). */
  buildProject(): string;
}

const sevOf = (s: number | undefined): Severity => (s === 1 ? 'error' : s === 2 ? 'warning' : s === 3 ? 'info' : 'hint');

/**
 * Feeds the Problems panel from the language server (per file) and gcc (per build), keeps the
 * status bar's counts, opens a problem's position, and marks gcc diagnostics in open generated files.
 */
export function connectProblems(d: ProblemsDeps): void {
  const { problems, workspace, editors, lsp, build, statusEl } = d;
  lsp.onDiagnostics.on(({ uri, diagnostics }) => {
    const path = workspace.pathOf(uri);
    if (!path || path.endsWith(STEP_INPUT_FILE)) return; // the Simulate panel's step field: checked in place
    problems.set(`cactal:${path}`, diagnostics.map((x) => ({
      path, line: x.range.start.line + 1, column: x.range.start.character + 1, severity: sevOf(x.severity), message: x.message, source: 'cactal',
    })));
  });
  problems.onCounts.on(({ errors, warnings }) => {
    statusEl.innerHTML = '';
    statusEl.append(`✖ ${errors}  ⚠ ${warnings}`);
    statusEl.dataset.errors = String(errors);
    statusEl.dataset.warnings = String(warnings);
  });
  statusEl.addEventListener('click', () => d.showPanel('problems'));
  problems.onOpen.on((p) => {
    if (p.path !== BUILD_WITHOUT_FILE) void editors.open(p.path, { lineNumber: p.line, column: p.column });
  });
  // the build's diagnostics (gcc's, and the run's crash site: source `run`) also become squiggles in the generated files (owner 'gcc'), when they are open
  let gccMarked = new Set<string>();
  const applyGccMarkers = () => {
    const byPath = new Map<string, monaco.editor.IMarkerData[]>();
    for (const p of problems.all().filter((q) => (q.source === 'gcc' || q.source === 'run') && q.path !== BUILD_WITHOUT_FILE)) {
      const list = byPath.get(p.path) ?? byPath.set(p.path, []).get(p.path)!;
      const sev = p.severity === 'error' ? monaco.MarkerSeverity.Error : p.severity === 'warning' ? monaco.MarkerSeverity.Warning : monaco.MarkerSeverity.Info;
      list.push({ severity: sev, message: p.message, source: p.source, startLineNumber: p.line, startColumn: p.column, endLineNumber: p.line, endColumn: p.column + 1 });
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
    const project = d.buildProject();
    const srcGen = `${project ? `${project}/` : ''}src-gen/`;
    problems.set('gcc', gccProblems(diags, srcGen));
    if (diags.some((x) => x.severity === 'error')) d.showPanel('problems');
  });
}
