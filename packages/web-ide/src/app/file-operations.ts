import type { EditorArea } from '../editor/editor-area.js';
import type { Explorer } from '../panels/explorer.js';
import type { LspClient } from '../lsp/lsp-client.js';
import type { Workspace } from '../workspace/workspace.js';
import type { TreeEntry } from '../api.js';
import { api } from '../api.js';
import { askText, confirmAction } from '../util/dialog.js';
import { toast } from '../util/toast.js';
import { isContract } from '../workspace/file-kinds.js';
import { reportError } from './report-error.js';
import { focusIsNowhere } from '../util/dom.js';
import { deleteFileDetail, deleteFolderDetail } from './delete-confirmation.js';

const join = (dir: string, name: string) => (dir ? `${dir}/${name}` : name);

/** New file / folder / project, rename and delete: through the server, then the tree, tabs and language server follow. */
export class FileOperations {
  constructor(private readonly d: { workspace: Workspace; editors: EditorArea; explorer: Explorer; lsp: LspClient }) {
    d.explorer.onContextAction.on(async ({ action, entry }) => {
      if (action === 'new-file') return void this.newEntry('file', entry.path);
      if (action === 'new-folder') return void this.newEntry('dir', entry.path);
      if (action === 'delete') return void this.remove(entry);
      if (action === 'rename') return void this.rename(entry);
    });
  }

  /** Paths being renamed on the server: a tree refresh meanwhile (the watcher saw the old path go) does not close their tabs. */
  private readonly renaming = new Set<string>();

  isRenaming(path: string): boolean {
    return [...this.renaming].some((from) => path === from || path.startsWith(from + '/'));
  }

  rootHasContracts(): boolean {
    return this.d.workspace.entries.some((e) => e.type === 'file' && isContract(e.path));
  }

  async newEntry(type: 'file' | 'dir', folder = this.d.explorer.targetFolder()): Promise<void> {
    const { workspace, editors, explorer } = this.d;
    const asked = await askText(type === 'file' ? 'New file' : 'New folder', type === 'file' ? 'new.contract' : 'folder', `in ${folder || 'the workspace root'}`);
    if (!asked) return;
    // the dialog selects the name without its extension: a whole name typed over it ended `.contract.contract`
    const name = type === 'file' ? asked.replace(/(\.[A-Za-z0-9]{1,12})\1$/, '$1') : asked;
    try {
      const { path } = await api.create(join(folder, name), type);
      await workspace.refreshTree();
      if (type === 'file') await editors.open(path);
      else explorer.expand(path);
    } catch (e) {
      reportError(e);
    }
  }

  async newProject(): Promise<void> {
    const { workspace, editors, lsp } = this.d;
    const rootHasContracts = this.rootHasContracts();
    const hint = rootHasContracts
      ? 'Folder to create. This workspace already holds a project and the language server checks all files together: to work on the new project alone, open its folder with `contract serve <folder>`.'
      : 'Folder to create (empty = the workspace root). Creates datatype, module1, module2, schema, sched and supervisor .contract files.';
    const folder = await askText('New project from the report templates', rootHasContracts ? 'my-robot' : '', hint, { allowEmpty: !rootHasContracts });
    // Escape or Cancel: nothing is created (it used to write the templates into an empty workspace's root)
    if (folder === null) return;
    try {
      const r = await api.newProject(folder);
      await workspace.refreshTree();
      await Promise.all(r.files.map((f) => workspace.ensureModel(f)));
      lsp.revalidateAll();
      await editors.open(r.files.find((f) => f.endsWith('supervisor.contract')) ?? r.files[0]!);
      toast('info', `Project created in ${r.folder || 'the workspace root'}`);
    } catch (e) {
      reportError(e);
    }
  }

  async remove(entry: TreeEntry): Promise<void> {
    const { workspace, lsp } = this.d;
    try {
      const detail = entry.type === 'dir' ? await deleteFolderDetail(entry.path) : await deleteFileDetail(entry.path);
      if (!(await confirmAction(`Delete ${entry.path}?`, detail))) return;
      await api.remove(entry.path);
      for (const p of [...workspace.files.keys()]) if (p === entry.path || p.startsWith(entry.path + '/')) workspace.dropFile(p);
      await workspace.refreshTree();
      lsp.revalidateAll();
    } catch (e) {
      reportError(e);
    }
  }

  async rename(entry: TreeEntry): Promise<void> {
    const { workspace, editors, lsp } = this.d;
    try {
      const name = await askText(`Rename ${entry.path}`, entry.name);
      if (!name || name === entry.name) return;
      const dir = entry.path.includes('/') ? entry.path.slice(0, entry.path.lastIndexOf('/')) : '';
      const to = join(dir, name);
      await workspace.saveAll();
      // until the tabs point at the new path and the tree has it, a tree fetched by the watcher
      // meanwhile (old path gone, or new path not there yet) must not close their tabs
      this.renaming.add(entry.path).add(to);
      try {
        await api.rename(entry.path, to);
        const moved = [...workspace.files.keys()].filter((p) => p === entry.path || p.startsWith(entry.path + '/'));
        for (const p of moved) workspace.dropFile(p);
        editors.renamePath(entry.path, to);
        await workspace.refreshTree();
        for (const p of moved) {
          const np = to + p.slice(entry.path.length);
          if (isContract(np)) await workspace.ensureModel(np);
        }
      } finally {
        this.renaming.delete(entry.path);
        this.renaming.delete(to);
      }
      lsp.revalidateAll();
      // the tab shows the file under its new name; the focus goes back to the editor unless the
      // user has moved it meanwhile (Ctrl+P pressed while the tree was being fetched)
      if (editors.active && workspace.hasFile(editors.active)) await editors.open(editors.active, undefined, { focus: focusIsFree() });
    } catch (e) {
      reportError(e);
    }
  }
}

/** Nobody holds the keyboard focus but the page itself or the editor. */
function focusIsFree(): boolean {
  return focusIsNowhere() || document.activeElement!.closest('.monaco-editor') !== null;
}
