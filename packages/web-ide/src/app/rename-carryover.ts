import type { EditorArea } from '../editor/editor-area.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import { api, ApiError } from '../api.js';
import { toast } from '../util/toast.js';
import { reportError } from './report-error.js';
import { undoRename } from './rename-undo.js';

/**
 * A rename refactoring carries the generated tree over, then regenerates: a module, supervisor,
 * datatype, enumeration or function moves its generated files and region IDs; a port's or
 * parameter's uses in its module's protected-region code follow, as a datatype's, an
 * enumeration's (its constants `Mode_AUTO` too), an enumeration member's constant and a
 * function's do in every region (whole C identifiers in code); the project's `.scenario` files
 * follow a module, supervisor, schema, supervision function, event port, datatype, enumeration or
 * enumeration member (`contract rename` does the same). Uses it could not change (the new name already in that code, a scenario changed
 * meanwhile) are said, with where. The `.contract` files the rename edited are written by the server
 * after the generated tree, under the rename's journal (server/rename-api.ts), not by autosave:
 * their saves are held until then. A rename the server does not make (refused, or no answer) is
 * taken back in the editor (rename-undo.ts) before the saves are let go: nothing renamed is saved.
 */
export function carryRenamesToGenerated(d: { lsp: LspClient; workspace: Workspace; editors: EditorArea; project(): string; generate(): Promise<boolean> }): void {
  const { lsp, workspace, editors } = d;
  lsp.onRename.on(({ oldName: old, newName, topLevel, kind, owner, members, files }) => {
    if (!old || old === newName || (!topLevel && !kind)) return; // schemas' parameters, fields: neither the generated tree nor a scenario names them
    // held before the edit applies (this event comes first): no autosave writes a renamed text before the server's journal
    const project = d.project();
    const inProject = (path: string) => path.endsWith('.contract') && (!project || path.startsWith(`${project}/`)) && !path.slice(project ? project.length + 1 : 0).startsWith('src-gen/');
    const renamed = files.flatMap((f) => { const path = workspace.pathOf(f.uri); return path !== undefined && inProject(path) ? [{ path, text: f.text }] : []; });
    const bases = workspace.holdSaves(renamed.map((f) => f.path));
    const sent = renamed.flatMap((f) => (bases.has(f.path) ? [{ path: f.path, text: f.text, base: bases.get(f.path)! }] : []));
    void (async () => {
      let r;
      try {
        r = await api.renameEntity(project, old, newName, { kind, owner, members, files: sent });
      } catch (e) {
        // not made (refused: a target path taken...; or no answer): the editor's rename is taken
        // back before the held saves go, so none writes a renamed text
        const left = await undoRename(files, (uri) => workspace.pathOf(uri) ?? uri).finally(() => workspace.releaseSaves([...bases.keys()], new Map()));
        toast('error', renameNotMadeText(old, newName, e, left));
        return;
      }
      // what the server wrote is the tabs' new base; a file it did not write (refused, left) is saved as any edit
      const written = new Map(r.written.map((w) => [w.file, { text: sent.find((f) => f.path === w.file)!.text, version: w.version }]));
      workspace.releaseSaves([...bases.keys()], written);
      if (r.filesLeft.length) toast('warning', `${r.filesLeft.length} renamed file(s) were not written by the rename (first: ${r.filesLeft[0]!.file}: ${r.filesLeft[0]!.reason}): saved from the editor instead`);
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

/** The error notice of a rename the server did not make (`e`: its refusal, or why it did not answer); `left`: files whose edits since overlap it. */
function renameNotMadeText(old: string, newName: string, e: unknown, left: readonly string[]): string {
  const answered = e instanceof ApiError && e.status > 0;
  const why = e instanceof Error ? e.message : String(e);
  return `Rename ${old} → ${newName} not made: ${why}. ` +
    (answered ? 'No file was changed; ' : 'The IDE server did not answer (if it stopped half-way through the rename, the next Generate All finishes it); ') +
    (left.length
      ? `the editor's rename was taken back except in ${left.join(', ')} (edited since, over the renamed names: change them back by hand)`
      : 'the editor\'s rename was taken back, nothing renamed was saved');
}
