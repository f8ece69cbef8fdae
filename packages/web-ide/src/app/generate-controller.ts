import type { GeneratePanel } from '../build/generate-panel.js';
import type { Explorer } from '../panels/explorer.js';
import type { ProblemsPanel } from '../panels/problems.js';
import type { Workspace } from '../workspace/workspace.js';
import { api, ApiError } from '../api.js';
import { toast } from '../util/toast.js';

/** Generate All: saves, generates src-gen/ of the current project, shows the report and reloads open generated files. */
export class GenerateController {
  constructor(private readonly d: {
    workspace: Workspace; explorer: Explorer; problems: ProblemsPanel; panel: GeneratePanel; button: HTMLButtonElement;
    showPanel(id: string): void; project(): string;
  }) {
    d.button.addEventListener('click', () => void this.generate());
  }

  /** True when the generator reported no error. */
  async generate(): Promise<boolean> {
    const { workspace, explorer, problems, panel, button } = this.d;
    this.d.showPanel('generate');
    panel.showRunning();
    button.disabled = true;
    try {
      await workspace.saveAll();
      const r = await api.generate(this.d.project());
      panel.show(r);
      problems.set('gcc', []); // the generated files changed: the last build's diagnostics are stale
      await workspace.refreshTree();
      explorer.expand(`${r.srcGen}/generated/architecture/modules`);
      for (const p of [...workspace.files.keys()]) if (p.startsWith(`${r.srcGen}/`)) void workspace.externalChange(p);
      for (const w of r.layoutWarnings ?? []) toast('warning', `Generate All: ${w}`);
      if (r.errors.length) toast('error', `Generate All: ${r.errors.length} error(s) — see the Generate panel`);
      else if (r.orphaned.length) toast('warning', `Generate All: ${r.orphaned.length} orphaned region(s) moved to ${r.srcGen}/orphans`);
      return r.errors.length === 0;
    } catch (e) {
      panel.showError(e instanceof ApiError ? e.message : String(e));
      return false;
    } finally {
      button.disabled = false;
    }
  }
}
