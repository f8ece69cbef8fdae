import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import { api } from '../api.js';
import { toast } from '../util/toast.js';
import { reportError } from './report-error.js';

/**
 * A rename refactoring carries the generated tree over, then regenerates: a module, supervisor,
 * datatype, enumeration or function moves its generated files and region IDs; a port's or
 * parameter's uses in its module's protected-region code follow, as a datatype's, an
 * enumeration's (its constants `Mode_AUTO` too), an enumeration member's constant and a
 * function's do in every region (whole C identifiers in code); the project's `.scenario` files
 * follow a module, supervisor, schema, supervision function, event port, datatype, enumeration or
 * enumeration member (`contract rename` does the same). Uses it could not change (the new name already in that code, a scenario changed
 * meanwhile) are said, with where.
 */
export function carryRenamesToGenerated(d: { lsp: LspClient; workspace: Workspace; editors: EditorArea; project(): string; generate(): Promise<boolean> }): void {
  const { lsp, workspace, editors } = d;
  lsp.onRename.on(({ oldName: old, newName, topLevel, kind, owner, members }) => {
    if (!old || old === newName || (!topLevel && !kind)) return; // schemas' parameters, fields: neither the generated tree nor a scenario names them
    void (async () => {
      await new Promise((r) => setTimeout(r, 50));
      await workspace.saveAll();
      const project = d.project();
      const r = await api.renameEntity(project, old, newName, { kind, owner, members });
      const base = `${project ? `${project}/` : ''}src-gen/`;
      const uses = r.rewritten.reduce((n, w) => n + w.occurrences, 0);
      const scenarioFiles = new Set(r.scenarios.map((e) => e.file)).size;
      const parts = [
        ...(r.movedPaths.length || r.regionIds.length ? [`${r.movedPaths.length} generated path(s) and ${r.regionIds.length} protected region(s) carried over`] : []),
        ...(uses ? [`${uses} use(s) in the code of ${r.rewritten.length} protected region(s) renamed`] : []),
        ...(scenarioFiles ? [`${r.scenarios.length} line(s) of ${scenarioFiles} scenario file(s) renamed`] : []),
      ];
      if (parts.length) toast('info', `Renamed ${old} → ${newName}: ${parts.join('; ')}`);
      if (r.scenariosLeft.length) {
        const first = r.scenariosLeft[0]!;
        toast('error', `${r.scenariosLeft.length} scenario file(s) naming ${old} were not renamed (first: ${first.file}: ${first.reason}): change them by hand`);
      }
      if (r.movedPaths.length || r.regionIds.length || uses) {
        await workspace.refreshTree();
        for (const m of r.movedPaths) {
          const from = base + m.from;
          if (workspace.files.has(from) || [...workspace.files.keys()].some((p) => p.startsWith(from + '/'))) {
            for (const p of [...workspace.files.keys()]) if (p === from || p.startsWith(from + '/')) workspace.dropFile(p);
            editors.renamePath(from, base + m.to);
          }
        }
        if (editors.active?.includes('/src-gen/') || editors.active?.startsWith('src-gen/')) await editors.open(editors.active);
        await d.generate();
      }
      const inCode = r.remaining.filter((m) => m.context === 'code');
      if (r.refused || inCode.length) {
        const first = inCode[0];
        toast('error', `${r.refused ?? `${inCode.length} use(s) of ${old} in protected-region code were not renamed`}` +
          (first ? ` (first: ${base}${first.file}:${first.line}, region ${first.id}): change them by hand, the build fails until then` : ''));
      }
    })().catch(reportError);
  });
}
