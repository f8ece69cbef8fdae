import { h } from '../util/dom.js';
import { RovingFocus } from '../util/roving-focus.js';
import { makePaneResizer } from './pane-resizer.js';

/** The editor's least height (styles.css `.editor-area`: min(260px, 100% - 84px)), which the bottom panel's resizer leaves it. */
const EDITOR_MIN_HEIGHT = 260;

/** The static frame of the IDE: top bar, sidebar (explorer + outline), editor, bottom panel, status bar. */
export function createLayout(root: HTMLElement) {
  const btn = (id: string, icon: string, label: string, title: string, cls = '') =>
    h('button', { class: `btn toolbar-btn ${cls}`, id, title, 'aria-label': label || title }, h('span', { class: 'btn-icon' }, icon), label ? h('span', {}, label) : null);
  const toolbar = {
    newFile: btn('btn-new-file', '+', 'File', 'New file in the selected folder (Alt+Shift+N)'),
    newFolder: btn('btn-new-folder', '▣', 'Folder', 'New folder in the selected folder'),
    newProject: btn('btn-new-project', '✦', 'New Project', 'Create a project from the report templates'),
    generate: btn('btn-generate', '⚙', 'Generate All', 'Generate the C tree (Ctrl+Shift+G)', 'accent'),
    run: btn('btn-run', '▶', 'Build & Run', 'Build in the sandbox and run the architecture (Ctrl+Shift+B)', 'run'),
    stop: btn('btn-stop', '■', 'Stop', 'Stop the running job (Alt+Shift+S)', 'stop'),
    runSettings: btn('btn-run-settings', '⚙', '', 'Run settings: duration, start request, init time, CPUs, stdin, real-time'),
    arch: btn('btn-arch', '⬡', 'Architecture', 'Architecture diagram of the schemas (Alt+Shift+D)'),
    timeline: btn('btn-timeline', '▤', 'Timeline', 'Module activations per period from the run logs (Alt+Shift+T)'),
    monitor: btn('btn-monitor', '◉', 'Monitor', 'Watch the run: rules, schemas, deadlines (live during Build & Run, replay after) (Alt+Shift+M)'),
  };
  toolbar.stop.disabled = true;
  const workspaceName = h('span', { class: 'workspace-name' });
  const topbar = h('header', { class: 'topbar' },
    h('h1', { class: 'brand' }, h('span', { class: 'brand-mark' }, '◈'), h('span', { class: 'brand-name' }, 'ContrACT'), h('span', { class: 'brand-sub' }, 'Studio')),
    workspaceName, h('div', { class: 'toolbar-group' }, toolbar.newFile, toolbar.newFolder, toolbar.newProject),
    h('div', { class: 'toolbar-group' }, toolbar.generate, toolbar.run, toolbar.runSettings, toolbar.stop),
    h('span', { class: 'grow' }), h('div', { class: 'toolbar-group' }, toolbar.arch, toolbar.timeline, toolbar.monitor));

  const explorerBody = h('div', { class: 'section-body explorer-body' });
  const outlineBody = h('div', { class: 'section-body outline-body' });
  const sidebar = h('aside', { class: 'sidebar', id: 'sidebar' },
    h('section', { class: 'side-section explorer-section', 'aria-labelledby': 'title-explorer' }, h('h2', { class: 'section-title', id: 'title-explorer' }, 'Explorer'), explorerBody),
    h('section', { class: 'side-section outline-section', 'aria-labelledby': 'title-outline' }, h('h2', { class: 'section-title', id: 'title-outline' }, 'Outline'), outlineBody));

  const editorRoot = h('main', { class: 'editor-area' });
  const panelTabs = h('div', { class: 'panel-tabs', role: 'tablist', 'aria-label': 'Panels' });
  const panelBodies = h('div', { class: 'panel-bodies' });
  const panel = h('section', { class: 'bottom-panel', id: 'bottom-panel', 'aria-label': 'Panels' }, panelTabs, panelBodies);

  const status = {
    problems: h('span', { class: 'status-item status-problems', id: 'status-problems', title: 'Problems' }),
    save: h('span', { class: 'status-item', id: 'status-save' }, '✓ All saved'),
    lsp: h('span', { class: 'status-item', id: 'status-lsp' }, '◌ Language server starting'),
    job: h('span', { class: 'status-item', id: 'status-job' }),
    cursor: h('span', { class: 'status-item', id: 'status-cursor' }),
    lang: h('span', { class: 'status-item', id: 'status-lang' }),
  };
  const statusbar = h('footer', { class: 'statusbar', 'aria-label': 'Status' }, status.problems, status.save, status.job, h('span', { class: 'grow' }), status.cursor, status.lang, status.lsp);

  const resizerV = h('div', { class: 'resizer vertical' });
  const resizerH = h('div', { class: 'resizer horizontal' });
  // each resizer lies on the edge of the pane it resizes, inside its landmark (axe-core: no content outside one)
  sidebar.append(resizerV);
  panel.prepend(resizerH);
  const center = h('div', { class: 'center' }, editorRoot, panel);
  const shell = h('div', { class: 'shell' }, topbar, h('div', { class: 'workbench' }, sidebar, center), statusbar);
  root.append(shell);
  // the pane resizers: dragged, or focused and moved by the arrow keys (docs/ide.md "Panes and small screens")
  const sidebarResizer = makePaneResizer(resizerV, {
    orientation: 'vertical', label: 'Resize the sidebar', controls: 'sidebar', direction: 1,
    min: () => 160, max: () => 600,
    size: () => sidebar.getBoundingClientRect().width,
    setSize: (px) => (sidebar.style.width = `${px}px`),
  });
  // the editor keeps a minimum height (styles.css .editor-area): on a short window the bottom panel gives way first
  const panelResizer = makePaneResizer(resizerH, {
    orientation: 'horizontal', label: 'Resize the bottom panel', controls: 'bottom-panel', direction: -1,
    min: () => 80,
    max: () => {
      const c = center.getBoundingClientRect().height;
      return Math.max(80, c - Math.min(EDITOR_MIN_HEIGHT, c - 84));
    },
    size: () => panel.getBoundingClientRect().height,
    setSize: (px) => (panel.style.height = `${px}px`),
  });
  /** The resizers' values said again (after the layout was restored). */
  const refreshResizers = () => {
    sidebarResizer.refresh();
    panelResizer.refresh();
  };

  const panels = new Map<string, { tab: HTMLElement; body: HTMLElement; onShow?: () => void }>();
  const showPanel = (id: string) => {
    for (const [k, p] of panels) {
      p.tab.classList.toggle('active', k === id);
      p.tab.setAttribute('aria-selected', String(k === id));
      p.body.classList.toggle('hidden', k !== id);
    }
    panels.get(id)?.onShow?.(); // however it is shown: a click, the keyboard, a command, the layout restored after a reload
    panelFocus.forget(); // the tab stop is the shown panel's tab
    panelFocus.refresh();
  };
  // the panel tabs: a WAI-ARIA tablist (←/→ show the next panel, Tab enters it, Escape back to the editor)
  let escape = () => undefined as unknown;
  const panelFocus = new RovingFocus(panelTabs, {
    orientation: 'horizontal', followFocus: true,
    items: () => [...panels.values()].map((p) => p.tab),
    keyOf: (tab) => tab.dataset.panel ?? '',
    current: () => panelTabs.querySelector<HTMLElement>('.panel-tab.active') ?? undefined,
    onActivate: (tab) => tab.click(),
    onEscape: () => escape(),
  });
  /** `onShow`: called each time the panel is shown. */
  const addPanel = (id: string, title: string, body: HTMLElement, onShow?: () => void) => {
    const tab = h('div', {
      class: 'panel-tab', role: 'tab', id: `panel-tab-${id}`, 'aria-controls': `panel-${id}`, 'aria-selected': 'false', tabindex: -1, 'data-panel': id,
      onclick: () => showPanel(id),
    }, title);
    const wrapper = h('div', { class: 'panel-body hidden', role: 'tabpanel', id: `panel-${id}`, 'aria-labelledby': `panel-tab-${id}`, 'data-panel': id }, body);
    panelTabs.append(tab);
    panelBodies.append(wrapper);
    panels.set(id, { tab, body: wrapper, onShow });
    panelFocus.refresh();
    return tab;
  };
  /** Focuses the tab of the panel shown. */
  const focusPanelTabs = () => panelFocus.focus();
  /** What Escape in the panel tabs does (focus the editor). */
  const onPanelEscape = (fn: () => void) => (escape = fn);
  return { toolbar, workspaceName, explorerBody, outlineBody, editorRoot, status, addPanel, showPanel, focusPanelTabs, onPanelEscape, refreshResizers };
}
