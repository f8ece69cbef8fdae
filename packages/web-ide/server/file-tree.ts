import { readdir } from 'node:fs/promises';
import { join } from 'node:path';
import type { TreeEntry } from './api-types.js';
import { isAtomicTempFile } from './atomic-write.js';

const SKIPPED = new Set(['node_modules', '.git', '.vite']);

/** Lists a folder recursively: folders first, then files, both sorted by name. */
export async function listTree(absDir: string, relDir = ''): Promise<TreeEntry[]> {
  const dirents = await readdir(absDir, { withFileTypes: true });
  const entries: TreeEntry[] = [];
  for (const d of dirents) {
    if (SKIPPED.has(d.name) || isAtomicTempFile(d.name)) continue;
    const path = relDir ? `${relDir}/${d.name}` : d.name;
    if (d.isDirectory()) {
      entries.push({ name: d.name, path, type: 'dir', children: await listTree(join(absDir, d.name), path) });
    } else if (d.isFile()) {
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
