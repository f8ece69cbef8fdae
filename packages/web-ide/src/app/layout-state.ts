import type { monaco } from '../editor/monaco.js';
import type { EditorArea } from '../editor/editor-area.js';
import { debounce } from '../util/dom.js';
import { PANE_RESIZED } from './pane-resizer.js';

/** What the browser keeps of the IDE's layout, per workspace root (localStorage). */
export interface StoredLayout {
  v: 1;
  /** Open tabs in order: workspace-relative file paths and view ids (`view:architecture`, `view:timeline`). */
  tabs: string[];
  active?: string;
  /** Monaco view state (cursor, selections, scroll) of each file tab. */
  viewStates: Record<string, monaco.editor.ICodeEditorViewState>;
  sidebarWidth?: number;
  panelHeight?: number;
  /** The bottom panel shown (problems, output, generate...). */
  panel?: string;
  /** The architecture diagram docked beside the editor (⇆ Side by side) rather than in a tab. */
  archDocked?: boolean;
}

const MAX_TABS = 100;
const MAX_ID = 1000;
const KEY_PREFIX = 'contract-studio:layout:';
export const layoutKey = (root: string) => `${KEY_PREFIX}${root}`;

const isId = (v: unknown): v is string => typeof v === 'string' && v.length > 0 && v.length <= MAX_ID;
const size = (v: unknown, min: number, max: number) => (typeof v === 'number' && Number.isFinite(v) ? Math.max(min, Math.min(max, Math.round(v))) : undefined);

/**
 * Reads a stored layout. The text comes from localStorage (another version of the IDE, a user
 * editing it, a full quota): anything malformed is dropped, field by field; never throws.
 */
export function parseLayout(raw: string | null): StoredLayout | undefined {
  if (!raw || raw.length > 4 * 1024 * 1024) return undefined;
  let v: unknown;
  try {
    v = JSON.parse(raw);
  } catch {
    return undefined;
  }
  if (!v || typeof v !== 'object' || (v as { v?: unknown }).v !== 1) return undefined;
  const o = v as Record<string, unknown>;
  const tabs = Array.isArray(o.tabs) ? [...new Set(o.tabs.filter(isId))].slice(0, MAX_TABS) : [];
  const viewStates: StoredLayout['viewStates'] = {};
  if (o.viewStates && typeof o.viewStates === 'object') {
    for (const [id, vs] of Object.entries(o.viewStates as Record<string, unknown>)) {
      if (tabs.includes(id) && vs && typeof vs === 'object' && 'cursorState' in vs && 'viewState' in vs) {
        viewStates[id] = vs as monaco.editor.ICodeEditorViewState;
      }
    }
  }
  return {
    v: 1, tabs, viewStates,
    active: isId(o.active) && tabs.includes(o.active) ? o.active : undefined,
    sidebarWidth: size(o.sidebarWidth, 160, 600),
    panelHeight: size(o.panelHeight, 80, 4000),
    panel: typeof o.panel === 'string' && /^[\w-]{1,40}$/.test(o.panel) ? o.panel : undefined,
    archDocked: o.archDocked === true ? true : undefined,
  };
}

export interface LayoutHooks {
  /** localStorage key (layoutKey(workspace root)). */
  key: string;
  editors: EditorArea;
  hasFile(path: string): boolean;
  showPanel(id: string): void;
  /** Opens a view tab by id (resolves once it is open; false if unknown). */
  openView(id: string): Promise<boolean>;
}

/**
 * Brings back the open tabs, the active tab, each tab's cursor and scroll, the sidebar and bottom
 * panel sizes, the bottom panel shown and the docked architecture diagram after a reload, and keeps them up to date while the IDE
 * is used (docs/ide.md, "Reload keeps the workspace"). A file deleted since is skipped silently.
 */
export class LayoutPersistence {
  private started = false;

  constructor(private readonly hooks: LayoutHooks) {}

  private sidebar = () => document.querySelector<HTMLElement>('.sidebar');
  private panel = () => document.querySelector<HTMLElement>('.bottom-panel');

  /** Applies the stored layout; false when there was none usable (the caller opens its default file). */
  async restore(): Promise<boolean> {
    let stored: StoredLayout | undefined;
    try {
      stored = parseLayout(localStorage.getItem(this.hooks.key));
    } catch {
      return false;
    }
    if (!stored) return false;
    const { editors } = this.hooks;
    if (stored.sidebarWidth && this.sidebar()) this.sidebar()!.style.width = `${stored.sidebarWidth}px`;
    if (stored.panelHeight && this.panel()) this.panel()!.style.height = `${Math.min(stored.panelHeight, Math.max(80, window.innerHeight - 200))}px`;
    if (stored.panel && document.querySelector(`.panel-tab[data-panel="${stored.panel}"]`)) this.hooks.showPanel(stored.panel);
    const opened: string[] = [];
    for (const id of stored.tabs) {
      try {
        if (id.startsWith('view:')) {
          if (await this.hooks.openView(id)) opened.push(id);
          continue;
        }
        if (!this.hooks.hasFile(id)) continue; // deleted or moved since: skipped, no error
        const vs = stored.viewStates[id];
        if (vs) editors.presetViewState(id, vs);
        await editors.open(id);
        if (editors.isOpen(id)) opened.push(id);
      } catch {
        // one tab that cannot come back does not stop the others
      }
    }
    if (stored.archDocked && (await this.hooks.openView('view:architecture'))) {
      // the diagram's own ⇆ button moves it from its tab to the side pane
      document.querySelector<HTMLButtonElement>('#arch-dock')?.click();
      opened.push('view:docked');
    }
    const active = stored.active && opened.includes(stored.active) ? stored.active : opened.filter((id) => editors.isOpen(id)).pop();
    if (active) {
      if (active.startsWith('view:')) await this.hooks.openView(active);
      else await editors.open(active);
    }
    return opened.length > 0;
  }

  /** Saves the layout on every change from now on (and when the page goes away). */
  start(): void {
    if (this.started) return;
    this.started = true;
    const later = debounce(() => this.save(), 250);
    const { editors } = this.hooks;
    editors.onTabsChanged.on(later);
    editors.onActiveChanged.on(later);
    editors.editor.onDidChangeCursorPosition(later);
    editors.editor.onDidScrollChange(later);
    window.addEventListener(PANE_RESIZED, later); // a resizer dragged or moved by the keyboard
    document.addEventListener('click', (e) => (e.target as Element | null)?.closest?.('.panel-tab') && later());
    window.addEventListener('pagehide', () => this.save());
    window.addEventListener('beforeunload', () => this.save());
    this.save();
  }

  save(): void {
    const { tabs, active, viewStates } = this.hooks.editors.tabsState();
    const sidebar = this.sidebar()?.getBoundingClientRect().width;
    const panelHeight = this.panel()?.getBoundingClientRect().height;
    const panel = document.querySelector<HTMLElement>('.panel-tab.active')?.dataset.panel;
    const layout: StoredLayout = {
      v: 1, tabs, active, viewStates,
      sidebarWidth: sidebar ? Math.round(sidebar) : undefined,
      panelHeight: panelHeight ? Math.round(panelHeight) : undefined,
      panel,
      archDocked: document.querySelector('.side-pane:not(.hidden) #arch-dock') ? true : undefined,
    };
    try {
      localStorage.setItem(this.hooks.key, JSON.stringify(layout));
    } catch {
      // storage full: the layout is a convenience, unsaved text has priority (workspace.ts)
    }
  }
}
