import type { TreeEntry } from './api-types.js';
import { RENAME_JOURNAL_NAME, TREE_LOCK_NAME } from '@contract-studio/conventions';
import { isAtomicTempFile } from './atomic-write.js';
import { WorkspaceFs, type DirAt } from './workspace-fs.js';

const SKIPPED = new Set(['node_modules', '.git', '.vite', TREE_LOCK_NAME, RENAME_JOURNAL_NAME]);

/**
 * Bounds of one listing: a hostile folder (20,000 nested folders, millions of files) must not
 * exhaust the server's descriptors (one is open per level of the walk) or its memory. A folder
 * past them is listed with `truncated: true` and no content.
 */
export const TREE_MAX_DEPTH = 64;
export const TREE_MAX_ENTRIES = 50_000;

/** Folders past the entries bound still listed (empty, `truncated`) in one folder, so that the Explorer names what it does not show. */
const TRUNCATED_MARKERS = 1000;

/**
 * Lists the workspace recursively: folders first, then files, both sorted by name. Symlinks are
 * not listed, and each sub-folder is opened from its parent without following links
 * (workspace-fs.ts), so a folder swapped for a link during the walk is skipped, not followed.
 * Each folder's own files are taken before its sub-folders are walked: the entries bound is spent
 * on a project's `.contract` files before a generated tree of 40,000 files (it was spent in
 * readdir's order, and the root's own files went missing without a word). A folder that was not
 * walked is listed `truncated` (no content); the folders whose listing the bound cut short say so
 * too (`truncated`, the entries listed before it kept).
 */
export async function listTree(fs: WorkspaceFs): Promise<TreeEntry[]> {
  const budget = { entries: TREE_MAX_ENTRIES };
  return fs.withDir([], false, async (root) => (await listDir(root, '', 1, budget)).entries);
}

/**
 * Lists folder `rel` of the workspace as listTree lists the workspace (same bounds, links not
 * followed): what deleting it deletes, as the Explorer shows it.
 */
export async function listFolder(fs: WorkspaceFs, rel: string): Promise<TreeEntry[]> {
  const budget = { entries: TREE_MAX_ENTRIES };
  const parts = rel.split('/').filter(Boolean);
  return fs.withDir(parts, false, async (dir) => (await listDir(dir, parts.join('/'), parts.length + 1, budget)).entries);
}

/** Whether a listing was cut by its bounds somewhere (a folder listed `truncated`). */
export function listingCut(entries: TreeEntry[]): boolean {
  return entries.some((e) => e.type === 'dir' && (e.truncated === true || listingCut(e.children ?? [])));
}

async function listDir(dir: DirAt, relDir: string, depth: number, budget: { entries: number }): Promise<{ entries: TreeEntry[]; cut: boolean }> {
  // in name order (the listing is the same whatever order the file system gives): files first, then folders
  const dirents = (await WorkspaceFs.list(dir)).filter((d) => !SKIPPED.has(d.name) && !isAtomicTempFile(d.name) && (d.isDirectory() || d.isFile()))
    .sort((a, b) => a.name.localeCompare(b.name));
  const entries: TreeEntry[] = [];
  let cut = false;
  const pathOf = (name: string) => (relDir ? `${relDir}/${name}` : name);
  for (const d of dirents) {
    if (!d.isFile()) continue;
    if (budget.entries <= 0) {
      cut = true;
      break;
    }
    budget.entries--;
    entries.push({ name: d.name, path: pathOf(d.name), type: 'file' });
  }
  let markers = 0;
  for (const d of dirents) {
    if (!d.isDirectory()) continue;
    const path = pathOf(d.name);
    if (depth >= TREE_MAX_DEPTH || budget.entries <= 0) {
      if (budget.entries <= 0 && markers++ >= TRUNCATED_MARKERS) {
        cut = true;
        break;
      }
      entries.push({ name: d.name, path, type: 'dir', children: [], truncated: true });
      continue;
    }
    budget.entries--;
    const sub = await WorkspaceFs.openSubdir(dir, d.name);
    if (!sub) continue;
    try {
      const listed = await listDir(sub, path, depth + 1, budget);
      entries.push(listed.cut ? { name: d.name, path, type: 'dir', children: listed.entries, truncated: true } : { name: d.name, path, type: 'dir', children: listed.entries });
    } finally {
      await sub.close();
    }
  }
  entries.sort((a, b) => (a.type === b.type ? a.name.localeCompare(b.name) : a.type === 'dir' ? -1 : 1));
  return { entries, cut };
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
