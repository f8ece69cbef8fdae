/** The report's tutorial project (examples/tutorial) as inline files, and edits of its user code. */
import { cpSync, lstatSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { listFilesNoFollow } from '../util/safe-fs.js';

export const REPO = join(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', '..');
export const TUTORIAL_DIR = join(REPO, 'examples', 'tutorial');
export const MAA_MODULE = 'src-gen/generated/architecture/modules/MAA_mod/module.c';

/** .contract files and the committed src-gen sources (no build products). */
export async function tutorialFiles(): Promise<Record<string, string>> {
  return exampleFiles(TUTORIAL_DIR);
}

/** An example project's (examples/NAME, or `dir`) .contract files and committed src-gen sources. */
export async function exampleFiles(dir: string): Promise<Record<string, string>> {
  const files: Record<string, string> = {};
  const list = await listFilesNoFollow(dir, (rel, isDir) => (isDir ? !/(^|\/)(run|logs)$/.test(rel) : rel.endsWith('.contract') || rel.startsWith('src-gen/')));
  for (const rel of list) {
    const path = join(dir, rel);
    if ((lstatSync(path).mode & 0o111) !== 0 || /\.(o|a|csv)$/.test(rel)) continue;
    files[rel] = readFileSync(path, 'utf8');
  }
  return files;
}

/** Replaces the body of a protected region of a file with `code` (or puts `code` before it with `keep`). */
export function withRegion(files: Record<string, string>, file: string, regionId: string, code: string, keep = false): Record<string, string> {
  const text = files[file];
  if (text === undefined) throw new Error(`no ${file} in the project`);
  const re = new RegExp(`(/\\*PROTECTED REGION ID\\(${regionId}\\) ENABLED START\\*/)([\\s\\S]*?)(/\\*PROTECTED REGION END\\*/)`);
  if (!re.test(text)) throw new Error(`no region ${regionId} in ${file}`);
  return { ...files, [file]: text.replace(re, (_m, a: string, b: string, c: string) => `${a}\n${code}\n${keep ? b : '    '}${c}`) };
}

/**
 * A snapshot of the repository's runtime sources (without build outputs), so that a test or a
 * benchmark is not disturbed by concurrent edits of runtime/ (a changed runtime relinks everything).
 */
export function snapshotRuntime(): string {
  const dir = mkdtempSync(join(tmpdir(), 'contract-runtime-'));
  cpSync(join(REPO, 'runtime'), dir, { recursive: true, filter: (src) => !/\/runtime\/build(\/|$)/.test(src) });
  return dir;
}
