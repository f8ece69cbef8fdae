/**
 * Runs work that reads and writes a project folder by path (loading the model, Generate All, the
 * rename carry-over, the simulator) on that folder *as opened*, not as named: the folder is opened
 * from the workspace root one component at a time without following links (WorkspaceFs.withDir),
 * and the work gets `/proc/self/fd/N` — the opened folder, whatever its path becomes meanwhile.
 * A project folder swapped for a link to a host folder after the request's checks therefore
 * cannot redirect a generation outside the workspace (docs/ide.md, "Localhost hardening").
 * The answer is given back with the folder's workspace path in place of the descriptor's.
 */
import type { WorkspacePaths } from './workspace-paths.js';

export async function inProjectFolder<T>(paths: WorkspacePaths, projectDir: string, work: (dir: string) => Promise<T>,
  options: { unanchor?: boolean } = {}): Promise<T> {
  const parts = paths.toRelative(projectDir).split('/').filter(Boolean);
  return paths.fs.withDir(parts, false, async (opened) => {
    const anchor = opened.at('').replace(/\/$/, '');
    let result: T;
    try {
      result = await work(anchor);
    } catch (e) {
      if (e instanceof Error) e.message = unanchor(e.message, anchor, projectDir);
      throw e;
    }
    // plain data (reports) is given back named from the workspace; other results are the caller's to name
    return options.unanchor === false ? result : unanchor(result, anchor, projectDir);
  });
}

/** `value` with the anchor in its strings (messages, file names) replaced by `projectDir`. */
function unanchor<T>(value: T, anchor: string, projectDir: string): T {
  if (typeof value === 'string') return (value.includes(anchor) ? value.split(anchor).join(projectDir) : value) as T;
  if (Array.isArray(value)) return value.map((v) => unanchor(v, anchor, projectDir)) as T;
  if (value && typeof value === 'object') {
    const out = Object.create(null) as Record<string, unknown>; // a "__proto__" key stays a key
    for (const [k, v] of Object.entries(value)) out[k] = unanchor(v, anchor, projectDir);
    return out as T;
  }
  return value;
}
