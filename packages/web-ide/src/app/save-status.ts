import type { Workspace } from '../workspace/workspace.js';
import { dismissToasts } from '../util/toast.js';

/** The status bar's save indicator: failed, conflicting, pending or all saved. */
export function showSaveStatus(workspace: Workspace, el: HTMLElement): void {
  const update = () => {
    const states = [...workspace.files.values()];
    const failed = states.filter((f) => f.state === 'error');
    const pending = states.filter((f) => f.state === 'dirty' || f.state === 'saving');
    const conflicts = states.filter((f) => f.state === 'conflict');
    el.textContent = failed.length ? `✖ Save failed (${failed.length}) — kept locally`
      : conflicts.length ? `⚠ Overlapping edits (${conflicts.length}) — choose in the side-by-side view`
      : pending.length ? `● Saving ${pending.length}…` : '✓ All saved';
    el.className = `status-item ${failed.length ? 'error' : conflicts.length || pending.length ? 'pending' : ''}`;
  };
  workspace.onFileState.on(update);
  // a new save attempt (or one that went through) makes the last "could not save, retrying" notice out of date
  workspace.onFileState.on((fs) => (fs.state === 'saved' || fs.state === 'saving') && dismissToasts(`Could not save ${fs.path}:`));
}
