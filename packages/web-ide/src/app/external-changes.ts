import type { LspClient } from '../lsp/lsp-client.js';
import { SAVE_SESSION_LOST, type Workspace } from '../workspace/workspace.js';
import { debounce } from '../util/dom.js';
import { dismissToasts, toast } from '../util/toast.js';
import { api, ApiError } from '../api.js';
import { isContract } from '../workspace/file-kinds.js';
import { ServerEvents } from './server-events.js';

/**
 * Follows the server's file events (another program, another tab): refreshes the tree, loads new
 * Cactal files into the language server, drops deleted ones, and saves pending edits on reconnect.
 * Returns the server's events (/api/events), which carry the other tabs' runs too (shared-runs.ts).
 */
export function watchExternalChanges(workspace: Workspace, lsp: LspClient): ServerEvents {
  const refreshTree = debounce(() => void workspace.refreshTree().then(async () => {
    let changed = false;
    for (const p of workspace.allFiles().filter(isContract)) {
      if (!workspace.files.has(p)) {
        await workspace.ensureModel(p).catch(() => undefined);
        changed = true;
      }
    }
    for (const p of [...workspace.files.keys()]) {
      if (!workspace.hasFile(p) && workspace.files.get(p)!.state === 'saved') {
        workspace.dropFile(p);
        changed = true;
      }
    }
    if (changed) lsp.revalidateAll();
  }).catch(() => undefined), 150); // server unreachable: the reconnect ('hello') refreshes again
  const events = new ServerEvents();
  events.on('change', (data) => {
    const paths = (data as { paths?: unknown } | null)?.paths;
    if (!Array.isArray(paths)) return;
    refreshTree();
    for (const p of paths) if (typeof p === 'string') void workspace.externalChange(p);
  });
  let wasDisconnected = false;
  let sessionEnded = false;
  events.onLost(() => {
    if (!wasDisconnected) toast('warning', `${LOST}: edits are kept in this browser until it is back`);
    wasDisconnected = true;
    // a server that answers but refuses the socket was restarted (a new session token): said at
    // once, and until the tab has a session again, rather than a quiet "disconnected" status
    if (!sessionEnded) void sessionRefused().then((refused) => {
      if (!refused || sessionEnded) return;
      sessionEnded = true;
      dismissToasts(LOST);
      toast('error', SESSION_ENDED, { sticky: true });
    });
  });
  events.on('hello', () => {
    if (sessionEnded) dismissToasts(SESSION_ENDED);
    // a save refused for want of the session (workspace.ts) is saved again below: its notice goes too
    dismissToasts(SAVE_SESSION_LOST);
    sessionEnded = false;
    if (wasDisconnected) {
      wasDisconnected = false;
      toast('info', 'Reconnected to the IDE server: saving pending edits');
      void workspace.saveAll();
      refreshTree();
    }
  });
  return events;
}

const LOST = 'Lost the connection to the IDE server';
export const SESSION_ENDED = 'The IDE server was restarted and no longer knows this tab\'s session: open the address it printed ' +
  '(…/?token=…) in this tab or another one of this browser. Your unsaved edits are kept in this browser, for this address: they come back ' +
  'and are saved when the server listens on the same port again (contract serve --port N; another port is another address to the browser).';

/** True when the IDE server answers but refuses this tab's session (401); false when it is unreachable. */
async function sessionRefused(): Promise<boolean> {
  return api.info().then(() => false, (e: unknown) => e instanceof ApiError && e.status === 401);
}
