import type { monaco } from '../editor/monaco.js';
import type { EditorArea } from '../editor/editor-area.js';
import type { Workspace } from '../workspace/workspace.js';
import { quickPick, type PickItem } from '../palette/quick-pick.js';
import type { CommandRegistry } from './commands.js';
import { focusIsNowhere } from '../util/dom.js';

/** Editor commands Monaco registers outside `getSupportedActions()` (its "action2" kind): listed too. */
const MORE_EDITOR_COMMANDS: Array<{ id: string; label: string; key: string }> = [
  { id: 'editor.action.revealDefinition', label: 'Go to Definition', key: 'F12' },
  { id: 'editor.action.peekDefinition', label: 'Peek Definition', key: 'Ctrl+Shift+F10' },
  { id: 'editor.action.goToReferences', label: 'Go to References', key: 'Shift+F12' },
];

type Keybindings = { lookupKeybinding(id: string): { getLabel(): string | null } | undefined };

/** Monaco's label of an editor action's shortcut (its keybinding service is internal: none when unreachable). */
function editorKeybinding(editor: monaco.editor.IStandaloneCodeEditor, id: string): string | undefined {
  try {
    const service = (editor as unknown as { _standaloneKeybindingService?: Keybindings })._standaloneKeybindingService;
    return service?.lookupKeybinding(id)?.getLabel() ?? undefined;
  } catch {
    return undefined;
  }
}

/**
 * The command palette (F1, Ctrl+Shift+P): the IDE's commands, then, with a file tab active, the
 * editor's own actions (Go to Definition, Format Document, ...). One palette inside and outside the
 * editor: the IDE's F1 replaces Monaco's.
 */
export async function openCommandPalette(commands: CommandRegistry, editors: EditorArea): Promise<void> {
  type Item = PickItem & { run(): unknown };
  const items: Item[] = commands.list().map((c) => ({ label: c.label, keybinding: c.keys?.[0], detail: 'IDE', run: () => c.run() }));
  const fileActive = !!editors.active && !editors.active.startsWith('view:') && !!editors.editor.getModel();
  if (fileActive) {
    const seen = new Set(items.map((i) => i.label));
    for (const a of editors.editor.getSupportedActions()) {
      if (seen.has(a.label) || !a.label) continue;
      seen.add(a.label);
      items.push({ label: a.label, keybinding: editorKeybinding(editors.editor, a.id), detail: 'Editor', run: () => {
        editors.editor.focus();
        return a.run();
      } });
    }
    for (const c of MORE_EDITOR_COMMANDS) {
      if (seen.has(c.label)) continue;
      items.push({ label: c.label, keybinding: editorKeybinding(editors.editor, c.id) ?? c.key, detail: 'Editor', run: () => {
        editors.editor.focus();
        editors.editor.trigger('command-palette', c.id, null);
      } });
    }
  }
  const picked = await quickPick({ id: 'command-palette', label: 'Command palette', placeholder: 'Type a command (Generate All, Build & Run, Format…)', items });
  if (!picked) return focusEditorIfNowhere(editors);
  await picked.run();
}

/** Quick open (Ctrl+P): every file of the workspace, fuzzy matched on its path; Enter opens it. */
export async function openQuickOpen(workspace: Workspace, editors: EditorArea): Promise<void> {
  const recent = editors.tabsState().tabs.filter((t) => !t.startsWith('view:')).reverse();
  const files = [...new Set([...recent, ...workspace.allFiles()])].filter((p) => workspace.hasFile(p));
  const items = files.map((path) => ({ label: path, detail: editors.isOpen(path) ? 'open' : undefined, path }));
  const picked = await quickPick({ id: 'quick-open', label: 'Go to file', placeholder: 'Go to a file of the workspace by name', items });
  if (picked) await editors.open(picked.path);
  else focusEditorIfNowhere(editors);
}

/**
 * Escape gives the focus back where it was; when that was nowhere (the page itself: a step that
 * had closed a dialog was still loading), the active tab gets it, so the keyboard is never lost.
 */
function focusEditorIfNowhere(editors: EditorArea): void {
  if (focusIsNowhere()) editors.focusActive();
}
