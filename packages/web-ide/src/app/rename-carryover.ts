import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import { api } from '../api.js';
import { toast } from '../util/toast.js';
import { reportError } from './report-error.js';

/** A rename refactoring of a module, schema or supervisor carries generated files and region IDs over, then regenerates. */
export function carryRenamesToGenerated(d: { lsp: LspClient; workspace: Workspace; editors: EditorArea; project(): string; generate(): Promise<boolean> }): void {
  const { lsp, workspace, editors } = d;
  lsp.onRename.on(({ oldName: old, newName, topLevel }) => {
    if (!old || old === newName || !topLevel) return; // ports, variables, labels: nothing generated is named after them
    void (async () => {
      await new Promise((r) => setTimeout(r, 50));
      await workspace.saveAll();
      const project = d.project();
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
        await d.generate();
      }
    })().catch(reportError);
  });
}
