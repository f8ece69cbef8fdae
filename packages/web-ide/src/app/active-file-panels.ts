import type { monaco } from '../editor/monaco.js';
import type { EditorArea } from '../editor/editor-area.js';
import type { Explorer } from '../panels/explorer.js';
import type { OutlinePanel } from '../panels/outline.js';
import type { Workspace } from '../workspace/workspace.js';
import { isContract, languageLabel } from '../workspace/file-kinds.js';
import { scanProtectedRegions } from '../editor/protected-regions.js';

/**
 * What follows the active tab: the explorer's highlight, the outline (symbols of a Cactal file,
 * protected regions of generated C), and the status bar's language and cursor position.
 */
export function followActiveFile(d: { editors: EditorArea; workspace: Workspace; explorer: Explorer; outline: OutlinePanel; langEl: HTMLElement; cursorEl: HTMLElement }): void {
  const { editors, workspace, explorer, outline } = d;
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
  editors.onActiveChanged.on((id) => {
    const isFile = id && !id.startsWith('view:');
    explorer.setActive(isFile ? id : undefined);
    const fs = isFile ? workspace.files.get(id) : undefined;
    const guard = isFile ? editors.guardOf(id) : undefined;
    if (fs && guard) showRegionOutline(fs.model);
    else outline.show(fs && isContract(id!) ? fs.model.uri.toString() : undefined);
    d.langEl.textContent = fs ? languageLabel(id!, fs.model.getLanguageId()) : '';
    // the cursor shown is the active editor's (a view tab has none)
    const pos = fs && editors.editor.getModel() === fs.model ? editors.editor.getPosition() : null;
    d.cursorEl.textContent = pos ? `Ln ${pos.lineNumber}, Col ${pos.column}` : '';
  });
  editors.editor.onDidChangeModelContent(() => {
    const model = editors.editor.getModel();
    if (model && editors.active && editors.guardOf(editors.active)) showRegionOutline(model);
    else outline.refresh();
  });
  editors.editor.onDidChangeCursorPosition((e) => (d.cursorEl.textContent = `Ln ${e.position.lineNumber}, Col ${e.position.column}`));
}
