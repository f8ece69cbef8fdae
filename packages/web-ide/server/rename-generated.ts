import { readdir, readFile, rename, lstat } from 'node:fs/promises';
import { join } from 'node:path';
import { writeFileAtomic } from './atomic-write.js';

const MARKER = /(\/\*PROTECTED REGION ID\()([^)]*)(\)(?: ENABLED)? START\*\/)/g;
const ENTITY_NAME = /^[A-Za-z][A-Za-z0-9_]*$/;

export interface RenameGeneratedReport {
  movedPaths: Array<{ from: string; to: string }>;
  rewrittenFiles: string[];
  regionIds: Array<{ file: string; from: string; to: string }>;
}

/** Rewrites one protected-region ID when the entity name is one of its `_`/`.`-separated parts. */
export function renameRegionId(id: string, from: string, to: string): string {
  return id
    .split(/([_.])/)
    .map((part) => (part === from ? to : part))
    .join('');
}

/** File or folder names that carry an entity name in the generated tree (SPEC §3). */
export function renameGeneratedName(name: string, from: string, to: string): string {
  const patterns: Array<[string, string]> = [
    [`${from}_mod`, `${to}_mod`],
    [`control${from}.c`, `control${to}.c`],
    [`makecontrol${from}`, `makecontrol${to}`],
    [`Shared${from}.h`, `Shared${to}.h`],
    [`SharedFunction${from}.h`, `SharedFunction${to}.h`],
  ];
  for (const [a, b] of patterns) if (name === a) return b;
  return name;
}

/**
 * Carries a renamed entity (module, supervisor, datatype or function) over in an existing
 * generated tree: renames its files/folders and the protected-region IDs that name it, so that
 * the next generation finds the user code under the new IDs and nothing becomes an orphan.
 */
export async function renameInGeneratedTree(srcGen: string, from: string, to: string): Promise<RenameGeneratedReport> {
  if (!ENTITY_NAME.test(from) || !ENTITY_NAME.test(to)) throw new Error(`invalid entity name: ${from} -> ${to}`);
  const report: RenameGeneratedReport = { movedPaths: [], rewrittenFiles: [], regionIds: [] };
  if (!(await lstat(srcGen).catch(() => undefined))?.isDirectory()) return report;
  await walk(srcGen, '', from, to, report);
  return report;
}

async function walk(abs: string, rel: string, from: string, to: string, report: RenameGeneratedReport): Promise<void> {
  const entries = await readdir(abs, { withFileTypes: true });
  for (const e of entries) {
    const newName = renameGeneratedName(e.name, from, to);
    let childAbs = join(abs, e.name);
    let childRel = rel ? `${rel}/${e.name}` : e.name;
    if (newName !== e.name) {
      const target = join(abs, newName);
      if (await lstat(target).catch(() => undefined)) throw new Error(`cannot carry ${childRel} over: ${newName} already exists`);
      await rename(childAbs, target);
      const newRel = rel ? `${rel}/${newName}` : newName;
      report.movedPaths.push({ from: childRel, to: newRel });
      childAbs = target;
      childRel = newRel;
    }
    if (e.isDirectory()) await walk(childAbs, childRel, from, to, report);
    else if (e.isFile()) await rewriteRegions(childAbs, childRel, from, to, report);
  }
}

async function rewriteRegions(abs: string, rel: string, from: string, to: string, report: RenameGeneratedReport): Promise<void> {
  if (!/\.(c|h)$/.test(abs)) return;
  const text = await readFile(abs, 'utf8');
  if (!text.includes('PROTECTED REGION ID(')) return;
  let changed = false;
  const next = text.replace(MARKER, (all, open: string, id: string, close: string) => {
    const renamed = renameRegionId(id, from, to);
    if (renamed === id) return all;
    changed = true;
    report.regionIds.push({ file: rel, from: id, to: renamed });
    return `${open}${renamed}${close}`;
  });
  if (changed) {
    await writeFileAtomic(abs, next);
    report.rewrittenFiles.push(rel);
  }
}
