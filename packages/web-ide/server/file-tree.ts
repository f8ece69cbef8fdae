import type { TreeEntry } from './api-types.js';
import { isAtomicTempFile } from './atomic-write.js';
import { WorkspaceFs, type DirAt } from './workspace-fs.js';

const SKIPPED = new Set(['node_modules', '.git', '.vite']);

/**
 * Bounds of one listing: a hostile folder (20,000 nested folders, millions of files) must not
 * exhaust the server's descriptors (one is open per level of the walk) or its memory. A folder
 * past them is listed with `truncated: true` and no content.
 */
export const TREE_MAX_DEPTH = 64;
export const TREE_MAX_ENTRIES = 50_000;

/**
 * Lists the workspace recursively: folders first, then files, both sorted by name. Symlinks are
 * not listed, and each sub-folder is opened from its parent without following links
 * (workspace-fs.ts), so a folder swapped for a link during the walk is skipped, not followed.
 */
export async function listTree(fs: WorkspaceFs): Promise<TreeEntry[]> {
  const budget = { entries: TREE_MAX_ENTRIES };
  return fs.withDir([], false, (root) => listDir(root, '', 1, budget));
}

async function listDir(dir: DirAt, relDir: string, depth: number, budget: { entries: number }): Promise<TreeEntry[]> {
  const dirents = await WorkspaceFs.list(dir);
  const entries: TreeEntry[] = [];
  for (const d of dirents) {
    if (SKIPPED.has(d.name) || isAtomicTempFile(d.name)) continue;
    if (!d.isDirectory() && !d.isFile()) continue;
    if (budget.entries <= 0) break;
    budget.entries--;
    const path = relDir ? `${relDir}/${d.name}` : d.name;
    if (d.isDirectory()) {
      if (depth >= TREE_MAX_DEPTH || budget.entries <= 0) {
        entries.push({ name: d.name, path, type: 'dir', children: [], truncated: true });
        continue;
      }
      const sub = await WorkspaceFs.openSubdir(dir, d.name);
      if (!sub) continue;
      try {
        entries.push({ name: d.name, path, type: 'dir', children: await listDir(sub, path, depth + 1, budget) });
      } finally {
        await sub.close();
      }
    } else {
      entries.push({ name: d.name, path, type: 'file' });
    }
  }
  entries.sort((a, b) => (a.type === b.type ? a.name.localeCompare(b.name) : a.type === 'dir' ? -1 : 1));
  return entries;
}

/** Every file path of a tree, depth first. */
export function flattenFiles(entries: TreeEntry[]): string[] {
  const out: string[] = [];
  for (const e of entries) {
    if (e.type === 'file') out.push(e.path);
    else if (e.children) out.push(...flattenFiles(e.children));
  }
  return out;
}
